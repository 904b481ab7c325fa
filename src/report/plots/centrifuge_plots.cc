// Plots of plan kind "centrifuge" (the centrifuge paper, cited in core/citations.h): the harmonic
// amplitudes k0, k1c, k1s, k2c, k2s of eq. (11) at each platform angle β and g-level (the paper's
// Table 3), and the residuals of the least-squares fit Y = Φq + ε (eqs. 13-16) at the same points.
#include <algorithm>
#include <map>

#include "report/procedure_plots.h"
#include "report/result_access.h"

namespace inertest::report {
namespace {

Panel harmonic_panel(const nlohmann::json& runs, const char* member_name, const std::string& axis_label) {
  // Series per (harmonic, g-level): colours by harmonic, marker and line by g-level.
  std::map<std::string, std::map<double, Series>> series;
  std::vector<double> g_levels;
  std::string unit;
  for (const auto& run : runs) {
    const auto* amplitudes = member(run, member_name);
    const auto* beta = member(run, "beta");
    const auto* g = member(run, "accel_g");
    if (amplitudes == nullptr || !amplitudes->is_object() || beta == nullptr || !number_of(*beta) || g == nullptr ||
        !number_of(*g)) {
      continue;
    }
    const double level = *number_of(*g);
    if (std::find(g_levels.begin(), g_levels.end(), level) == g_levels.end()) g_levels.push_back(level);
    for (const auto& [harmonic, amplitude] : amplitudes->items()) {
      if (!number_of(amplitude)) continue;
      if (unit.empty()) unit = unit_of(amplitude);
      Series& s = series[harmonic][level];
      s.x.push_back(*number_of(*beta));
      s.y.push_back(*number_of(amplitude));
    }
  }
  const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"};
  const Marker shapes[] = {Marker::circle, Marker::square, Marker::triangle, Marker::diamond};
  Panel panel;
  panel.height = 360.0;
  panel.x = make_axis("β", "°");
  panel.x.min = -30.0;
  panel.x.max = 300.0;
  panel.x.ticks = {0.0, 90.0, 180.0, 270.0};
  panel.y = make_axis(axis_label, pretty_unit(unit));
  std::size_t h = 0;
  for (auto& [harmonic, by_level] : series) {
    for (auto& [level, s] : by_level) {
      const auto g_index =
          static_cast<std::size_t>(std::find(g_levels.begin(), g_levels.end(), level) - g_levels.begin());
      s.name = harmonic + ", " + format_number(level) + " g";
      s.color = colours[h % std::size(colours)];
      s.marker = shapes[g_index % std::size(shapes)];
      s.line = g_index == 0 ? LineStyle::solid : LineStyle::dashed;
      s.line_width = 1.2;
      panel.series.push_back(std::move(s));
    }
    ++h;
  }
  return panel;
}

std::vector<ReportPlot> centrifuge_plots(const PlotContext& context) {
  const auto* runs = curve_of(context, "runs");
  if (runs == nullptr || !runs->is_array() || runs->empty()) return {};
  std::vector<ReportPlot> plots;
  ReportPlot harmonics;
  harmonics.field = "runs";
  harmonics.caption = context.labels("axis.harmonic") + " — eq. (11), Table 3 of the centrifuge paper";
  harmonics.plot.panels.push_back(harmonic_panel(*runs, "amplitudes", context.labels("axis.harmonic")));
  ReportPlot residuals;
  residuals.field = "runs";
  residuals.caption = context.labels("axis.residual") + " — eqs. (13)-(16) of the centrifuge paper";
  residuals.plot.panels.push_back(harmonic_panel(*runs, "residuals", context.labels("axis.residual")));
  if (!harmonics.plot.panels.back().series.empty()) plots.push_back(std::move(harmonics));
  if (!residuals.plot.panels.back().series.empty()) plots.push_back(std::move(residuals));
  return plots;
}

}  // namespace

void register_centrifuge_plots();

void register_centrifuge_plots() { register_plots("centrifuge", centrifuge_plots); }

}  // namespace inertest::report
