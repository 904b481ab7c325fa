#include "report/figure_format.h"

#include <fmt/format.h>

#include <cmath>

#include "report/result_access.h"

namespace inertest::report {

using nlohmann::json;

bool is_unidentified_figure(const json& node) {
  const auto* identified = member(node, "identified");
  const auto* bound = member(node, "upper_bound");
  const auto* unit = member(node, "unit");
  return identified != nullptr && identified->is_boolean() && !identified->get<bool>() && bound != nullptr &&
         bound->is_number() && unit != nullptr && unit->is_string();
}

bool is_unmeasured_figure(const json& node) {
  const auto* value = member(node, "value");
  const auto* measured = member(node, "measured");
  const auto* unit = member(node, "unit");
  return value != nullptr && value->is_null() && measured != nullptr && measured->is_boolean() &&
         !measured->get<bool>() && unit != nullptr && unit->is_string();
}

bool is_scalar_figure(const json& node) {
  return is_figure(node) || is_unidentified_figure(node) || is_unmeasured_figure(node);
}

bool is_array_figure(const json& node) {
  const auto* value = member(node, "value");
  const auto* unit = member(node, "unit");
  return value != nullptr && value->is_array() && !value->empty() && unit != nullptr && unit->is_string();
}

std::pair<std::string, std::string> format_figure(const json& figure, const Labels& labels) {
  if (is_unidentified_figure(figure)) {
    return {labels("ui.not_identified") + " (< " + format_number(figure.at("upper_bound").get<double>(), 2) + ")", ""};
  }
  if (is_unmeasured_figure(figure)) return {labels("ui.not_measured"), ""};
  // A declared text or yes/no figure (polarity's "positive", its "as specified").
  if (figure.at("value").is_string()) return {figure.at("value").get<std::string>(), ""};
  if (figure.at("value").is_boolean()) return {labels(figure.at("value").get<bool>() ? "ui.yes" : "ui.no"), ""};
  const double value = figure.at("value").get<double>();
  const auto* u = member(figure, "uncertainty");
  if (u == nullptr || !u->is_number() || !(u->get<double>() > 0.0) || !std::isfinite(value)) {
    return {format_number(value), ""};
  }
  const double uncertainty = u->get<double>();
  const int decimals = 1 - static_cast<int>(std::floor(std::log10(uncertainty)));
  if (decimals < 0 || decimals > 9 || std::abs(value) >= 1e9) {
    return {format_number(value), format_number(uncertainty, 2)};
  }
  return {fmt::format("{:.{}f}", value, decimals), fmt::format("{:.{}f}", uncertainty, decimals)};
}

std::string significance_note(const json& figure, const Labels& labels) {
  const auto* significant = member(figure, "significant");
  const auto* bound = member(figure, "upper_bound");
  if (significant == nullptr || !significant->is_boolean() || significant->get<bool>() || bound == nullptr ||
      !bound->is_number()) {
    return "";
  }
  return labels("ui.not_significant") + " (< " + format_number(bound->get<double>(), 2) + ")";
}

std::string figure_text(const json& figure, const Labels& labels) {
  const auto [value, uncertainty] = format_figure(figure, labels);
  const std::string unit = is_unmeasured_figure(figure) ? "" : pretty_unit(figure.value("unit", ""));  // not "not measured °/h"
  const std::string note = significance_note(figure, labels);
  return value + (uncertainty.empty() ? "" : " ± " + uncertainty) + (unit.empty() ? "" : " " + unit) +
         (note.empty() ? "" : ", " + note);
}

}  // namespace inertest::report
