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

// The fleet: an array of archive::fleet_summary JSON, one per figure, and the figures left out as
// archived in units that do not convert (archive::report_data's "not_comparable"), each named with
// why.
std::string render_fleet_page(const nlohmann::json& fleet, const ReportOptions& options,
                              const nlohmann::json& not_comparable);

// The file name of an instrument's history page: "history-<id>.html", every byte of the id but
// letters, digits, '-', '.' and '_' percent-encoded ("LAB2/FOG-001": "history-LAB2%2FFOG-001.html"),
// so that any id names one file of the directory and no two ids the same file.
std::string history_page_file_name(const std::string& instrument);

// Writes out_dir/fleet.html and out_dir/<history_page_file_name> of each instrument for
// archive::report_data's {"histories", "fleet"}: all of them or (an Error: a page that cannot be
// rendered or written) none; returns the paths written (fleet first).
std::vector<std::string> write_archive_pages(const nlohmann::json& data, const std::string& out_dir,
                                             const ReportOptions& options);

}  // namespace inertest::report
