#include "inertest/procedures/earth_rate.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/core/units.h"

namespace inertest {

void AxisOrientation::validate() const {
  if (std::isnan(latitude_deg)) {
    // A plan's step adds where it is given ([site] latitude_deg: campaign/procedure_step.cc).
    throw ParameterError("latitude_deg", "latitude_deg is needed to remove the Earth rate");
  }
  if (!std::isfinite(latitude_deg) || std::abs(latitude_deg) > 90.0) {
    throw Error(fmt::format("latitude {} deg is not in [-90, 90]", latitude_deg));
  }
  if (!std::isfinite(elevation_deg) || std::abs(elevation_deg) > 90.0) {
    throw Error(fmt::format("IRA elevation {} deg is not in [-90, 90]", elevation_deg));
  }
  if (!std::isfinite(heading_deg)) throw Error("IRA heading is not a finite number");
}

double earth_rate_on_axis(const AxisOrientation& axis) {
  using constants::kDegree;
  const double phi = axis.latitude_deg * kDegree;
  const double h = axis.heading_deg * kDegree;
  const double e = axis.elevation_deg * kDegree;
  return constants::kEarthRate * (std::cos(phi) * std::cos(e) * std::cos(h) + std::sin(phi) * std::sin(e));
}

}  // namespace inertest
