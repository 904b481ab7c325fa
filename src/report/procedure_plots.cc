#include "report/procedure_plots.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "report/result_access.h"

namespace inertest::report {
namespace {

std::map<std::string, PlotBuilder>& registry() {
  static std::map<std::string, PlotBuilder> builders;
  return builders;
}

bool spans_decades(const std::vector<double>& values, double decades) {
  double lo = INFINITY;
  double hi = 0.0;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    if (v <= 0.0) return false;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return hi > 0.0 && std::log10(hi / lo) > decades;
}

// The numeric members of the first element, in the element's order.
std::vector<std::string> numeric_members(const nlohmann::json& element) {
  std::vector<std::string> keys;
  for (const auto& [key, value] : element.items()) {
    if (number_of(value)) keys.push_back(key);
  }
  return keys;
}

}  // namespace

bool register_plots(const std::string& kind, PlotBuilder builder) {
  registry()[kind] = std::move(builder);
  return true;
}

const PlotBuilder* find_plots(const std::string& kind) {
  const auto found = registry().find(kind);
  return found == registry().end() ? nullptr : &found->second;
}

std::vector<ReportPlot> generic_plots(const PlotContext& context) {
  std::vector<ReportPlot> plots;
  if (!context.result.is_object()) return plots;
  for (const auto& [key, curve] : context.result.items()) {
    if (!curve.is_array() || curve.size() < 3 || !curve.front().is_object()) continue;
    const auto keys = numeric_members(curve.front());
    if (keys.size() < 2) continue;
    const Column x = column(curve, keys.front());
    std::map<std::string, std::vector<std::string>> by_unit;  // ordinates sharing a unit share a panel
    std::vector<std::string> unit_order;
    for (std::size_t i = 1; i < keys.size(); ++i) {
      const std::string unit = column(curve, keys[i]).unit;
      if (!by_unit.contains(unit)) unit_order.push_back(unit);
      by_unit[unit].push_back(keys[i]);
    }
    ReportPlot plot;
    plot.caption = context.labels(key);
    for (std::size_t u = 0; u < unit_order.size() && u < 3; ++u) {
      Panel panel;
      panel.height = 280.0;
      panel.x = make_axis(context.labels(keys.front()), pretty_unit(x.unit),
                          spans_decades(x.values, 2.0) ? AxisScale::log : AxisScale::linear);
      const auto& members = by_unit[unit_order[u]];
      panel.y = make_axis(members.size() == 1 ? context.labels(members.front()) : "", pretty_unit(unit_order[u]));
      for (const auto& name : members) {
        const Column y = column(curve, name);
        Series series;
        series.name = members.size() == 1 ? "" : context.labels(name);
        series.x = x.values;
        series.y = y.values;
        series.marker = Marker::circle;
        panel.series.push_back(std::move(series));
      }
      plot.plot.panels.push_back(std::move(panel));
    }
    plots.push_back(std::move(plot));
  }
  return plots;
}

std::vector<ReportPlot> procedure_plots(const std::string& kind, const PlotContext& context) {
  if (const auto* builder = find_plots(kind)) return (*builder)(context);
  return generic_plots(context);
}

}  // namespace inertest::report
