// Plots of plan kinds "gyro_misalignment" and "accelerometer_misalignment" (the misalignment
// paper, core/citations.h): the least-squares residual at each test position (α, β), and the
// separated error angles with their 1σ bars at each table rate (gyro) or in each run
// (accelerometer), the combined solution dashed.
#include <cmath>
#include <map>
#include <span>

#include "report/procedure_plots.h"
#include "report/result_access.h"

namespace inertest::report {
namespace {

constexpr const char* kGyroAngles[] = {"delta_theta_y0", "delta_theta_x0", "delta_theta_y1",
                                       "delta_theta_y2", "delta_theta_z2", "misalignment"};
constexpr const char* kAccelerometerAngles[] = {"delta_theta_y2", "delta_theta_z2", "misalignment"};

// The residual at each position: β along x, one series per α, one marker shape per table rate.
std::optional<ReportPlot> position_plot(const PlotContext& context) {
  const auto* residuals = curve_of(context, "residuals");
  if (residuals == nullptr || !residuals->is_array() || residuals->empty()) return std::nullopt;
  const Column alpha = column(*residuals, "alpha_deg");
  const Column beta = column(*residuals, "beta_deg");
  const Column residual = column(*residuals, "residual");
  std::map<double, Series> by_alpha;
  for (std::size_t i = 0; i < residual.values.size(); ++i) {
    Series& series = by_alpha[alpha.values[i]];
    series.name = "α = " + format_number(alpha.values[i]) + "°";
    series.line = LineStyle::none;
    series.marker = Marker::circle;
    series.x.push_back(beta.values[i]);
    series.y.push_back(residual.values[i]);
  }
  Panel panel;
  panel.height = 300.0;
  panel.x = make_axis("β", "°");
  panel.x.min = -30.0;
  panel.x.max = 300.0;
  panel.x.ticks = {0.0, 90.0, 180.0, 270.0};
  panel.y = make_axis(context.labels("axis.residual"), pretty_unit(residual.unit));
  panel.y.include_zero = true;
  const Marker shapes[] = {Marker::circle, Marker::square, Marker::triangle, Marker::diamond};
  std::size_t shape = 0;
  for (auto& [a, series] : by_alpha) {
    series.marker = shapes[shape++ % std::size(shapes)];
    panel.series.push_back(std::move(series));
  }
  panel.references.push_back({ReferenceLine::Direction::horizontal, 0.0, "", "#999999"});
  ReportPlot plot;
  plot.field = "residuals";
  plot.caption = context.labels("ui.positions") + " (α, β) — " + context.labels("axis.residual");
  plot.plot.panels.push_back(std::move(panel));
  return plot;
}

// The angles of each sub-solution (per rate or per run) against its abscissa, with 1σ bars.
std::optional<ReportPlot> angles_plot(const PlotContext& context, const char* table, const char* abscissa,
                                      const Axis& x_axis, std::span<const char* const> angles) {
  const auto* rows = curve_of(context, table);
  if (rows == nullptr || !rows->is_array() || rows->empty()) return std::nullopt;
  const Column x = column(*rows, abscissa);
  Panel panel;
  panel.height = 340.0;
  panel.x = x_axis;
  std::string unit;
  const Marker shapes[] = {Marker::circle, Marker::square, Marker::triangle, Marker::diamond};
  std::size_t index = 0;
  for (const char* angle : angles) {
    const Column values = column(*rows, angle);
    if (values.empty()) continue;
    if (unit.empty()) unit = values.unit;
    Series series = make_series(context.labels(angle), x.values, values.values, LineStyle::solid,
                                shapes[index++ % std::size(shapes)]);
    for (std::size_t i = 0; i < values.values.size(); ++i) {
      const double u = std::isnan(values.uncertainties[i]) ? 0.0 : values.uncertainties[i];
      series.y_low.push_back(values.values[i] - u);
      series.y_high.push_back(values.values[i] + u);
    }
    panel.series.push_back(std::move(series));
  }
  if (panel.series.empty()) return std::nullopt;
  panel.y = make_axis(context.labels("axis.angle"), pretty_unit(unit));
  panel.y.include_zero = true;
  panel.legend = LegendPosition::automatic;
  ReportPlot plot;
  plot.field = table;
  plot.caption = context.labels("misalignment");
  plot.plot.panels.push_back(std::move(panel));
  return plot;
}

std::vector<ReportPlot> gyro_plots(const PlotContext& context) {
  std::vector<ReportPlot> plots;
  if (auto plot = position_plot(context)) plots.push_back(std::move(*plot));
  Axis rate = make_axis(context.labels("axis.rate"), "°/s");
  if (auto plot = angles_plot(context, "by_rate", "rate_dps", rate, kGyroAngles)) {
    plot->caption = context.labels("misalignment") + " — " + context.labels("axis.rate");
    plots.push_back(std::move(*plot));
  }
  return plots;
}

std::vector<ReportPlot> accelerometer_plots(const PlotContext& context) {
  std::vector<ReportPlot> plots;
  Axis run = make_axis(context.labels("ui.run"), "");
  if (auto plot = angles_plot(context, "by_run", "run", run, kAccelerometerAngles)) {
    plot->caption = context.labels("misalignment") + " — " + context.labels("ui.run");
    plots.push_back(std::move(*plot));
  }
  return plots;
}

}  // namespace

void register_misalignment_plots();

void register_misalignment_plots() {
  register_plots("gyro_misalignment", gyro_plots);
  register_plots("accelerometer_misalignment", accelerometer_plots);
}

}  // namespace inertest::report
