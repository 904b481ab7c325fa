// inertest archive fleet --figure PROCEDURE/FIGURE [--since DATE] [--db DB] [--json]
#include <algorithm>
#include <fmt/format.h>
#include <map>
#include <nlohmann/json.hpp>

#include "archive_command.h"
#include "inertest/numerics/control_chart.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string figure;
  std::string since;
  std::string db;
  bool json = false;
};

nlohmann::json optional_json(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }

CommandAction setup(CLI::App& archive) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = archive.add_subcommand(
      "fleet",
      "One figure across every archived instrument: each instrument's latest value, in the order of\n"
      "their first test, a Shewhart individuals / moving range control chart of them (NIST/SEMATECH\n"
      "e-Handbook 6.3.2.2; limits x̄ ± 3·MR̄/1.128; Western Electric rules 1 and 4) and the process\n"
      "capability Cp, Cpk (6.1.6) against the plans' specification limits where they exist.");
  command->add_option("--figure", arguments->figure, "PROCEDURE/FIGURE as named in results.json")->required();
  command->add_option("--since", arguments->since, "only tests on or after this date, YYYY-MM-DD");
  add_db_option(*command, arguments->db);
  command->add_flag("--json", arguments->json,
                    "print {\"figure\", \"unit\", \"instruments\": [...], \"control_chart\": {\"center\", \"ucl\", "
                    "\"lcl\", \"out_of_control\": [...]}, \"capability\": {\"cp\", \"cpk\"}}");
  return [arguments] {
    const auto store = open_archive_option(arguments->db);
    const archive::FleetFigure fleet = store->fleet(
        arguments->figure, arguments->since.empty() ? std::nullopt : std::optional<std::string>(arguments->since));
    // Each instrument's latest value (points come by instrument, then test date), ordered by the
    // instrument's first test: the order the batch came off the line.
    std::map<std::string, std::pair<std::string, const archive::FigurePoint*>> latest;  // id → (first test, latest)
    std::map<std::string, std::size_t> tests;
    for (const auto& p : fleet.points) {
      auto [it, inserted] = latest.try_emplace(p.instrument, p.tested_on, &p);
      if (!inserted) it->second.second = &p;
      ++tests[p.instrument];
    }
    std::vector<std::pair<std::string, const archive::FigurePoint*>> order;
    for (const auto& [id, first_and_latest] : latest) order.emplace_back(first_and_latest.first + " " + id, first_and_latest.second);
    std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<double> values;
    nlohmann::json instruments = nlohmann::json::array();
    for (const auto& [key, p] : order) {
      values.push_back(p->value);
      instruments.push_back({{"instrument", p->instrument}, {"value", p->value}, {"uncertainty", optional_json(p->uncertainty)},
                             {"tested_on", p->tested_on}, {"campaign", p->campaign}, {"tests", tests[p->instrument]}});
    }
    nlohmann::json json = {{"figure", fleet.figure},
                           {"unit", fleet.unit},
                           {"since", arguments->since.empty() ? nlohmann::json(nullptr) : nlohmann::json(arguments->since)},
                           {"instruments", instruments},
                           {"lower_limit", optional_json(fleet.lower_limit)},
                           {"upper_limit", optional_json(fleet.upper_limit)}};
    std::string report = fmt::format("{} ({}), {} instruments\n", fleet.figure, fleet.unit, values.size());
    for (const auto& i : instruments) {
      report += fmt::format("  {:<16} {:<10} {:.10g}\n", i["instrument"].get<std::string>(), i["tested_on"].get<std::string>(),
                            i["value"].get<double>());
    }
    if (values.size() >= 2) {
      const ControlChart chart = individuals_control_chart(values);
      nlohmann::json flagged = nlohmann::json::array();
      for (const auto& o : chart.out_of_control) {
        flagged.push_back({{"instrument", instruments[o.index]["instrument"]}, {"value", values[o.index]}, {"rule", o.rule}});
        report += fmt::format("  out of control: {} ({})\n", instruments[o.index]["instrument"].get<std::string>(), o.rule);
      }
      json["control_chart"] = {{"center", chart.center},  {"ucl", chart.ucl},       {"lcl", chart.lcl},
                               {"moving_range_mean", chart.moving_range_mean}, {"sigma", chart.sigma},
                               {"out_of_control", flagged}};
      report += fmt::format("  center {:.10g}, UCL {:.10g}, LCL {:.10g}\n", chart.center, chart.ucl, chart.lcl);
      if (chart.sigma > 0.0) {
        const ProcessCapability capability =
            process_capability(chart.center, chart.sigma, fleet.lower_limit, fleet.upper_limit);
        json["capability"] = {{"cp", optional_json(capability.cp)}, {"cpk", optional_json(capability.cpk)}};
        if (capability.cpk) report += fmt::format("  Cpk {:.4g}\n", *capability.cpk);
      } else {
        json["capability"] = {{"cp", nullptr}, {"cpk", nullptr}};
      }
    } else {
      json["control_chart"] = nullptr;  // one instrument: no moving range
      json["capability"] = {{"cp", nullptr}, {"cpk", nullptr}};
    }
    print_result(json, report, arguments->json);
    return 0;
  };
}

const bool registered = register_archive_command("fleet", setup);

}  // namespace
}  // namespace inertest::cli
