#include "inertest/sim/dividing_head_tumble.h"

#include <cmath>

#include <fmt/format.h>

#include "inertest/core/units.h"
#include "inertest/sim/random.h"

namespace inertest::sim {

double accelerometer_tumble_output(const AccelerometerTumbleOptions& options, double angle_deg, bool turned) {
  const AccelerometerTumbleTruth& t = options.truth;
  const double gamma = options.gravity_m_s2 / constants::kStandardGravity;
  const double theta = angle_deg * constants::kDegree - t.mounting_error_rad;
  const double a_i = gamma * std::cos(theta);
  const double a_c = (turned ? -1.0 : 1.0) * gamma * std::sin(theta);
  const double h = options.head_along_output ? 1.0 : -1.0;
  return t.scale_factor * (t.bias_g + a_i + t.second_order * a_i * a_i + t.third_order * a_i * a_i * a_i +
                           h * t.misalignment_rad * a_c + t.cross_coupling * a_i * a_c);
}

std::string simulate_accelerometer_tumble(const AccelerometerTumbleOptions& options, std::uint64_t seed) {
  Random random(seed);
  std::string csv = "run,mounting_deg,angle_deg,output\n";
  for (std::size_t run = 1; run <= options.turns; ++run) {
    for (const bool turned : {false, true}) {
      if (turned && !options.both_mountings) continue;
      for (std::size_t k = 0; k < options.positions; ++k) {
        const double angle = 360.0 * static_cast<double>(k) / static_cast<double>(options.positions);
        const double output = accelerometer_tumble_output(options, angle, turned) + options.truth.noise * random.normal();
        csv += fmt::format("{},{},{},{:.17g}\n", run, turned ? 180 : 0, angle, output);
      }
    }
  }
  return csv;
}

}  // namespace inertest::sim
