// inertest hand-checks --check "name=...,value=...,unit=...,min=...,max=..." ...
#include <set>
#include <string>

#include <fast_float/fast_float.h>
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/procedures/hand_checks.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::vector<std::string> checks;
  bool json = false;
};

double number_of(const std::string& text, const std::string& spec) {
  double value = 0.0;
  const auto result = fast_float::from_chars(text.data(), text.data() + text.size(), value);
  if (result.ec != std::errc() || result.ptr != text.data() + text.size()) {
    throw Error("hand-checks: '" + text + "' is not a number in --check \"" + spec + "\"");
  }
  return value;
}

// "name=Insulation resistance,value=120,unit=Mohm,min=20": key=value pairs separated by commas.
HandCheck parse_check(const std::string& spec) {
  HandCheck check;
  std::set<std::string> given;
  std::size_t begin = 0;
  while (begin <= spec.size()) {
    const std::size_t end = std::min(spec.find(',', begin), spec.size());
    const std::string pair = spec.substr(begin, end - begin);
    const std::size_t equals = pair.find('=');
    if (equals == std::string::npos) throw Error("hand-checks: expected key=value, found '" + pair + "' in --check \"" + spec + "\"");
    const std::string key = pair.substr(0, equals);
    const std::string value = pair.substr(equals + 1);
    // A key given twice kept its last value: a second unit= turned 120 Mohm into 120 kohm.
    if (!given.insert(key).second) throw Error("hand-checks: key '" + key + "' given twice in --check \"" + spec + "\"");
    if (key == "name") {
      check.name = value;
    } else if (key == "value") {
      if (value == "pass" || value == "fail") {
        check.verdict = value == "pass";
      } else if (value == "PASS" || value == "FAIL" || value == "Pass" || value == "Fail") {
        throw Error("hand-checks: value '" + value + "': a verdict is written pass or fail in --check \"" + spec + "\"");
      } else {
        check.value = number_of(value, spec);
      }
    } else if (key == "unit") {
      check.unit = value;
    } else if (key == "min") {
      check.min = number_of(value, spec);
    } else if (key == "max") {
      check.max = number_of(value, spec);
    } else {
      throw Error("hand-checks: unknown key '" + key + "' in --check \"" + spec + "\" (name, value, unit, min, max)");
    }
    begin = end + 1;
  }
  return check;
}

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "hand-checks",
      "Checks measured by hand (GJB 2426A-2004 5.2 appearance, 5.3 insulation resistance, impedance,\n"
      "dielectric strength, 5.4 power per supply): each --check gives name, value (a number, or pass/fail\n"
      "for appearance), unit, and optional min and max (max alone bounds the magnitude), as\n"
      "\"name=Insulation resistance,value=120,unit=Mohm,min=20\". Exit 0 when every check passes, 1 when one fails.\n"
      "JSON: one figure per check under its snake_case name, check_pass, checks, all_pass.");
  command->add_option("--check", arguments->checks, "one check: name=...,value=...,unit=...,min=...,max=...")->required();
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    std::vector<HandCheck> checks;
    for (const auto& spec : arguments->checks) checks.push_back(parse_check(spec));
    const HandChecksResult result = hand_checks(checks);
    print_result(result.to_json(), result.report(), arguments->json);
    return result.all_pass ? 0 : 1;
  };
}

const bool registered = register_command("hand-checks", setup);

}  // namespace
}  // namespace inertest::cli
