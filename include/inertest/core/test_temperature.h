// The temperatures a gyro or an accelerometer is tested at, to tell a temperature in degC from one
// in kelvin read as degC (298.15 for 25 degC).
#pragma once

namespace inertest {

// No inertial instrument is tested above this (chambers reach +125 degC at most): a value above it,
// given in degC, is a temperature in kelvin.
inline constexpr double kHottestTestDegC = 200.0;

}  // namespace inertest
