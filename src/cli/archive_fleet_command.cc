// inertest archive fleet --figure PROCEDURE/FIGURE [--since DATE] [--db DB] [--json]
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "archive_command.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string figure;
  std::string since;
  std::string db;
  bool json = false;
};

CommandAction setup(CLI::App& archive) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = archive.add_subcommand(
      "fleet",
      "One figure across every archived instrument: each instrument's latest value, in the order of\n"
      "their first test, a Shewhart individuals / moving range control chart of them (NIST/SEMATECH\n"
      "e-Handbook 6.3.2.2; limits x̄ ± 3·MR̄/1.128; Western Electric rules 1 and 4) and the process\n"
      "capability Cp, Cpk (6.1.6) against the plans' specification limits where they exist (a max\n"
      "alone bounds |value|, as the campaign judged it: the spec is then [-max, max]).");
  command->add_option("--figure", arguments->figure, "PROCEDURE/FIGURE as named in results.json")->required();
  command->add_option("--since", arguments->since, "only tests on or after this date, YYYY-MM-DD");
  add_db_option(*command, arguments->db);
  command->add_flag("--json", arguments->json,
                    "print {\"figure\", \"unit\", \"instruments\": [...], \"control_chart\": {\"center\", \"ucl\", "
                    "\"lcl\", \"out_of_control\": [...]}, \"capability\": {\"cp\", \"cpk\"}}");
  return [arguments] {
    const auto store = open_archive_option(arguments->db);
    const auto since = arguments->since.empty() ? std::nullopt : std::optional<std::string>(arguments->since);
    const nlohmann::json json = archive::fleet_summary(store->fleet(arguments->figure, since), since);
    std::string report = fmt::format("{} ({}), {} instruments\n", json["figure"].get<std::string>(),
                                     json["unit"].get<std::string>(), json["instruments"].size());
    for (const auto& i : json["instruments"]) {
      report += fmt::format("  {:<16} {:<10} {}\n", i["instrument"].get<std::string>(), i["tested_on"].get<std::string>(),
                            i["value"].is_number() ? fmt::format("{:.10g}", i["value"].get<double>()) : "not measured");
    }
    if (const auto& chart = json["control_chart"]; !chart.is_null()) {
      report += fmt::format("  center {:.10g}, UCL {:.10g}, LCL {:.10g}\n", chart["center"].get<double>(),
                            chart["ucl"].get<double>(), chart["lcl"].get<double>());
      for (const auto& o : chart["out_of_control"]) {
        report += fmt::format("  out of control: {} ({})\n", o["instrument"].get<std::string>(), o["rule"].get<std::string>());
      }
    }
    for (const char* index : {"cp", "cpk"}) {
      if (const auto& v = json["capability"][index]; !v.is_null()) report += fmt::format("  {} {:.4g}\n", index, v.get<double>());
    }
    print_result(json, report, arguments->json);
    return 0;
  };
}

const bool registered = register_archive_command("fleet", setup);

}  // namespace
}  // namespace inertest::cli
