// The gyro's attitude integration of the IMU calibration (procedures/imu_calibration.h), exposed for
// its order test. Private to src/procedures.
#pragma once

#include <array>
#include <cstddef>

#include "inertest/procedures/imu_calibration.h"

namespace inertest {

using Quaternion = std::array<double, 4>;  // w, x, y, z

// The attitude change (the body at sample `to` relative to the body at sample `from`, from < to, both
// within the record) that the gyro samples turn through, each calibrated as rate = tk (output - bias)
// (rad/s). Each sample is taken as the instantaneous rate at its time stamp. dq/dt = q (x) (0, w) / 2
// is integrated by the classical RK4 (Hairer, Norsett and Wanner, Solving Ordinary Differential
// Equations I, 2nd ed., table II.1.2) over each step between samples, with the rate at the step's
// middle from the cubic through the four samples nearest it: fourth order in the step wherever the
// rate is smooth over four samples.
Quaternion attitude_change(const ImuRecord& record, std::size_t from, std::size_t to, const Matrix3& tk,
                           const Vector3& bias);

}  // namespace inertest
