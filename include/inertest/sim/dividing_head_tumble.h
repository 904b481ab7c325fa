// The accelerometer's multipoint tumble on a dividing head (issue 18; procedure
// "accelerometer_tumble", IEEE Std 1293-1998 8.3): the head's axis horizontal along the
// accelerometer's output (or pendulous) axis, the head stepped through equally spaced angles over
// whole turns, and the accelerometer's mean output read at each. The output follows the model
// equation of 8.3 in the convention of src/procedures/accelerometer_tumble_spec.cc:
//   a_i = gamma cos(theta - e), a_c = s gamma sin(theta - e),
//   E = K1 (K0 + a_i + K2 a_i^2 + K3 a_i^3 + h c a_c + K_x a_i a_c) + noise,
// with gamma the site's gravity in g, e the fixture's mounting error (IA's reference leaning toward
// the head's cross direction), s = -1 when the accelerometer is turned 180 deg about IA in the
// fixture, h = +1 with the head along OA (c = delta_o) and -1 along PA (c = delta_p), and white
// noise on each position's mean. Every coefficient's truth follows from how the rows were made.
#pragma once

#include <cstdint>
#include <string>

namespace inertest::sim {

struct AccelerometerTumbleTruth {
  double bias_g = 1.5e-3;            // K0, g
  double scale_factor = 1.25;        // K1, output unit per g
  double second_order = 15e-6;       // K2, 1/g
  double third_order = 4e-6;         // K3, 1/g^2
  double misalignment_rad = 2e-4;    // delta_o (head along OA) or delta_p (head along PA)
  double cross_coupling = 8e-6;      // K_ip (head along OA) or K_io (head along PA), 1/g
  double mounting_error_rad = 0.0;   // e
  double noise = 2e-6;               // 1 sigma of each position's mean, output unit
};

struct AccelerometerTumbleOptions {
  AccelerometerTumbleTruth truth;
  std::size_t positions = 8;     // equally spaced head angles per turn
  std::size_t turns = 1;         // repeated turns ('run' 1, 2, ...)
  bool both_mountings = true;    // each turn also turned 180 deg about IA (mounting_deg 180)
  bool head_along_output = true;
  double gravity_m_s2 = 9.80665;
};

// The model's noise-free output at head angle theta (deg), turned or not.
double accelerometer_tumble_output(const AccelerometerTumbleOptions& options, double angle_deg, bool turned);

// The positions CSV the procedure reads: header run,mounting_deg,angle_deg,output, one row per
// position (turn by turn, mounting 0 then 180), outputs with noise drawn from `seed`.
std::string simulate_accelerometer_tumble(const AccelerometerTumbleOptions& options, std::uint64_t seed);

}  // namespace inertest::sim
