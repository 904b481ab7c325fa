// A hand-held IMU tumble for the triad calibration of issue 18 (procedures/imu_calibration.h): an
// IMU held still, then turned by hand about random axes, held still again, and so on. Each triad
// follows the calibration's model inverted, output = diag(scale_factor) (I + M)^-1 input + bias,
// with white noise and, when asked, rounding to whole counts, so that every parameter's truth
// follows from how the record was made.
#pragma once

#include <cstdint>

#include "inertest/procedures/imu_calibration.h"

namespace inertest::sim {

struct ImuTriadTruth {
  Vector3 bias{};          // output unit, before the offset
  Vector3 scale_factor{};  // output unit per input unit (m/s^2, rad/s)
  Matrix3 misalignment{};  // rad, the calibration's M (upper-triangular for the accelerometer)
  double noise = 0.0;      // white noise per sample, output unit (1 sigma)
};

struct ImuTumbleOptions {
  ImuTriadTruth accelerometer = {{96.0, 507.0, -404.0},
                                 {414.4, 412.0, 414.6},
                                 {{{0, 0.0034, -0.0096}, {0, 0, 0.0214}, {0, 0, 0}}},
                                 3.0};
  ImuTriadTruth gyro = {{9.0, -309.0, -256.0},
                        {6258.0, 6190.0, 6320.0},
                        {{{0, 0.012, -0.004}, {-0.007, 0, 0.009}, {0.015, -0.011, 0}}},
                        4.0};
  double offset = 32768.0;  // added to every output (a 16-bit ADC's mid-scale); 0 for none
  bool quantised = true;    // outputs rounded to whole counts
  double sample_rate_hz = 100.0;
  double gravity_m_s2 = 9.80665;
  double first_still_s = 20.0;
  std::size_t orientations = 20;
  double still_s = 6.0;  // held still after each rotation
};

// The record: `first_still_s` still, then `orientations` rotations, each of 60 to 150 deg about a
// random axis of the body over 2 to 3 s in the cycloidal profile (speed and acceleration zero at
// either end, see imu_tumble.cc), followed by `still_s` still. The specific force is the gravity's only (the IMU turns about
// its own centre); no Earth rate.
ImuRecord simulate_imu_tumble(const ImuTumbleOptions& options, std::uint64_t seed);

}  // namespace inertest::sim
