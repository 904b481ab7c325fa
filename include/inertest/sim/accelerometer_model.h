// The simulated accelerometer of the 4-position gravity test (the misalignment paper): a
// single-axis accelerometer with bias, scale factor and the two misalignment angles of its input
// axis, white noise and an output quantised by the voltmeter's resolution.
//
// Output model: V = V0 + kI·(u·f) + noise, u = IA tilted toward PA by a and toward OA by b,
// u = (cos a·cos b, sin a·cos b, sin b) in the IA/PA/OA frame; f the specific force in g.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/sim/geometry.h"
#include "inertest/sim/random.h"

namespace inertest::sim {

struct AccelerometerParameters {
  std::string id = "ACC-SIM";
  std::string output_unit = "V";
  double sample_rate_hz = 10.0;
  double scale_factor = 1.3;      // kI, output unit per g
  double bias_g = 0.0;            // V0 / kI, g
  std::array<double, 2> misalignment_arcsec{};  // IA tilt toward PA, toward OA
  double noise_ug_rt_hz = 0.0;    // white noise, one-sided amplitude spectral density, µg/√Hz
  double output_resolution = 0.0; // voltmeter quantum, output unit; 0: none

  void validate() const;  // throws Error naming the bad parameter
  nlohmann::json to_json() const;
  // The IA unit vector in the IA/PA/OA frame.
  Vector3 input_axis() const;
};

class AccelerometerModel {
 public:
  AccelerometerModel(const AccelerometerParameters& parameters, Random random);

  // `samples` outputs at the sample rate under the constant specific force f (g, IA/PA/OA frame).
  std::vector<double> record(const Vector3& specific_force_g, std::size_t samples);

  // The noise-free output under f.
  double noise_free_output(const Vector3& specific_force_g) const;

 private:
  AccelerometerParameters parameters_;
  Random random_;
  Vector3 input_axis_{};
};

}  // namespace inertest::sim
