#include "sim/lab.h"

#include <cmath>
#include <filesystem>
#include <fmt/format.h>

#include "inertest/core/units.h"
#include "inertest/io/atomic_write.h"

namespace inertest::sim {

void Lab::write(const std::string& relative, const std::string& content) {
  const std::filesystem::path path = std::filesystem::path(out_dir) / relative;
  std::filesystem::create_directories(path.parent_path());
  write_file_atomically(path.string(), content);
  written_files.push_back(path.string());
}

std::string time_series_csv(const std::vector<std::int64_t>& pulses, double sample_rate_hz, double start_s,
                            const std::string& comment) {
  std::string text = "# " + comment + "\ntime,output\n";
  text.reserve(text.size() + pulses.size() * 24);
  const double dt = 1.0 / sample_rate_hz;
  for (std::size_t i = 0; i < pulses.size(); ++i) {
    const double t = start_s + (static_cast<double>(i) + 0.5) * dt;
    fmt::format_to(std::back_inserter(text), "{:.6f},{}\n", t, exact(static_cast<double>(pulses[i]) * sample_rate_hz));
  }
  return text;
}

double noise_of_mean_deg_s(const GyroParameters& gyro, double tau) {
  const NoiseParameters n = gyro.noise();
  const double flicker = 2.0 * std::log(2.0) / constants::kPi;  // IEEE 952 C.5
  const double variance = 3.0 * n.quantization * n.quantization / (tau * tau) +
                          n.angle_random_walk * n.angle_random_walk / tau +
                          flicker * n.bias_instability * n.bias_instability +
                          n.rate_random_walk * n.rate_random_walk * tau / 3.0 +
                          n.rate_ramp * n.rate_ramp * tau * tau / 2.0;
  // Pulse counter: the count over τ is within one pulse of the angle; two such ends per mean.
  const double counter = 1.0 / (std::abs(gyro.scale_factor) * tau) / std::sqrt(6.0);
  return std::sqrt(variance / (constants::kDegree * constants::kDegree) + counter * counter);
}

std::string exact(double value) { return fmt::format("{}", value); }

}  // namespace inertest::sim
