// The plots of each procedure's section. Each plan kind registers a builder from its own file
// (src/report/plots/<kind>_plots.cc), so adding a procedure's plots touches no shared file.
// A kind without a builder gets generic plots of the curves in its result.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inertest/core/procedure_spec.h"
#include "inertest/report/svg_plot.h"
#include "report/labels.h"

namespace inertest::report {

struct ReportPlot {
  std::string caption;  // what the plot shows, with the clause and equation it illustrates
  Plot plot;
  std::string field;  // the declared curve field it draws (FieldRole::curve), "" for another plot
};

struct PlotContext {
  const nlohmann::json& result;  // the procedure's to_json()
  const Labels& labels;
  const nlohmann::json& verdicts;  // the campaign's verdicts on this procedure (array)
  const ProcedureSpec* spec;       // the procedure's declaration, null for a kind not declared yet
};

using PlotBuilder = std::function<std::vector<ReportPlot>(const PlotContext&)>;

// Registers the builder for a plan kind: call from `void register_<file>()` of
// src/report/plots/<file>.cc, which the generated list register_plot_builders() calls (CMake
// lists the files: no static initialiser, and a misnamed function fails to link).
void register_plots(const std::string& kind, PlotBuilder builder);
void register_plot_builders();
const PlotBuilder* find_plots(const std::string& kind);

// Plots for a kind without a builder: every array of at least three objects in the result is a
// curve, its first numeric member the abscissa and its other members the ordinates (one panel
// per unit). Log abscissa when it is positive and spans more than two decades.
std::vector<ReportPlot> generic_plots(const PlotContext& context);

// The curve or table `field` of the result that a builder plots (null when the result has none).
// For a declared procedure the field must be declared with FieldRole::curve or FieldRole::table,
// else an Error: a renamed key fails loudly instead of making its plot vanish.
const nlohmann::json* curve_of(const PlotContext& context, const std::string& field);

// Helpers for builders.
// count values from lo to hi evenly spaced in log10 (lo, hi > 0; count >= 2).
std::vector<double> log_spaced(double lo, double hi, std::size_t count);
// A series with a name, data and style.
Series make_series(std::string name, std::vector<double> x, std::vector<double> y, LineStyle line = LineStyle::solid,
                   Marker marker = Marker::none);
// The value converted between units, or nothing when either unit is unknown or they differ in kind.
std::optional<double> converted(double value, const std::string& from, const std::string& to);
// A long series reduced to its envelope: the minimum and the maximum of each of `buckets` runs of
// consecutive points, in order, so a dense noisy record draws as its band.
void reduce_to_envelope(std::vector<double>& x, std::vector<double>& y, std::size_t buckets);

// The plan's specification limit on a figure of this procedure (a verdict of the campaign), if any.
const nlohmann::json* limit_on(const PlotContext& context, const std::string& figure);
// Reference lines at a limit's min and max, converted into `unit` (none when it does not convert).
std::vector<ReferenceLine> limit_lines(const PlotContext& context, const std::string& figure,
                                       ReferenceLine::Direction direction, const std::string& unit,
                                       const std::string& label);

// The plots of one procedure. A declared procedure: its builder's, then a plot of each declared
// curve that no plot of the builder draws (FieldSpec::axes). Otherwise its builder's, else the
// generic ones.
std::vector<ReportPlot> procedure_plots(const std::string& kind, const PlotContext& context);

}  // namespace inertest::report
