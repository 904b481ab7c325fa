#include "inertest/demo/demo.h"

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>
#include <fmt/format.h>

#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
#include "inertest/core/figure.h"
#include "inertest/core/units.h"
#include "inertest/io/atomic_write.h"
#include "inertest/sim/simulation.h"

namespace inertest {
namespace {

const nlohmann::json* find_result(const nlohmann::json& results, const std::string& procedure) {
  for (const auto& p : results.at("procedures")) {
    if (p.at("name") == procedure) return &p.at("result");
  }
  return nullptr;
}

// The figure at `figure`, a key or a JSON pointer; a pointer to an element of the value of a
// vector or matrix figure (".../scale_factor/value/0", ".../misalignment/value/0/1") reads as that
// element's figure: the figure's unit and the uncertainty at the same place. nullopt: none there.
std::optional<nlohmann::json> find_figure(const nlohmann::json& result, const std::string& figure) {
  if (figure.empty() || figure.front() != '/') {
    return result.contains(figure) ? std::optional<nlohmann::json>(result.at(figure)) : std::nullopt;
  }
  const nlohmann::json::json_pointer pointer(figure);
  if (!result.contains(pointer)) return std::nullopt;
  nlohmann::json::json_pointer owner = pointer;
  std::vector<std::string> place;
  while (!owner.empty() && owner.back() != "value") {
    place.insert(place.begin(), owner.back());
    owner.pop_back();
  }
  if (!result.at(pointer).is_number() || owner.empty()) return result.at(pointer);
  owner.pop_back();
  nlohmann::json element = {{"value", result.at(pointer)}, {"unit", result.at(owner).at("unit")}};
  nlohmann::json::json_pointer uncertainty = owner / "uncertainty";
  for (const std::string& index : place) uncertainty /= index;
  if (result.contains(uncertainty)) element["uncertainty"] = result.at(uncertainty);
  return element;
}

std::string report_text(const nlohmann::json& results, const std::string& campaign_report) {
  std::string text = "inertest demo: a simulated navigation-grade FOG through the virtual lab\n"
                     "==========================================================================\n\n";
  text += campaign_report;
  text += "\nTruth check (expected = true value + the predicted systematic of rig and method; tolerance from the noise)\n";
  for (const auto& c : results.at("truth_check")) {
    // A figure the analysis could not identify is checked against its upper bound.
    const std::string measured = c.at("measured").is_null()
                                     ? fmt::format("not identified, < {:.3g}", c.at("upper_bound").get<double>())
                                     : fmt::format("measured {:>13.7g}  ±{:<10.3g}", c.at("measured").get<double>(),
                                                   c.at("tolerance").get<double>());
    text += fmt::format("  {:<7} {:<26} {:<36} true {:>13.7g}  expected {:>13.7g}  {} {}\n",
                        c.at("within").get<bool>() ? "within" : "OUTSIDE", c.at("procedure").get<std::string>(),
                        c.at("quantity").get<std::string>(), c.at("true").get<double>(), c.at("expected").get<double>(),
                        measured, c.at("unit").get<std::string>());
  }
  if (!results.at("not_checked").empty()) {
    text += "\nSimulated but not yet measured (no plan step in this build reports them):\n";
    for (const auto& c : results.at("not_checked")) {
      text += fmt::format("  {:<22} {:<28} true {:.7g} {}\n", c.at("procedure").get<std::string>(),
                          c.at("quantity").get<std::string>(), c.at("true").get<double>(),
                          c.at("unit").get<std::string>());
    }
  }
  return text;
}

}  // namespace

DemoSummary run_demo(const std::string& out_dir, const DemoOptions& options) {
  const std::filesystem::path out(out_dir);
  const std::string lab_dir = (out / "lab").string();
  sim::SimulationOptions simulation;
  simulation.progress = options.progress;
  const sim::SimulationSummary lab =
      options.simulation_plan.empty()
          ? sim::simulate_text(demo_simulation_plan(), "built-in demo plan", lab_dir, simulation)
          : sim::simulate(options.simulation_plan, lab_dir, simulation);
  if (options.simulation_plan.empty()) {
    write_file_atomically((out / "lab" / "simulation.toml").string(), demo_simulation_plan());
  }

  CampaignOptions campaign;
  campaign.progress = options.progress;
  const CampaignSummary processed = run_campaign(lab.plan_path, out_dir, campaign);

  DemoSummary summary;
  summary.results = processed.results;
  nlohmann::json checks = nlohmann::json::array();
  nlohmann::json unchecked = nlohmann::json::array();
  bool all_within = true;
  for (const auto& truth : lab.truth.at("truth")) {
    const std::string procedure = truth.at("procedure");
    const nlohmann::json* result = find_result(summary.results, procedure);
    if (truth.at("figure").is_null() || result == nullptr) {
      unchecked.push_back({{"procedure", procedure}, {"quantity", truth.at("quantity")}, {"true", truth.at("true")},
                           {"unit", truth.at("unit")}});
      continue;
    }
    const std::string figure_key = truth.at("figure");
    const std::optional<nlohmann::json> node = find_figure(*result, figure_key);
    if (!node) throw Error("demo: procedure '" + procedure + "' reports no figure '" + figure_key + "'");
    const std::string unit = truth.at("unit");
    if (node->value("identified", true) == false) {
      // Not identified (e.g. a noise term the fit holds at zero): the truth must lie below the bound.
      const double bound = convert(node->at("upper_bound").get<double>(), node->at("unit").get<std::string>(), unit);
      const double expected = truth.at("expected");
      const bool within = expected <= bound;
      all_within = all_within && within;
      checks.push_back({{"procedure", procedure}, {"quantity", truth.at("quantity")}, {"true", truth.at("true")},
                        {"expected", expected}, {"measured", nullptr}, {"upper_bound", bound}, {"unit", unit},
                        {"tolerance", bound}, {"within", within},
                        {"basis", "not identified: the truth must lie below the reported upper bound"}});
      continue;
    }
    const Figure figure = node->get<Figure>();
    const double measured = convert(figure.value, figure.unit, unit);
    const double true_value = truth.at("true");
    const double expected = truth.at("expected");
    double tolerance = truth.at("tolerance");
    if (truth.contains("tolerance_sigmas")) {
      if (!figure.uncertainty) throw Error("demo: '" + procedure + "' reports '" + figure_key + "' without uncertainty");
      tolerance = truth.at("tolerance_sigmas").get<double>() * convert(*figure.uncertainty, figure.unit, unit);
    }
    const bool within = std::abs(measured - expected) <= tolerance;
    all_within = all_within && within;
    checks.push_back({{"procedure", procedure}, {"quantity", truth.at("quantity")}, {"true", true_value},
                      {"expected", expected}, {"measured", measured}, {"unit", unit}, {"tolerance", tolerance},
                      {"within", within}, {"basis", truth.at("basis")}});
  }
  summary.results["truth_check"] = checks;
  summary.results["not_checked"] = unchecked;
  summary.results["truth_check_all_within"] = all_within;
  summary.all_within = all_within;
  summary.results_path = (out / "results.json").string();
  summary.report_path = (out / "report.txt").string();
  summary.report = report_text(summary.results, report::render_text_report(summary.results, options.report));
  write_file_atomically(summary.results_path, summary.results.dump(2) + "\n");
  write_file_atomically(summary.report_path, summary.report);
  summary.html_report_path = report::write_report(summary.results, out_dir, options.report);
  return summary;
}

}  // namespace inertest
