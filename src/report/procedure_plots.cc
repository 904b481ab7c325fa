#include "report/procedure_plots.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "report/result_access.h"

namespace inertest::report {
namespace {

std::map<std::string, PlotBuilder>& registry() {
  static std::map<std::string, PlotBuilder> builders;
  return builders;
}

// The builders, registered on first use by the generated list (cmake/plot_builder_list.cc.in).
const std::map<std::string, PlotBuilder>& registered_builders() {
  [[maybe_unused]] static const bool registered = (register_plot_builders(), true);
  return registry();
}

bool spans_decades(const std::vector<double>& values, double decades) {
  double lo = std::numeric_limits<double>::infinity();
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

// A plot of the curve `key`: the member `keys[0]` of each point on the abscissa, the others as
// ordinates (those sharing a unit share a panel, at most three panels). Log abscissa when it is
// positive and spans more than two decades, unless it is the time of a record (a chamber profile
// squeezed into its last decade reads wrong).
ReportPlot curve_plot(const PlotContext& context, const std::string& key, const nlohmann::json& curve,
                      const std::vector<std::string>& keys) {
  const Column x = column(curve, keys.front());
  std::map<std::string, std::vector<std::string>> by_unit;
  std::vector<std::string> unit_order;
  for (std::size_t i = 1; i < keys.size(); ++i) {
    const std::string unit = column(curve, keys[i]).unit;
    if (!by_unit.contains(unit)) unit_order.push_back(unit);
    by_unit[unit].push_back(keys[i]);
  }
  ReportPlot plot;
  plot.caption = context.spec != nullptr ? context.labels.field_of(context.spec->kind, key) : context.labels(key);
  for (std::size_t u = 0; u < unit_order.size() && u < 3; ++u) {
    Panel panel;
    panel.height = 280.0;
    panel.x = make_axis(context.labels(keys.front()), pretty_unit(x.unit),
                        !keys.front().starts_with("time") && spans_decades(x.values, 2.0) ? AxisScale::log
                                                                                          : AxisScale::linear);
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
  return plot;
}

}  // namespace

void register_plots(const std::string& kind, PlotBuilder builder) { registry()[kind] = std::move(builder); }

const PlotBuilder* find_plots(const std::string& kind) {
  const auto& builders = registered_builders();
  const auto found = builders.find(kind);
  return found == builders.end() ? nullptr : &found->second;
}

std::vector<ReportPlot> generic_plots(const PlotContext& context) {
  std::vector<ReportPlot> plots;
  if (!context.result.is_object()) return plots;
  for (const auto& [key, curve] : context.result.items()) {
    if (!curve.is_array() || curve.size() < 3 || !curve.front().is_object()) continue;
    if (curve.front().contains("name") && curve.front().contains("pass")) continue;  // a checklist, tabulated
    auto keys = numeric_members(curve.front());
    if (keys.size() < 2) continue;
    // The abscissa: the first member named like one, else the first numeric member.
    static const char* kAbscissae[] = {"rate",     "input",    "increment",   "temperature", "frequency_hz",
                                       "tau_s",    "tau",      "smoothing_s", "time",        "beta",
                                       "beta_deg", "rate_dps", "run"};
    for (const char* name : kAbscissae) {
      const auto found = std::find(keys.begin(), keys.end(), name);
      if (found != keys.end()) {
        std::rotate(keys.begin(), found, found + 1);
        break;
      }
    }
    plots.push_back(curve_plot(context, key, curve, keys));
  }
  return plots;
}

const nlohmann::json* curve_of(const PlotContext& context, const std::string& field) {
  if (context.spec != nullptr) {
    const auto& fields = context.spec->fields;
    const bool declared = std::any_of(fields.begin(), fields.end(), [&](const FieldSpec& f) {
      return f.name == field && (f.role == FieldRole::curve || f.role == FieldRole::table);
    });
    if (!declared) {
      throw Error(fmt::format("report: procedure '{}' declares no curve or table field '{}'", context.spec->kind, field));
    }
  }
  return member(context.result, field);
}

std::vector<double> log_spaced(double lo, double hi, std::size_t count) {
  std::vector<double> values;
  if (!(lo > 0.0) || !(hi > 0.0) || count < 2) return values;
  const double a = std::log10(lo);
  const double b = std::log10(hi);
  for (std::size_t i = 0; i < count; ++i) {
    values.push_back(std::pow(10.0, a + (b - a) * static_cast<double>(i) / static_cast<double>(count - 1)));
  }
  return values;
}

Series make_series(std::string name, std::vector<double> x, std::vector<double> y, LineStyle line, Marker marker) {
  Series series;
  series.name = std::move(name);
  series.x = std::move(x);
  series.y = std::move(y);
  series.line = line;
  series.marker = marker;
  return series;
}

std::optional<double> converted(double value, const std::string& from, const std::string& to) {
  if (from == to) return value;
  try {
    return convert(value, from, to);
  } catch (const Error&) {
    return std::nullopt;
  }
}

void reduce_to_envelope(std::vector<double>& x, std::vector<double>& y, std::size_t buckets) {
  const std::size_t count = std::min(x.size(), y.size());
  if (buckets == 0 || count <= 2 * buckets) return;
  std::vector<double> ex;
  std::vector<double> ey;
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t begin = b * count / buckets;
    const std::size_t end = (b + 1) * count / buckets;
    std::size_t low = begin;
    std::size_t high = begin;
    for (std::size_t i = begin; i < end; ++i) {
      if (y[i] < y[low]) low = i;
      if (y[i] > y[high]) high = i;
    }
    for (std::size_t i : {std::min(low, high), std::max(low, high)}) {
      ex.push_back(x[i]);
      ey.push_back(y[i]);
    }
  }
  x = std::move(ex);
  y = std::move(ey);
}

const nlohmann::json* limit_on(const PlotContext& context, const std::string& figure) {
  for (const auto& verdict : context.verdicts) {
    const std::string name = verdict.value("figure", "");
    if (name == figure || name == "/" + figure) return &verdict;
  }
  return nullptr;
}

std::vector<ReferenceLine> limit_lines(const PlotContext& context, const std::string& figure,
                                       ReferenceLine::Direction direction, const std::string& unit,
                                       const std::string& label) {
  std::vector<ReferenceLine> lines;
  const nlohmann::json* verdict = limit_on(context, figure);
  if (verdict == nullptr) return lines;
  const std::string limit_unit = verdict->value("unit", unit);
  for (const char* end : {"min", "max"}) {
    const auto* bound = member(*verdict, end);
    if (bound == nullptr || !bound->is_number()) continue;
    if (const auto value = converted(bound->get<double>(), limit_unit, unit)) {
      lines.push_back({direction, *value,
                       label + (std::string(end) == "min" ? " ≥ " : " ≤ ") + format_number(bound->get<double>()) + " " +
                           pretty_unit(limit_unit),
                       "#e07b00"});
    }
  }
  return lines;
}

std::vector<ReportPlot> procedure_plots(const std::string& kind, const PlotContext& context) {
  const PlotBuilder* builder = find_plots(kind);
  if (context.spec == nullptr) return builder != nullptr ? (*builder)(context) : generic_plots(context);
  std::vector<ReportPlot> plots;
  if (builder != nullptr) plots = (*builder)(context);
  for (const FieldSpec& field : context.spec->fields) {
    if (field.role != FieldRole::curve) continue;
    const bool drawn = std::any_of(plots.begin(), plots.end(), [&](const ReportPlot& p) { return p.field == field.name; });
    const nlohmann::json* curve = member(context.result, field.name);
    if (drawn || curve == nullptr || !curve->is_array() || curve->empty()) continue;
    if (field.axes.size() < 2) {
      throw Error(fmt::format("report: the curve '{}' of '{}' declares no axes", field.name, context.spec->kind));
    }
    ReportPlot plot = curve_plot(context, field.name, *curve, field.axes);
    plot.field = field.name;
    plots.push_back(std::move(plot));
  }
  return plots;
}

}  // namespace inertest::report
