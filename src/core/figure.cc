#include "inertest/core/figure.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "inertest/core/units.h"

namespace inertest {

Figure Figure::in(const std::string& other_unit) const {
  const Unit from = Unit::parse(unit);
  const Unit to = Unit::parse(other_unit);
  Figure converted{convert(value, from, to), other_unit, std::nullopt};
  if (uncertainty) converted.uncertainty = std::abs(convert(*uncertainty, from, to));
  return converted;
}

void to_json(nlohmann::json& json, const Figure& figure) {
  json = nlohmann::json{{"value", figure.value}, {"unit", figure.unit}};
  if (figure.uncertainty) json["uncertainty"] = *figure.uncertainty;
}

void from_json(const nlohmann::json& json, Figure& figure) {
  figure.value = json.at("value").get<double>();
  figure.unit = json.at("unit").get<std::string>();
  if (json.contains("uncertainty")) {
    figure.uncertainty = json.at("uncertainty").get<double>();
  } else {
    figure.uncertainty.reset();
  }
}

}  // namespace inertest
