#include "report/result_access.h"

#include <fmt/format.h>
#include <cmath>
#include <limits>

namespace inertest::report {

bool is_figure(const nlohmann::json& node) {
  return node.is_object() && node.contains("value") && node.at("value").is_number() && node.contains("unit") &&
         node.at("unit").is_string();
}

std::optional<double> number_of(const nlohmann::json& node) {
  if (node.is_number()) return node.get<double>();
  if (is_figure(node)) return node.at("value").get<double>();
  return std::nullopt;
}

std::string unit_of(const nlohmann::json& node) { return is_figure(node) ? node.at("unit").get<std::string>() : ""; }

const nlohmann::json* member(const nlohmann::json& node, std::string_view key) {
  if (!node.is_object()) return nullptr;
  const auto found = node.find(key);
  return found == node.end() ? nullptr : &*found;
}

namespace {

void append(Column& column, const nlohmann::json* node) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const auto value = node ? number_of(*node) : std::nullopt;
  column.values.push_back(value.value_or(kNaN));
  double uncertainty = kNaN;
  if (node && is_figure(*node) && node->contains("uncertainty") && node->at("uncertainty").is_number()) {
    uncertainty = node->at("uncertainty").get<double>();
  }
  column.uncertainties.push_back(uncertainty);
  if (column.unit.empty() && node) column.unit = unit_of(*node);
}

}  // namespace

Column column(const nlohmann::json& array, std::string_view key) {
  Column result;
  if (!array.is_array()) return result;
  for (const auto& element : array) append(result, member(element, key));
  return result;
}

Column number_array(const nlohmann::json& node) {
  Column result;
  if (!node.is_array()) return result;
  for (const auto& element : node) append(result, &element);
  return result;
}

std::string pretty_unit(const std::string& unit) {
  if (unit == "1") return "";
  static const std::pair<std::string_view, std::string_view> kReplacements[] = {
      {"sqrt(h)", "√h"}, {"sqrt(s)", "√s"}, {"sqrt(Hz)", "√Hz"}, {"degC", "°C"}, {"deg", "°"},
      {"arcsec", "″"},   {"arcmin", "′"},   {"^2", "²"},         {"^3", "³"},
  };
  std::string text = unit;
  for (const auto& [from, to] : kReplacements) {
    for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
      text.replace(at, from.size(), to);
    }
  }
  return text;
}

std::string format_number(double value, int significant) {
  if (!std::isfinite(value)) return value != value ? "NaN" : (value > 0 ? "∞" : "-∞");
  std::string text = fmt::format("{:.{}g}", value, significant);
  const auto e = text.find('e');
  if (e == std::string::npos) return text;
  const int exponent = std::stoi(text.substr(e + 1));
  return text.substr(0, e) + "e" + std::to_string(exponent);
}

}  // namespace inertest::report
