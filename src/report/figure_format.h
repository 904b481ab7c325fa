// Figures as the report writes them, in one place for its tables, its rows and its plots' captions.
#pragma once

#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "report/labels.h"

namespace inertest::report {

// A figure the analysis could not measure: {"value": null, "unit", "identified": false,
// "upper_bound"} (e.g. a noise term that the fit of GJB eq. (30) holds at zero).
bool is_unidentified_figure(const nlohmann::json& node);

// A figure the data could not give, kept at its place with the reason: {"value": null, "unit",
// "measured": false, "reason"} (e.g. a smoothing time longer than half the record).
bool is_unmeasured_figure(const nlohmann::json& node);

// A figure of one value, as format_figure takes it: is_figure, is_unidentified_figure or
// is_unmeasured_figure.
bool is_scalar_figure(const nlohmann::json& node);

// A figure of a triad (issue 18): {"value": [x, y, z] or a 3x3, "unit", "uncertainty": the same shape}.
bool is_array_figure(const nlohmann::json& node);

// Value and uncertainty to the uncertainty's second significant digit (GUM 7.2.6), else 6 digits
// (the uncertainty "" when the figure has none); an unidentified figure as "not identified (< upper
// bound)"; an unmeasured one as "not measured"; a text or yes/no figure as its text. The figure is
// is_scalar_figure.
std::pair<std::string, std::string> format_figure(const nlohmann::json& figure, const Labels& labels);

// For a figure measured but within 2 sigma of zero ({"significant": false, "upper_bound"}, e.g. a
// noise term whose coefficient the fit leaves free near zero): "not significant (< upper bound)",
// to follow its unit; "" for any other figure.
std::string significance_note(const nlohmann::json& figure, const Labels& labels);

// The figure in one piece: "1.249999 ± 0.000020 Hz" (format_figure, then the readable unit),
// "0.0101 °/s" without an uncertainty, then its significance_note after a comma.
std::string figure_text(const nlohmann::json& figure, const Labels& labels);

}  // namespace inertest::report
