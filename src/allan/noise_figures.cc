#include "allan/noise_figures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>

#include <nlohmann/json.hpp>

#include "inertest/allan/noise_terms.h"

namespace inertest::detail {

FigureUnits units_for(const std::string& input_unit, int p) {
  static constexpr std::array<std::string_view, 5> kSuffix = {"*s", "*sqrt(s)", "", "/sqrt(s)", "/s"};
  static constexpr std::array<std::string_view, 5> kGyro = {"arcsec", "deg/sqrt(h)", "deg/h", "deg/h/sqrt(h)",
                                                            "deg/h/h"};
  static constexpr std::array<std::string_view, 5> kAccelerometer = {"m/s", "m/s/sqrt(h)", "ug", "m/s/h/sqrt(h)",
                                                                     "m/s/h/h"};
  const auto k = static_cast<std::size_t>(p + 2);
  const std::string computed = kSuffix[k].empty() ? input_unit : "(" + input_unit + ")" + std::string(kSuffix[k]);
  switch (sensor_kind_of(input_unit)) {
    case SensorKind::kGyro: return {computed, std::string(kGyro[k])};
    case SensorKind::kAccelerometer: return {computed, std::string(kAccelerometer[k])};
    case SensorKind::kOther: break;
  }
  return {computed, computed};
}

Figure figure_of(double coefficient, double uncertainty, double c, const FigureUnits& units) {
  Figure figure;
  figure.unit = units.computed;
  figure.value = std::sqrt(c * std::max(0.0, coefficient));
  if (std::isfinite(uncertainty)) {
    figure.uncertainty = coefficient > 0.0 ? std::sqrt(c) * uncertainty / (2.0 * std::sqrt(coefficient))
                                           : std::sqrt(c * uncertainty);
  }
  return figure.in(units.reported);
}

nlohmann::json noise_figure_json(const Figure& figure, bool identified, bool significant,
                                 const std::optional<Figure>& upper_bound) {
  nlohmann::json json = figure;
  if (!identified) {
    json["value"] = nullptr;
    json["identified"] = false;
  } else if (!significant) {
    json["significant"] = false;
  }
  if (!significant) json["upper_bound"] = upper_bound ? nlohmann::json(upper_bound->value) : nlohmann::json(nullptr);
  return json;
}

}  // namespace inertest::detail
