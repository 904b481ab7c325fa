// `inertest demo`: simulates a complete test campaign of a navigation-grade FOG in the virtual lab
// (sim/simulation.h), processes it through the public campaign API (run_campaign), and compares
// every simulated parameter a procedure measures with its true value.
//
// Writes DIR/lab/ (records, plan.toml, truth.json, simulation.toml), DIR/results.json (the
// campaign's results plus "truth_check": [{"procedure", "quantity", "true", "measured", "unit",
// "tolerance", "within", "basis"}] and "not_checked": the true parameters no plan step reports
// yet), DIR/report.txt and the HTML test report DIR/report.html (report/report.h).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "inertest/core/progress.h"
#include "inertest/report/report.h"

namespace inertest {

struct DemoOptions {
  ProgressCallback progress;
  // The simulation plan; empty: the built-in demo plan (examples/demo/simulation.toml).
  std::string simulation_plan;
  // Language and run date of DIR/report.html.
  report::ReportOptions report;
};

struct DemoSummary {
  nlohmann::json results;
  std::string report;
  std::string results_path;
  std::string report_path;
  std::string html_report_path;  // DIR/report.html
  bool all_within = false;
};

DemoSummary run_demo(const std::string& out_dir, const DemoOptions& options = {});

// The built-in demo simulation plan (TOML text).
const std::string& demo_simulation_plan();

}  // namespace inertest
