#include "inertest/procedures/hand_checks.h"

#include <cctype>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <set>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/core/utf8.h"

namespace inertest {
namespace {

// Keys that the result itself uses; a check may not take them.
const std::set<std::string> kReservedKeys = {"procedure", "clause", "checks", "check_pass", "all_pass"};

}  // namespace

std::string snake_case_key(const std::string& name) {
  std::string key;
  bool separator = false;
  std::size_t size = 0;
  for (std::size_t at = 0; at < name.size(); at += size) {
    const char32_t c = code_point_at(name, at, size);
    // Letters of any script are kept as they are (a GJB lab names its checks 绝缘电阻); punctuation
    // and blanks beyond ASCII separate, as ASCII's do (（壳体） is _壳体, a no-break space a space).
    const bool letter = c < 0x80 ? std::isalnum(static_cast<int>(c)) != 0 : !is_unicode_punctuation_or_blank(c);
    if (!letter) {
      separator = true;
      continue;
    }
    if (separator && !key.empty()) key += '_';
    key += c < 0x80 ? std::string(1, static_cast<char>(std::tolower(static_cast<int>(c)))) : name.substr(at, size);
    separator = false;
  }
  return key;
}

HandChecksResult hand_checks(std::span<const HandCheck> checks) {
  if (checks.empty()) throw Error("hand checks: no checks given");
  HandChecksResult result;
  std::set<std::string> keys;
  for (const auto& check : checks) {
    const std::string key = snake_case_key(check.name);
    if (key.empty()) throw Error(fmt::format("hand checks: the check '{}' has no usable name", check.name));
    if (kReservedKeys.contains(key)) throw Error(fmt::format("hand checks: the name '{}' is reserved", check.name));
    if (!keys.insert(key).second) {
      throw Error(fmt::format("hand checks: two checks share the key '{}' ('{}')", key, check.name));
    }
    if (check.value.has_value() == check.verdict.has_value()) {
      throw Error(fmt::format("hand checks: '{}' needs either a measured value or a pass/fail verdict", check.name));
    }
    if (check.verdict && (check.min || check.max)) {
      throw Error(fmt::format("hand checks: '{}' is a pass/fail verdict and takes no min or max", check.name));
    }
    if (check.value && !std::isfinite(*check.value)) {
      throw Error(fmt::format("hand checks: the value of '{}' is not a finite number", check.name));
    }
    // A nan bound failed every value (a FAIL, exit 1, for a mistyped limit), an infinite one passed it.
    for (const auto& [bound, word] : {std::pair{check.min, "min"}, std::pair{check.max, "max"}}) {
      if (bound && !std::isfinite(*bound)) {
        throw Error(fmt::format("hand checks: the {} of '{}' is not a finite number", word, check.name));
      }
    }
    if (check.max && !check.min && *check.max < 0.0) {
      throw Error(fmt::format("hand checks: '{}' has max {} alone, which bounds the magnitude and cannot be negative "
                              "(a signed range takes min too)",
                              check.name, *check.max));
    }
    if (check.min && check.max && *check.min > *check.max) {
      throw Error(fmt::format("hand checks: '{}' has min {} above max {}", check.name, *check.min, *check.max));
    }
    try {
      Unit::parse(check.unit);
    } catch (const Error& e) {
      throw Error(fmt::format("hand checks: '{}': {}", check.name, e.message()));
    }
    HandCheckResult entry;
    entry.key = key;
    entry.check = check;
    if (check.verdict) {
      entry.figure = {*check.verdict ? 1.0 : 0.0, "1", std::nullopt};
      entry.pass = *check.verdict;
    } else {
      entry.figure = {*check.value, check.unit, std::nullopt};
      // A max alone bounds the magnitude, as a plan's limit does (the campaign judges these bounds
      // as its limits: the two verdicts are one).
      const double judged = check.max && !check.min ? std::abs(*check.value) : *check.value;
      entry.pass = (!check.min || judged >= *check.min) && (!check.max || judged <= *check.max);
    }
    result.all_pass = result.all_pass && entry.pass;
    result.checks.push_back(std::move(entry));
  }
  return result;
}

nlohmann::json HandChecksResult::to_json() const {
  nlohmann::json json = {{"procedure", "hand_checks"}, {"clause", "GJB 2426A-2004 5.2-5.4"}};
  nlohmann::json flags = nlohmann::json::object();
  nlohmann::json table = nlohmann::json::array();
  for (const auto& c : checks) {
    json[c.key] = c.figure;
    flags[c.key] = c.pass;
    nlohmann::json row = {{"key", c.key}, {"name", c.check.name}, {"pass", c.pass}};
    if (c.check.verdict) {
      row["value"] = *c.check.verdict ? "pass" : "fail";
    } else {
      row["value"] = *c.check.value;
      row["unit"] = c.check.unit;
    }
    if (c.check.min) row["min"] = *c.check.min;
    if (c.check.max) row["max"] = *c.check.max;
    table.push_back(std::move(row));
  }
  json["check_pass"] = flags;
  json["checks"] = table;
  json["all_pass"] = all_pass;
  return json;
}

std::string HandChecksResult::report() const {
  std::string text = "Checks measured by hand (GJB 2426A-2004 5.2-5.4)\n";
  for (const auto& c : checks) {
    const std::string value = c.check.verdict ? std::string(*c.check.verdict ? "pass" : "fail")
                                              : fmt::format("{:.6g} {}", *c.check.value, c.check.unit);
    std::string limits;
    if (c.check.min) limits += fmt::format(" min {:g}", *c.check.min);
    if (c.check.max) limits += fmt::format(" max {:g}", *c.check.max);
    text += fmt::format("  {:<5} {:<40} {}{}\n", c.pass ? "PASS" : "FAIL", c.check.name, value, limits);
  }
  return text;
}

}  // namespace inertest
