#include "allan/noise_figures.h"

#include <algorithm>
#include <cmath>

#include "inertest/core/units.h"

namespace inertest::detail {
namespace {

bool is_angular_rate(const std::string& unit) {
  return Unit::parse(unit).dimension() == Unit::parse("rad/s").dimension();
}

}  // namespace

FigureUnits units_for(const std::string& input_unit, const std::string& suffix, const std::string& angular) {
  const std::string computed = suffix.empty() ? input_unit : "(" + input_unit + ")" + suffix;
  return {computed, is_angular_rate(input_unit) ? angular : computed};
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

}  // namespace inertest::detail
