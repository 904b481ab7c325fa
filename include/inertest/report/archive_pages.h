// The archive's report pages, in the style of the campaign report (report.h: one self-contained
// HTML page each, inline CSS and SVG, en/zh): an instrument's history (a trend plot per figure,
// with 1-sigma uncertainty bars and the plans' specification limits) and the fleet (per figure a
// control chart with its center line and control limits, the points flagged out of control, and
// the capability table). They render plain JSON (archive::report_data), so the report part needs
// no database.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/report/report.h"

namespace inertest::report {

// One instrument's history: {"instrument", "figures": [archive FigureHistory JSON]}.
std::string render_history_page(const nlohmann::json& history, const ReportOptions& options);

// The fleet: an array of archive::fleet_summary JSON, one per figure.
std::string render_fleet_page(const nlohmann::json& fleet, const ReportOptions& options);

// Writes out_dir/fleet.html and out_dir/history-<instrument>.html for archive::report_data's
// {"histories", "fleet"}, each atomically; returns the paths written (fleet first).
std::vector<std::string> write_archive_pages(const nlohmann::json& data, const std::string& out_dir,
                                             const ReportOptions& options);

}  // namespace inertest::report
