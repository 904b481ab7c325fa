#include "inertest/core/test_temperature.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/units.h"

namespace inertest {

void check_test_temperature(const std::string& procedure, std::size_t run, double degC) {
  if (!std::isfinite(degC)) throw Error(fmt::format("{}: run {}: temperature is not finite", procedure, run));
  if (degC < constants::kAbsoluteZeroDegC) {  // a typo (-400 for -40) moved the sensitivity silently
    throw Error(fmt::format("{}: run {}: {} degC is below absolute zero", procedure, run, degC));
  }
  if (degC > kHottestTestDegC) {
    throw Error(fmt::format("{}: run {}: {} degC is above {} degC; is it in kelvin? temperatures are in degC", procedure,
                            run, degC, kHottestTestDegC));
  }
}

void check_first_run_is_room_temperature(const std::string& procedure, const std::string& clause, double first_degC,
                                         const std::string& how_to_name) {
  if (first_degC >= kStandardAtmosphereDegC[0] && first_degC <= kStandardAtmosphereDegC[1]) return;
  throw Error(fmt::format("{}: the first run, taken as the room-temperature run ({}), is at {} degC, outside the "
                          "standard atmosphere's {}-{} degC (4.1.1.1): give the room temperature ({})",
                          procedure, clause, first_degC, kStandardAtmosphereDegC[0], kStandardAtmosphereDegC[1],
                          how_to_name));
}

}  // namespace inertest
