// The temperatures a gyro or an accelerometer is tested at, to tell a temperature in degC from one
// in kelvin read as degC (298.15 for 25 degC), and the room-temperature run of GJB 2426A's
// temperature sensitivities.
#pragma once

#include <cstddef>
#include <string>

namespace inertest {

// No inertial instrument is tested above this (chambers reach +125 degC at most): a value above it,
// given in degC, is a temperature in kelvin.
inline constexpr double kHottestTestDegC = 200.0;

// GJB 2426A-2004 4.1.1.1 a): the standard atmosphere's temperature, the room temperature of a test.
inline constexpr double kStandardAtmosphereDegC[2] = {15.0, 35.0};

// An Error "<procedure>: run <run>: ..." unless degC is a finite temperature above absolute zero and
// at most kHottestTestDegC (above: "is it in kelvin?"; 293.15 beside runs in degC divided a
// sensitivity by up to 9).
void check_test_temperature(const std::string& procedure, std::size_t run, double degC);

// The run taken as the room-temperature run when none is named is the first (GJB 2426A 5.8.5.3 a,
// 5.12.4.3 a): an Error unless it lies in the standard atmosphere's 15-35 degC. Runs listed cold to
// hot made the coldest the reference: Bt 2.2 times too small, Kt 3.00 for 3.50 ppm/degC. `clause`
// cites the procedure's, `how_to_name` says how to name the room temperature.
void check_first_run_is_room_temperature(const std::string& procedure, const std::string& clause, double first_degC,
                                         const std::string& how_to_name);

}  // namespace inertest
