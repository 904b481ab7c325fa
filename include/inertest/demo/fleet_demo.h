// `inertest demo --fleet`: a simulated production batch through the archive. Twelve gyros, each
// with its own seed and its own true scale factor and bias (three of them out of specification,
// one drifting from day to day), each tested on three days: every campaign is simulated
// (sim/simulation.h, with SimulationOptions' seed, instrument id and date), processed
// (run_campaign) with specification limits on the scale factor and the bias, and added to
// DIR/archive.sqlite; then DIR/fleet.html and DIR/history-<ID>.html are written
// (report/archive_pages.h). Campaign folders: DIR/campaigns/<ID>/<date>/.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inertest/core/progress.h"
#include "inertest/report/report.h"

namespace inertest {

struct FleetDemoOptions {
  ProgressCallback progress;
  report::ReportOptions report;  // language and run date of the pages
};

struct FleetDemoSummary {
  std::string archive_path;            // DIR/archive.sqlite
  std::vector<std::string> pages;      // fleet.html first, then one history page per instrument
  std::size_t campaigns_added = 0;     // new to the archive (a second run adds none)
  nlohmann::json fleet;                // archive::fleet_summary of each figure with limits
  // One line per figure: instruments, center, control limits, Cp, Cpk and the flagged points.
  std::string report() const;
};

FleetDemoSummary run_fleet_demo(const std::string& out_dir, const FleetDemoOptions& options = {});

}  // namespace inertest
