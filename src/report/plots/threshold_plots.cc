// Plots of plan kinds "threshold" and "resolution": the relative error of each tested input (or
// input increment) against it, per branch, with the 50 % criterion of GJB 2426A-2004 eq. (15)
// (threshold, 5.10.4) and eq. (18) (resolution, 5.11.4) and each branch's candidate marked.
#include "report/procedure_plots.h"
#include "report/result_access.h"

namespace inertest::report {
namespace {

std::vector<ReportPlot> criterion_plots(const PlotContext& context, const char* input_key, const char* kind,
                                        const char* clause) {
  const auto* branches = curve_of(context, "branches");
  if (branches == nullptr || !branches->is_array() || branches->empty()) return {};
  Panel panel;
  panel.height = 300.0;
  std::string unit;
  const Marker shapes[] = {Marker::circle, Marker::square, Marker::triangle, Marker::diamond};
  std::size_t index = 0;
  for (const auto& branch : *branches) {
    const auto* points = member(branch, "points");
    if (points == nullptr || !points->is_array() || points->empty()) continue;
    const Column input = column(*points, input_key);
    const Column error = column(*points, "relative_error");
    if (unit.empty()) unit = input.unit;
    std::vector<double> percent;
    for (double e : error.values) percent.push_back(100.0 * e);
    panel.series.push_back(make_series(branch.value("name", ""), input.values, percent, LineStyle::solid,
                                       shapes[index++ % std::size(shapes)]));
    if (const auto* candidate = member(branch, "candidate"); candidate != nullptr && number_of(*candidate)) {
      panel.references.push_back(
          {ReferenceLine::Direction::vertical, *number_of(*candidate), branch.value("name", ""), "#888888"});
    }
  }
  if (panel.series.empty()) return {};
  panel.x = make_axis(context.labels(std::string("axis.") + input_key), pretty_unit(unit));
  panel.y = make_axis(context.labels("axis.relative_error"), "%");
  panel.y.include_zero = true;
  panel.references.push_back({ReferenceLine::Direction::horizontal, 50.0, "50 %", "#c62828"});
  ReportPlot plot;
  plot.field = "branches";
  plot.caption = context.labels.title_of(kind) + " — " + clause;
  plot.plot.panels.push_back(std::move(panel));
  return {std::move(plot)};
}

}  // namespace

void register_threshold_plots();

void register_threshold_plots() {
  register_plots("threshold", [](const PlotContext& context) {
    return criterion_plots(context, "input", "threshold", "GJB 2426A-2004 5.10.4, eqs. (14)-(17)");
  });
  register_plots("resolution", [](const PlotContext& context) {
    return criterion_plots(context, "increment", "resolution", "GJB 2426A-2004 5.11.4, eq. (18)");
  });
}

}  // namespace inertest::report
