// The units and figures of the noise terms, shared by the Allan fit (noise_terms.cc) and the PSD
// fit (power_spectral_density.cc) so that both report the same names in the same units.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "inertest/core/figure.h"

namespace inertest::detail {

// The unit a figure is computed in from the input unit U, and the unit it is reported in.
struct FigureUnits {
  std::string computed;
  std::string reported;
};

// The units of the figure of the term A_p tau^p (p = -2..2): computed in U times the power of s its
// coefficient A_p (U^2 s^p) gives under the root; reported in the units of IEEE Std 952-1997 C.1 for
// a gyro (arcsec, deg/sqrt(h), deg/h, deg/h/sqrt(h), deg/h/h), of IEEE Std 1293-1998 for an
// accelerometer (m/s, m/s/sqrt(h), ug, m/s/h/sqrt(h), m/s/h/h), else as computed.
FigureUnits units_for(const std::string& input_unit, int p);

// value = sqrt(c A) in units.reported; its 1-sigma uncertainty by first order from that of A, or the
// figure of the bound sqrt(c uncertainty) for A = 0; none when the uncertainty is not finite.
Figure figure_of(double coefficient, double uncertainty, double c, const FigureUnits& units);

// A coefficient is significant when it lies at least this many of its 1-sigma uncertainties above
// zero, and its upper bound is this many above its estimate (the figure is the root of the
// coefficient, so its own value / uncertainty is twice the coefficient's).
inline constexpr double kSignificance = 2.0;

// A fitted term's JSON: the Figure; with "significant": false and "upper_bound" when identified but
// not significant; {"value": null, "unit", "identified": false, "upper_bound"} when held at zero.
nlohmann::json noise_figure_json(const Figure& figure, bool identified, bool significant,
                                 const std::optional<Figure>& upper_bound);

}  // namespace inertest::detail
