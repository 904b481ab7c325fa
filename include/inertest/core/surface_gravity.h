// The range a site's gravity is checked against, shared by the procedures that take one
// (imu-calibration, imu-apply, centrifuge): a value outside it is a mistyped parameter, not a site.
#pragma once

#include <string>

#include <fmt/format.h>

#include "inertest/core/procedure_spec.h"

namespace inertest {

// Normal gravity on the ellipsoid runs from 9.7803 m/s^2 at the equator to 9.8322 m/s^2 at the poles
// (GRS 80: Moritz, Bull. Geod. 54 (1980) 395); the free-air gradient, -3.086e-6 s^-2, takes 0.03
// m/s^2 off at the highest summits. (9.7, 9.9) m/s^2 holds every site on the Earth's surface with a
// margin, and refuses a value in another unit (0.98 daN/kg, 980 Gal) or of another digit.
inline void check_surface_gravity(const std::string& parameter, double gravity_m_s2) {
  if (!(gravity_m_s2 > 9.7 && gravity_m_s2 < 9.9)) {
    throw ParameterError(parameter, fmt::format("{} m/s^2 is not a gravity on the Earth's surface", gravity_m_s2));
  }
}

}  // namespace inertest
