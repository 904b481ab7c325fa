#include "inertest/sim/imu_noise.h"

#include <cmath>
#include <string>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/sim/random.h"

namespace inertest::sim {

std::vector<std::vector<double>> simulate_imu_noise(const std::vector<ImuAxisNoise>& axes, double sample_rate_hz,
                                                    std::size_t samples, std::uint64_t seed) {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) throw Error("the sample rate must be positive");
  const double dt = 1.0 / sample_rate_hz;
  std::vector<std::vector<double>> columns;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const ImuAxisNoise& axis = axes[a];
    NoiseGenerator noise(axis.noise, dt, Random(seed).stream(axis.name.empty() ? std::to_string(a) : axis.name));
    std::vector<double> column(samples);
    const double omega = 2.0 * constants::kPi * axis.sine_frequency_hz;
    for (std::size_t i = 0; i < samples; ++i) {
      column[i] = noise.next() + axis.sine_amplitude * std::sin(omega * (static_cast<double>(i) + 0.5) * dt);
    }
    columns.push_back(std::move(column));
  }
  return columns;
}

}  // namespace inertest::sim
