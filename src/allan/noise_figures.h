// The units and figures of the noise terms, shared by the Allan fit (noise_terms.cc) and the PSD
// fit (power_spectral_density.cc) so that both report the same names in the same units.
#pragma once

#include <string>

#include "inertest/core/figure.h"

namespace inertest::detail {

// The unit a figure is computed in from the input unit U, and the unit it is reported in.
struct FigureUnits {
  std::string computed;
  std::string reported;
};

// computed: U (no suffix) or "(U)" + suffix; reported: `angular` when U is an angular rate, else
// computed. E.g. units_for("deg/h", "*sqrt(s)", "deg/sqrt(h)") for the angle random walk.
FigureUnits units_for(const std::string& input_unit, const std::string& suffix, const std::string& angular);

// value = sqrt(c A) in units.reported; its 1-sigma uncertainty by first order from that of A, or the
// figure of the bound sqrt(c uncertainty) for A = 0; none when the uncertainty is not finite.
Figure figure_of(double coefficient, double uncertainty, double c, const FigureUnits& units);

}  // namespace inertest::detail
