// Plots of plan kind "allan": the Allan deviation on log-log axes with its confidence interval, the
// fitted noise model σ²(τ) = Σ A_p τ^p (GJB 2426A-2004 eq. 30; IEEE Std 952-1997 Annex C) and each
// of its terms as a line of slope p/2: quantization −1, angle random walk −1/2, bias instability 0,
// rate random walk +1/2, rate ramp +1.
#include <algorithm>
#include <fmt/format.h>
#include <cmath>
#include <iterator>
#include <limits>
#include <optional>

#include "inertest/allan/noise_terms.h"
#include "inertest/core/error.h"
#include "report/figure_format.h"
#include "report/procedure_plots.h"
#include "report/result_access.h"

namespace inertest::report {
namespace {

// The estimators the allan procedure may report, the preferred one first.
constexpr const char* kEstimators[] = {"oadev", "adev", "mdev", "hdev", "ohdev", "totdev"};

struct NoiseTerm {
  int power;
  const char* label_key;
  const char* slope;
};
constexpr NoiseTerm kTerms[] = {{-2, "quantization_noise", "−1"},
                                {-1, "angle_random_walk", "−1/2"},
                                {0, "bias_instability", "0"},
                                {1, "rate_random_walk", "+1/2"},
                                {2, "rate_ramp", "+1"}};

// The estimator a result draws: the preferred one it holds.
std::pair<const nlohmann::json*, std::string> drawn_curve(const nlohmann::json& result) {
  for (const char* name : kEstimators) {
    const auto* candidate = member(result, name);
    if (candidate != nullptr && candidate->is_object() && candidate->contains("values")) return {candidate, name};
  }
  return {nullptr, ""};
}

// The y range of the measured points (bars included), so steep model terms do not stretch it.
void fit_y_range(Panel& panel) {
  double y_lo = std::numeric_limits<double>::infinity();
  double y_hi = 0.0;
  for (const Series& series : panel.series) {
    if (series.marker == Marker::none) continue;
    for (const auto* values : {&series.y, &series.y_low, &series.y_high}) {
      for (double v : *values) {
        if (v > 0.0 && std::isfinite(v)) {
          y_lo = std::min(y_lo, v);
          y_hi = std::max(y_hi, v);
        }
      }
    }
  }
  if (y_hi > 0.0) {
    const std::vector<double> ends{y_lo, y_hi};
    const Range range = auto_range(ends, AxisScale::log);
    panel.y.min = range.lo;
    panel.y.max = range.hi;
  }
}

// The fitted model over the measured τ range: coefficients in (input unit)²·s^p, rescaled to the
// curve's unit when the two differ. With `terms`, each term of the model too, as a line of its slope.
std::vector<Series> model_series(const PlotContext& context, const nlohmann::json& result, const Column& tau,
                                 const std::string& unit, bool terms) {
  const auto* coefficients = member(result, "noise") ? member(*member(result, "noise"), "fit") : nullptr;
  coefficients = coefficients ? member(*coefficients, "coefficients") : nullptr;
  if (coefficients == nullptr || !coefficients->is_array()) return {};
  const double scale = converted(1.0, result.value("input_unit", unit), unit).value_or(1.0);
  double tau_lo = std::numeric_limits<double>::infinity();
  double tau_hi = 0.0;
  for (double t : tau.values) {
    if (t > 0.0) {
      tau_lo = std::min(tau_lo, t);
      tau_hi = std::max(tau_hi, t);
    }
  }
  const std::vector<double> grid = log_spaced(tau_lo, tau_hi, 80);
  std::vector<double> total(grid.size(), 0.0);
  std::vector<Series> lines;
  const char* colours[] = {"#9467bd", "#2ca02c", "#ff7f0e", "#8c564b", "#e377c2"};
  for (const auto& term : kTerms) {
    double a = 0.0;
    for (const auto& c : *coefficients) {
      if (c.value("power", 99) == term.power && number_of(c)) a = *number_of(c);
    }
    if (!(a > 0.0)) continue;
    std::vector<double> values;
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const double variance = a * std::pow(grid[i], term.power);
      total[i] += variance;
      values.push_back(std::sqrt(variance) * scale);
    }
    if (!terms) continue;
    Series line = make_series(context.labels(term.label_key) + " (" + context.labels("ui.slope") + " " + term.slope + ")",
                              grid, values, LineStyle::dashed);
    line.color = colours[term.power + 2];
    line.line_width = 1.3;
    lines.push_back(std::move(line));
  }
  std::vector<double> model;
  for (double v : total) model.push_back(v > 0.0 ? std::sqrt(v) * scale : std::numeric_limits<double>::quiet_NaN());
  Series fit = make_series(context.labels("ui.noise_model"), grid, model);
  fit.color = "#222222";
  fit.line_width = 1.8;
  lines.push_back(std::move(fit));
  return lines;
}

// The measured curve of a result with its confidence bars, named `name`.
Series measured_series(const nlohmann::json& result, const nlohmann::json& curve, const Column& tau,
                       std::string name) {
  Series measured = make_series(std::move(name), tau.values, number_array(curve.at("values")).values, LineStyle::none,
                                Marker::circle);
  const Column lower = number_array(curve.value("lower", nlohmann::json::array()));
  const Column upper = number_array(curve.value("upper", nlohmann::json::array()));
  if (lower.values.size() == tau.values.size() && upper.values.size() == tau.values.size()) {
    measured.y_low = lower.values;
    measured.y_high = upper.values;
    const auto* level = member(result, "confidence_level");
    if (level != nullptr && level->is_number()) {
      measured.name += " (" + format_number(100.0 * level->get<double>(), 3) + " %)";
    }
  }
  return measured;
}

Panel allan_panel(const PlotContext& context, const std::string& unit) {
  Panel panel;
  panel.height = 420.0;
  panel.x = make_axis(context.labels("axis.averaging_time"), "s", AxisScale::log);
  panel.y = make_axis(context.labels("axis.allan_deviation"), pretty_unit(unit), AxisScale::log);
  panel.legend = LegendPosition::automatic;
  return panel;
}

// The fit's verdict and range: how far the fitted model can be trusted.
std::string fit_caption(const PlotContext& context, const nlohmann::json& result) {
  const auto* fit = member(result, "noise") ? member(*member(result, "noise"), "fit") : nullptr;
  const auto* range = fit ? member(*fit, "fit_range") : nullptr;
  const auto* verdict = fit ? member(*fit, "verdict") : nullptr;
  const auto* chi_squared = fit ? member(*fit, "reduced_chi_squared") : nullptr;
  if (range == nullptr || verdict == nullptr || !verdict->is_string() || chi_squared == nullptr ||
      !chi_squared->is_number()) {
    return "";
  }
  return fmt::format("{}: {} ({} {}), τ {}–{} s ({}: {})", context.labels("ui.noise_fit"), verdict->get<std::string>(),
                     context.labels("ui.reduced_chi_squared"), format_number(chi_squared->get<double>(), 3),
                     format_number(range->value("tau_min_s", 0.0), 4), format_number(range->value("tau_max_s", 0.0), 4),
                     range->value("chosen_by", ""), range->value("reason", ""));
}

const std::string kCaption = " — GJB 2426A-2004 5.12.5.4.2, eqs. (25)-(31); IEEE Std 952-1997 Annex C";

// The amplitude spectral density of a result with a PSD (its band means, IEEE Std 952-1997 Annex C),
// in `colour`, converted to the panel's unit; empty without one. Periodic components go to `peaks`.
std::optional<Series> asd_series(const PlotContext& context, const nlohmann::json& result, const std::string& name,
                                 const std::string& panel_unit, std::string& peaks) {
  const auto* psd = member(result, "psd");
  if (psd == nullptr || !psd->is_object()) return std::nullopt;
  const Column frequency = number_array(psd->value("band_frequency_hz", nlohmann::json::array()));
  const auto* asd = member(*psd, "amplitude_spectral_density");
  if (asd == nullptr || frequency.empty()) return std::nullopt;
  Column values = number_array(asd->value("values", nlohmann::json::array()));
  const std::optional<double> scale = converted(1.0, asd->value("unit", ""), panel_unit);
  if (!scale || values.values.size() != frequency.values.size()) return std::nullopt;
  for (double& v : values.values) v *= *scale;
  for (const auto& peak : psd->value("peaks", nlohmann::json::array())) {
    // Each figure as value ± uncertainty and unit, as the report's tables write it (GUM 7.2.6).
    const auto* f = member(peak, "frequency");
    const auto* a = member(peak, "amplitude");
    if (f == nullptr || a == nullptr || !is_figure(*f) || !is_figure(*a)) continue;
    peaks += fmt::format("{}{}: {} {}, {}", peaks.empty() ? "" : "; ", name, context.labels("ui.periodic_component"),
                         figure_text(*f, context.labels), figure_text(*a, context.labels));
  }
  return make_series(name, frequency.values, values.values);
}

// One panel of amplitude spectral densities, one line per (name, result) that has a PSD.
std::optional<ReportPlot> asd_plot(const PlotContext& context,
                                   const std::vector<std::pair<std::string, const nlohmann::json*>>& results,
                                   const std::string& title) {
  const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  Panel panel;
  panel.height = 360.0;
  std::string unit;
  std::string peaks;
  std::size_t index = 0;
  for (const auto& [name, result] : results) {
    const auto* psd = member(*result, "psd");
    const auto* asd = psd ? member(*psd, "amplitude_spectral_density") : nullptr;
    if (asd == nullptr) continue;
    if (unit.empty()) unit = asd->value("unit", "");
    std::optional<Series> line = asd_series(context, *result, name, unit, peaks);
    if (!line) continue;
    line->color = colours[index++ % std::size(colours)];
    panel.series.push_back(std::move(*line));
  }
  if (panel.series.empty()) return std::nullopt;
  panel.x = make_axis(context.labels("axis.frequency"), "Hz", AxisScale::log);
  panel.y = make_axis(context.labels("axis.amplitude_spectral_density"), pretty_unit(unit), AxisScale::log);
  panel.legend = LegendPosition::automatic;
  ReportPlot plot;
  plot.caption = title + context.labels("axis.amplitude_spectral_density") +
                 " — Welch; IEEE Std 952-1997 Annex C (band means)" + (peaks.empty() ? "" : ". " + peaks);
  plot.plot.panels.push_back(std::move(panel));
  return plot;
}

// A record of several channels (issue 19): one figure per sensor (gyro, accelerometer, other),
// every axis of it as one curve with its fitted model in the same colour.
std::vector<ReportPlot> channel_plots(const PlotContext& context, const nlohmann::json& channels) {
  constexpr SensorKind kSensors[] = {SensorKind::kGyro, SensorKind::kAccelerometer, SensorKind::kOther};
  const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  std::vector<ReportPlot> plots;
  for (const SensorKind sensor : kSensors) {
    std::optional<Panel> panel;
    std::string panel_unit;
    std::string captions;
    std::size_t axis = 0;
    std::vector<std::pair<std::string, const nlohmann::json*>> drawn;
    for (const auto& [name, result] : channels.items()) {
      const std::string input_unit = result.value("input_unit", "");
      SensorKind kind = SensorKind::kOther;
      try {
        kind = sensor_kind_of(input_unit);
      } catch (const Error&) {
      }
      const auto [curve, estimator] = drawn_curve(result);
      const Column tau = number_array(result.value("tau", nlohmann::json::array()));
      if (kind != sensor || curve == nullptr || tau.empty()) continue;
      const std::string unit = curve->value("unit", input_unit);
      if (!panel) {
        panel = allan_panel(context, unit);
        panel_unit = unit;
      }
      // Axes of one sensor in different units are drawn in the first one's.
      const std::optional<double> scale = converted(1.0, unit, panel_unit);
      if (!scale) continue;
      const std::string colour = colours[axis++ % std::size(colours)];
      drawn.emplace_back(name, &result);
      Series measured = measured_series(result, *curve, tau, name + " " + estimator);
      for (auto* values : {&measured.y, &measured.y_low, &measured.y_high}) {
        for (double& v : *values) v *= *scale;
      }
      measured.color = colour;
      panel->series.push_back(std::move(measured));
      for (Series& line : model_series(context, result, tau, panel_unit, false)) {
        line.name = name + " " + context.labels("ui.noise_model");
        line.color = colour;
        line.line_width = 1.2;
        panel->series.push_back(std::move(line));
      }
      const std::string fit = fit_caption(context, result);
      if (!fit.empty()) captions += fmt::format(". {}: {}", name, fit);
    }
    if (!panel) continue;
    fit_y_range(*panel);
    const std::string title =
        sensor == SensorKind::kOther
            ? ""
            : context.labels(sensor == SensorKind::kAccelerometer ? "ui.accelerometer" : "ui.gyro") + ", ";
    ReportPlot plot;
    plot.caption = title + context.labels("axis.allan_deviation") + kCaption + captions;
    plot.plot.panels.push_back(std::move(*panel));
    plots.push_back(std::move(plot));
    if (std::optional<ReportPlot> spectrum = asd_plot(context, drawn, title)) plots.push_back(std::move(*spectrum));
  }
  return plots;
}

std::vector<ReportPlot> allan_plots(const PlotContext& context) {
  const nlohmann::json& result = context.result;
  if (const auto* channels = member(result, "channels"); channels != nullptr && channels->is_object()) {
    return channel_plots(context, *channels);
  }
  const Column tau = number_array(result.value("tau", nlohmann::json::array()));
  const auto [curve, estimator] = drawn_curve(result);
  if (curve == nullptr || tau.empty()) return {};
  const std::string unit = curve->value("unit", result.value("input_unit", ""));
  Panel panel = allan_panel(context, unit);
  Series measured = measured_series(result, *curve, tau, estimator.empty() ? "" : estimator + " " + context.labels("ui.data"));
  measured.color = "#1f77b4";
  panel.series.push_back(std::move(measured));
  fit_y_range(panel);
  for (Series& line : model_series(context, result, tau, unit, true)) panel.series.push_back(std::move(line));
  ReportPlot plot;
  plot.caption = context.labels("axis.allan_deviation") + kCaption;
  if (const std::string fit = fit_caption(context, result); !fit.empty()) plot.caption += ". " + fit;
  plot.plot.panels.push_back(std::move(panel));
  std::vector<ReportPlot> plots;
  plots.push_back(std::move(plot));
  if (std::optional<ReportPlot> spectrum = asd_plot(context, {{context.labels("ui.data"), &result}}, "")) {
    plots.push_back(std::move(*spectrum));
  }
  return plots;
}

}  // namespace

void register_allan_plots();

void register_allan_plots() {
  register_plots("allan", allan_plots);
}

}  // namespace inertest::report
