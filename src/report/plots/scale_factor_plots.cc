// Plots of plan kind "scale_factor": the nonlinearity curve αj against the input rate, which
// GJB 2426A-2004 5.8.2.4 asks for besides Kn (eq. 8; Kn = max |αj|, eq. 9).
#include <algorithm>
#include <numeric>

#include "report/procedure_plots.h"
#include "report/result_access.h"

namespace inertest::report {
namespace {

std::vector<ReportPlot> scale_factor_plots(const PlotContext& context) {
  std::vector<ReportPlot> plots;
  const nlohmann::json* curve = curve_of(context, "nonlinearity_curve");
  if (curve == nullptr || !curve->is_array() || curve->empty()) return plots;
  const Column rate = column(*curve, "rate");
  const Column deviation = column(*curve, "deviation");

  // Points in rate order, so the line runs from the largest negative to the largest positive rate.
  std::vector<std::size_t> order(rate.values.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return rate.values[a] < rate.values[b]; });
  Series points;
  points.marker = Marker::circle;
  for (auto i : order) {
    points.x.push_back(rate.values[i]);
    points.y.push_back(deviation.values[i]);
  }

  Panel panel;
  panel.height = 320.0;
  panel.x = make_axis(context.labels("axis.rate"), pretty_unit(rate.unit));
  panel.y = make_axis(context.labels("axis.deviation") + " αj", pretty_unit(deviation.unit));
  panel.y.include_zero = true;
  panel.series.push_back(std::move(points));
  if (const auto* kn = member(context.result, "nonlinearity"); kn != nullptr && number_of(*kn)) {
    const double value = *number_of(*kn);
    const std::string label = "±Kn = " + format_number(value, 4) + " " + pretty_unit(unit_of(*kn));
    panel.references.push_back({ReferenceLine::Direction::horizontal, value, label, "#c62828"});
    panel.references.push_back({ReferenceLine::Direction::horizontal, -value, "", "#c62828"});
  }
  panel.references.push_back({ReferenceLine::Direction::vertical, 0.0, "", "#999999"});
  // The specification on Kn = max |αj| bounds the curve on both sides.
  for (auto line : limit_lines(context, "nonlinearity", ReferenceLine::Direction::horizontal, deviation.unit,
                               context.labels("ui.specification") + " Kn")) {
    panel.references.push_back(line);
    line.value = -line.value;
    line.label.clear();
    panel.references.push_back(line);
  }

  ReportPlot plot;
  plot.field = "nonlinearity_curve";
  plot.caption = context.labels("nonlinearity_curve") + " — GJB 2426A-2004 5.8.2.4, eqs. (7)-(9)";
  plot.plot.panels.push_back(std::move(panel));
  plots.push_back(std::move(plot));
  return plots;
}

}  // namespace

void register_scale_factor_plots();

void register_scale_factor_plots() { register_plots("scale_factor", scale_factor_plots); }

}  // namespace inertest::report
