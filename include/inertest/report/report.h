// The test report: one self-contained HTML page per campaign (inline CSS and SVG plots, no script,
// no external files or fonts) that prints cleanly to PDF. It shows the instrument, the site, the
// date, the inertest version and the plan; a summary of every figure with its unit and 1-sigma
// uncertainty and, where the plan sets specification limits (IEEE Std 952-1997 specification
// format), a PASS/FAIL column and the overall verdict; then one section per procedure with its
// method (standard clause and equations) and its plots. Labels in English or Chinese (GJB terms).
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace inertest::report {

enum class Language { english, chinese };

// "en" or "zh"; throws Error otherwise.
Language parse_language(const std::string& code);

struct ReportOptions {
  Language language = Language::english;
  // The date shown when the plan's [plan] table gives none (the run date, e.g. "2024-05-01"), and
  // the date the footer says the report was made. results.json stays free of it (deterministic).
  std::string run_date;
  // Whether each plot carries its data (report::Plot::embed_data) for the web view's script to
  // redraw it zoomed; the page looks the same without that script.
  bool embed_plot_data = false;
};

// Renders the campaign's results (the content of results.json, see campaign.h) as one HTML page.
// Tolerates procedures and keys it does not know: their figures are listed, their curves plotted
// generically. Throws Error when results lacks the campaign's top-level keys.
std::string render_report(const nlohmann::json& results, const ReportOptions& options);

// The same figures as plain text (what `inertest run` prints and the demo's report.txt holds): per
// procedure the rows of the HTML report's figure table (value ± 1-sigma uncertainty, unit), then the
// specification limits with each verdict and the overall verdict.
std::string render_text_report(const nlohmann::json& results, const ReportOptions& options);

// Renders the report and writes out_dir/report.html atomically; returns the path written.
std::string write_report(const nlohmann::json& results, const std::string& out_dir, const ReportOptions& options);

// Today's local date as YYYY-MM-DD, for ReportOptions::run_date.
std::string current_date();

}  // namespace inertest::report
