// Plots of plan kind "bandwidth": Bode magnitude and phase (GJB 2426A-2004 5.13-5.14). Magnitude
// in dB relative to the fitted K: the measured gains and the first-order model G = K/√(1 + ω²T²)
// of eq. (32)-(35), with the −3 dB line and the bandwidth Bw = 1/(2πT) (eq. 36) marked; phase: the
// measured phases and the model −atan(ωT) − ω·Td of eqs. (42)-(46).
#include <cmath>
#include <limits>
#include <numbers>

#include "inertest/core/units.h"
#include "report/procedure_plots.h"
#include "report/result_access.h"

namespace inertest::report {
namespace {

std::optional<double> figure_in(const nlohmann::json& result, const char* key, const std::string& unit) {
  const auto* node = member(result, key);
  if (node == nullptr || !is_figure(*node)) return std::nullopt;
  return converted(*number_of(*node), unit_of(*node), unit);
}

std::vector<ReportPlot> bandwidth_plots(const PlotContext& context) {
  const auto* bode = curve_of(context, "bode");
  if (bode == nullptr || !bode->is_array() || bode->size() < 2) return {};
  const Column frequency = column(*bode, "frequency_hz");
  const Column gain = column(*bode, "gain");
  const Column fitted_gain = column(*bode, "fitted_gain");
  const Column phase = column(*bode, "phase_deg");
  const Column fitted_phase = column(*bode, "fitted_phase_deg");
  const auto* dc = member(context.result, "dc_gain");
  const double k = dc != nullptr && number_of(*dc) && *number_of(*dc) != 0.0 ? std::abs(*number_of(*dc)) : 1.0;
  const auto decibels = [k](double g) {
    return g > 0.0 ? 20.0 * std::log10(g / k) : std::numeric_limits<double>::quiet_NaN();
  };

  const auto time_constant = figure_in(context.result, "time_constant", "s");
  const auto delay = figure_in(context.result, "delay", "s");
  const auto bandwidth = figure_in(context.result, "bandwidth", "Hz");
  double f_lo = std::numeric_limits<double>::infinity();
  double f_hi = 0.0;
  for (double f : frequency.values) {
    if (f > 0.0) {
      f_lo = std::min(f_lo, f);
      f_hi = std::max(f_hi, f);
    }
  }
  if (bandwidth && *bandwidth > 0.0) f_hi = std::max(f_hi, *bandwidth * 1.5);
  const std::vector<double> grid = log_spaced(f_lo, f_hi, 120);

  Panel magnitude;
  magnitude.height = 300.0;
  magnitude.title = context.labels("axis.magnitude");
  magnitude.x = make_axis(context.labels("axis.frequency"), "Hz", AxisScale::log);
  magnitude.y = make_axis(context.labels("axis.magnitude"), "dB");
  std::vector<double> measured_db;
  for (double g : gain.values) measured_db.push_back(decibels(std::abs(g)));
  magnitude.series.push_back(
      make_series(context.labels("ui.data"), frequency.values, measured_db, LineStyle::none, Marker::circle));
  std::vector<double> model_db;
  if (time_constant) {
    for (double f : grid) {
      const double wt = 2.0 * std::numbers::pi * f * *time_constant;
      model_db.push_back(-10.0 * std::log10(1.0 + wt * wt));  // 20·log10(1/√(1 + ω²T²))
    }
    magnitude.series.push_back(make_series(context.labels("ui.fit") + " K/√(1+ω²T²)", grid, model_db));
  } else if (!fitted_gain.empty()) {
    std::vector<double> fitted_db;
    for (double g : fitted_gain.values) fitted_db.push_back(decibels(std::abs(g)));
    magnitude.series.push_back(make_series(context.labels("ui.fit"), frequency.values, fitted_db));
  }
  magnitude.references.push_back({ReferenceLine::Direction::horizontal, -3.0, "−3 dB", "#c62828"});
  if (bandwidth) {
    magnitude.references.push_back(
        {ReferenceLine::Direction::vertical, *bandwidth, "Bw = " + format_number(*bandwidth, 4) + " Hz", "#c62828"});
  }
  for (auto& line : limit_lines(context, "bandwidth", ReferenceLine::Direction::vertical, "Hz",
                                context.labels("ui.specification"))) {
    magnitude.references.push_back(std::move(line));
  }
  magnitude.legend = LegendPosition::bottom_left;

  Panel phase_panel;
  phase_panel.height = 300.0;
  phase_panel.title = context.labels("axis.phase");
  phase_panel.x = make_axis(context.labels("axis.frequency"), "Hz", AxisScale::log);
  phase_panel.y = make_axis(context.labels("axis.phase"), "°");
  phase_panel.series.push_back(
      make_series(context.labels("ui.data"), frequency.values, phase.values, LineStyle::none, Marker::circle));
  if (time_constant && delay) {
    std::vector<double> model;
    for (double f : grid) {
      const double w = 2.0 * std::numbers::pi * f;
      model.push_back(-(std::atan(w * *time_constant) + w * *delay) * 180.0 / std::numbers::pi);  // eqs. (42)-(46)
    }
    phase_panel.series.push_back(make_series(context.labels("ui.fit") + " −atan(ωT) − ωTd", grid, model));
  } else if (!fitted_phase.empty()) {
    phase_panel.series.push_back(make_series(context.labels("ui.fit"), frequency.values, fitted_phase.values));
  }
  if (bandwidth) phase_panel.references.push_back({ReferenceLine::Direction::vertical, *bandwidth, "", "#c62828"});
  phase_panel.legend = LegendPosition::bottom_left;

  ReportPlot plot;
  plot.field = "bode";
  plot.caption = context.labels("bandwidth") + " — GJB 2426A-2004 5.13-5.14, eqs. (32)-(46)";
  plot.plot.panels = {std::move(magnitude), std::move(phase_panel)};
  return {std::move(plot)};
}

}  // namespace

void register_bandwidth_plots();

void register_bandwidth_plots() { register_plots("bandwidth", bandwidth_plots); }

}  // namespace inertest::report
