// Plots of plan kinds "bias_temperature" and "scale_factor_temperature": the bias (GJB 2426A-2004
// 5.12.4, eq. 22) and the scale factor (5.8.5, eq. 13) at each test temperature, with the room or
// reference temperature's value marked, and the sensitivity at each temperature below.
#include <algorithm>
#include <numeric>

#include "report/procedure_plots.h"
#include "report/result_access.h"

namespace inertest::report {
namespace {

struct TemperaturePlotSpec {
  const char* table;            // the result's array of runs
  const char* quantity;         // the member plotted against temperature
  const char* reference;        // the result's figure at the reference temperature (a line, under its label)
  const char* kind;             // the plan kind, whose label heads the caption
  const char* clause;           // the clause and equation the plot illustrates
};

// The rows of the table in temperature order.
std::vector<std::size_t> by_temperature(const Column& temperature) {
  std::vector<std::size_t> order(temperature.values.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return temperature.values[a] < temperature.values[b]; });
  return order;
}

std::vector<double> pick(const std::vector<double>& values, const std::vector<std::size_t>& order) {
  std::vector<double> picked;
  for (auto i : order) picked.push_back(values[i]);
  return picked;
}

std::vector<ReportPlot> temperature_plots(const PlotContext& context, const TemperaturePlotSpec& spec) {
  const auto* table = curve_of(context, spec.table);
  if (table == nullptr || !table->is_array() || table->empty()) return {};
  const Column temperature = column(*table, "temperature");
  const Column quantity = column(*table, spec.quantity);
  const Column sensitivity = column(*table, "sensitivity");
  const auto order = by_temperature(temperature);

  Panel main;
  main.height = 300.0;
  main.x = make_axis(context.labels("axis.temperature"), pretty_unit(temperature.unit));
  main.y = make_axis(context.labels(spec.quantity), pretty_unit(quantity.unit));
  main.series.push_back(
      make_series("", pick(temperature.values, order), pick(quantity.values, order), LineStyle::solid, Marker::circle));
  if (const auto* reference = member(context.result, spec.reference); reference != nullptr && number_of(*reference)) {
    main.references.push_back({ReferenceLine::Direction::horizontal, *number_of(*reference),
                               context.labels(spec.reference), "#555555"});
  }
  ReportPlot plot;
  plot.field = spec.table;
  plot.caption = context.labels.title_of(spec.kind) + " — " + spec.clause;
  plot.plot.panels.push_back(std::move(main));

  if (!sensitivity.empty() && !sensitivity.unit.empty()) {
    Panel lower;
    lower.height = 240.0;
    lower.x = make_axis(context.labels("axis.temperature"), pretty_unit(temperature.unit));
    lower.y = make_axis(context.labels("temperature_sensitivity"), pretty_unit(sensitivity.unit));
    lower.y.include_zero = true;
    Series bars = make_series("", pick(temperature.values, order), pick(sensitivity.values, order), LineStyle::dotted,
                              Marker::square);
    bars.color = "#d62728";
    lower.series.push_back(std::move(bars));
    plot.plot.panels.push_back(std::move(lower));
  }
  return {std::move(plot)};
}

}  // namespace

void register_temperature_plots();

void register_temperature_plots() {
  register_plots("bias_temperature", [](const PlotContext& context) {
    return temperature_plots(context, {"runs", "bias", "room_temperature_bias", "bias_temperature",
                                       "GJB 2426A-2004 5.12.4, eq. (22)"});
  });
  register_plots("scale_factor_temperature", [](const PlotContext& context) {
    return temperature_plots(context,
                             {"test_temperatures", "scale_factor", "reference_scale_factor", "scale_factor_temperature",
                              "GJB 2426A-2004 5.8.5, eq. (13)"});
  });
}

}  // namespace inertest::report
