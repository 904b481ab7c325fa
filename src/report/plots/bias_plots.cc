// Plots of plan kind "bias": the record smoothed over each smoothing time (the F_i of GJB
// 2426A-2004 eq. (20), whose standard deviation is the bias stability) around the bias B0 of
// eq. (19), and the normalised stability curve Bs(τ) of the random walk coefficient's
// normalisation method (5.12.5.4.1, eqs. (23)-(24)) on log-log axes with its slope −1/2 line.
#include <cmath>

#include "report/procedure_plots.h"
#include "report/result_access.h"

namespace inertest::report {
namespace {

constexpr std::size_t kEnvelopeBuckets = 700;

std::optional<ReportPlot> smoothed_record_plot(const PlotContext& context) {
  const auto* records = curve_of(context, "smoothed_record");
  if (records == nullptr || !records->is_array() || records->empty()) return std::nullopt;
  Panel panel;
  panel.height = 340.0;
  panel.x = make_axis(context.labels("axis.time"), "s");
  panel.x.min = 0.0;  // the record's time: padding the range below its start drew negative seconds
  std::string unit = "deg/h";
  const char* colours[] = {"#aec7e8", "#1f77b4", "#d62728", "#2ca02c", "#ff7f0e"};
  std::size_t index = 0;
  for (const auto& record : *records) {
    const auto* smoothing = member(record, "smoothing_s");
    const Column values = number_array(record.value("values", nlohmann::json::array()));
    if (smoothing == nullptr || !smoothing->is_number() || values.empty()) continue;
    unit = record.value("unit", unit);
    const double s = smoothing->get<double>();
    std::vector<double> time;
    for (std::size_t i = 0; i < values.values.size(); ++i) time.push_back((static_cast<double>(i) + 0.5) * s);
    std::vector<double> y = values.values;
    reduce_to_envelope(time, y, kEnvelopeBuckets);
    Series series =
        make_series(format_number(s) + " s " + context.labels("ui.smoothing"), std::move(time), std::move(y),
                    LineStyle::solid, values.values.size() <= 60 ? Marker::circle : Marker::none);
    series.color = colours[std::min(index++, std::size(colours) - 1)];
    series.line_width = index == 1 ? 1.0 : 1.6;
    panel.series.push_back(std::move(series));
  }
  if (panel.series.empty()) return std::nullopt;
  panel.y = make_axis(context.labels("bias"), pretty_unit(unit));
  if (const auto* bias = member(context.result, "bias"); bias != nullptr && number_of(*bias)) {
    panel.references.push_back({ReferenceLine::Direction::horizontal, *number_of(*bias),
                                "B0 = " + format_number(*number_of(*bias), 5) + " " + pretty_unit(unit_of(*bias)),
                                "#444444"});
  }
  ReportPlot plot;
  plot.field = "smoothed_record";
  plot.caption = context.labels("bias_stability") + " — GJB 2426A-2004 5.12.1-5.12.2, eqs. (19)-(20)";
  plot.plot.panels.push_back(std::move(panel));
  return plot;
}

std::optional<ReportPlot> normalised_stability_plot(const PlotContext& context) {
  const auto* curve = curve_of(context, "normalised_stability_curve");
  if (curve == nullptr || !curve->is_array() || curve->size() < 2) return std::nullopt;
  const Column tau = column(*curve, "tau_s");
  const Column stability = column(*curve, "value");
  std::string unit = "deg/h";
  if (!curve->empty()) unit = curve->front().value("unit", unit);
  Panel panel;
  panel.height = 360.0;
  panel.x = make_axis(context.labels("axis.averaging_time"), "s", AxisScale::log);
  panel.y = make_axis("Bs(τ)", pretty_unit(unit), AxisScale::log);
  panel.series.push_back(make_series("Bs(τ)", tau.values, stability.values, LineStyle::solid, Marker::circle));
  // The slope −1/2 line through NER = Bs(1 s): the white-noise behaviour eq. (24) assumes.
  if (const auto* ner = member(context.result, "noise_equivalent_rate"); ner != nullptr && number_of(*ner)) {
    std::vector<double> x;
    std::vector<double> y;
    for (double t : tau.values) {
      if (t > 0.0) {
        x.push_back(t);
        y.push_back(*number_of(*ner) / std::sqrt(t));
      }
    }
    Series line = make_series("NER·τ^−1/2 (" + context.labels("ui.slope_half") + ")", std::move(x), std::move(y),
                              LineStyle::dashed);
    line.color = "#2ca02c";
    panel.series.push_back(std::move(line));
  }
  ReportPlot plot;
  plot.field = "normalised_stability_curve";
  plot.caption = context.labels("random_walk_coefficient") + " — GJB 2426A-2004 5.12.5.4.1, eqs. (23)-(24)";
  plot.plot.panels.push_back(std::move(panel));
  return plot;
}

std::vector<ReportPlot> bias_plots(const PlotContext& context) {
  std::vector<ReportPlot> plots;
  if (auto plot = smoothed_record_plot(context)) plots.push_back(std::move(*plot));
  if (auto plot = normalised_stability_plot(context)) plots.push_back(std::move(*plot));
  return plots;
}

}  // namespace

void register_bias_plots();

void register_bias_plots() { register_plots("bias", bias_plots); }

}  // namespace inertest::report
