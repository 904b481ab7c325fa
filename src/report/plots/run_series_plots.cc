// Plots of the procedures that repeat a measurement: the bias (GJB 2426A-2004 5.12.3, eq. 21) and
// the scale factor (5.8.4, eq. 12) of each run around their mean, and the scale factor
// nonlinearity of each tested input range against the maximum input rate's requirement (5.9).
#include "report/procedure_plots.h"
#include "report/result_access.h"

namespace inertest::report {
namespace {

// The declared procedure's `runs_key` table around its `mean_key` figure.
std::vector<ReportPlot> runs_plot(const PlotContext& context, const char* runs_key, const char* mean_key) {
  const std::string& kind = context.spec->kind;
  const auto* runs = curve_of(context, runs_key);
  if (runs == nullptr || !runs->is_array() || runs->empty()) return {};
  const Column values = number_array(*runs);
  std::vector<double> run_number;
  for (std::size_t i = 0; i < values.values.size(); ++i) run_number.push_back(static_cast<double>(i + 1));
  Panel panel;
  panel.height = 300.0;
  panel.x = make_axis(context.labels("ui.run"), "");
  panel.x.min = 0.5;
  panel.x.max = static_cast<double>(values.values.size()) + 0.5;
  panel.y = make_axis(context.labels.field_of(kind, runs_key), pretty_unit(values.unit));
  panel.series.push_back(make_series("", run_number, values.values, LineStyle::none, Marker::circle));
  if (const auto* mean = member(context.result, mean_key); mean != nullptr && number_of(*mean)) {
    panel.references.push_back(
        {ReferenceLine::Direction::horizontal, *number_of(*mean), context.labels.field_of(kind, mean_key), "#555555"});
  }
  ReportPlot plot;
  plot.field = runs_key;
  plot.caption = context.labels.title_of(kind) + " — " + context.spec->clause;
  plot.plot.panels.push_back(std::move(panel));
  return {std::move(plot)};
}

std::vector<ReportPlot> maximum_input_rate_plots(const PlotContext& context) {
  const auto* ranges = curve_of(context, "ranges");
  if (ranges == nullptr || !ranges->is_array() || ranges->empty()) return {};
  const Column rate = column(*ranges, "rate");
  const Column nonlinearity = column(*ranges, "nonlinearity");
  Series meets = make_series(context.labels("ui.pass"), {}, {}, LineStyle::none, Marker::circle);
  meets.color = "#1a7f37";
  Series fails = make_series(context.labels("ui.fail"), {}, {}, LineStyle::none, Marker::square);
  fails.color = "#c62828";
  for (std::size_t i = 0; i < ranges->size(); ++i) {
    Series& target = (*ranges)[i].value("meets_requirement", false) ? meets : fails;
    target.x.push_back(rate.values[i]);
    target.y.push_back(nonlinearity.values[i]);
  }
  Panel panel;
  panel.height = 300.0;
  panel.x = make_axis(context.labels("maximum_input_rate"), pretty_unit(rate.unit));
  panel.y = make_axis(context.labels("nonlinearity"), pretty_unit(nonlinearity.unit));
  panel.y.include_zero = true;
  if (!meets.x.empty()) panel.series.push_back(std::move(meets));
  if (!fails.x.empty()) panel.series.push_back(std::move(fails));
  if (const auto* limit = member(context.result, "nonlinearity_limit"); limit != nullptr && number_of(*limit)) {
    panel.references.push_back(
        {ReferenceLine::Direction::horizontal, *number_of(*limit), context.labels("ui.specification"), "#c62828"});
  }
  ReportPlot plot;
  plot.field = "ranges";
  plot.caption = context.labels.title_of(context.spec->kind) + " — " + context.spec->clause;
  plot.plot.panels.push_back(std::move(panel));
  return {std::move(plot)};
}

}  // namespace

void register_run_series_plots();

void register_run_series_plots() {
  register_plots("bias_repeatability", [](const PlotContext& context) {
    return runs_plot(context, "run_biases", "mean_bias");
  });
  register_plots("scale_factor_repeatability", [](const PlotContext& context) {
    return runs_plot(context, "run_scale_factors", "mean_scale_factor");
  });
  register_plots("maximum_input_rate", maximum_input_rate_plots);
}

}  // namespace inertest::report
