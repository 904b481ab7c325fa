// Reading procedure results (their to_json() form) for the report: figures, curves, units.
// Results are JSON written by procedures the report may not know, so every reader tolerates
// missing or oddly typed members (it returns nothing rather than throwing).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace inertest::report {

// Whether the node is a figure: an object with a numeric "value" and a string "unit".
bool is_figure(const nlohmann::json& node);

// A number, or a figure's value; nothing for anything else.
std::optional<double> number_of(const nlohmann::json& node);

// A figure's unit; "" for plain numbers and anything else.
std::string unit_of(const nlohmann::json& node);

// The member of an object, or null when the node is no object or lacks it.
const nlohmann::json* member(const nlohmann::json& node, std::string_view key);

// One member read across the elements of an array (figures or plain numbers), e.g. the "rate" of
// each point of a curve. Elements without it give NaN; the unit is the first figure's unit.
struct Column {
  std::vector<double> values;
  std::vector<double> uncertainties;  // NaN where a figure has none
  std::string unit;
  bool empty() const { return values.empty(); }
};
Column column(const nlohmann::json& array, std::string_view key);

// An array of plain numbers or figures (all in the first one's unit).
Column number_array(const nlohmann::json& node);

// A unit as a reader expects it: "deg/h" -> "°/h", "sqrt(h)" -> "√h", "degC" -> "°C", "1" -> "".
std::string pretty_unit(const std::string& unit);

// A number with `significant` digits, exponents as "1.5e-5"; plain text.
std::string format_number(double value, int significant = 6);

}  // namespace inertest::report
