#include "sim/lab.h"

#include <bit>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/io/atomic_write.h"

namespace inertest::sim {

void Lab::require_not_the_plan(const std::string& relative) const {
  std::error_code error;  // equivalent() is false, with an error, when either does not exist
  if (std::filesystem::equivalent(std::filesystem::path(out_dir) / relative, plan_path, error)) {
    throw Error(SourceLocation{plan_path, 0, 0},
                "the simulation would write its " + relative + " over this plan: give another --out directory");
  }
}

std::size_t Lab::samples(double seconds, double rate_hz) const {
  constexpr double kMostSamples = 1e9;
  const double count = std::round(seconds * rate_hz);
  if (!(count >= 0.0 && count <= kMostSamples)) {
    throw Error(SourceLocation{plan_path, 0, 0},
                fmt::format("a record of {:g} s at {:g} Hz is {:.3g} samples, more than the simulator makes in one "
                            "record ({:g}): shorten a test's seconds or hours, or lower its sample_rate_hz",
                            seconds, rate_hz, count, kMostSamples));
  }
  return static_cast<std::size_t>(count);
}

void Lab::write(const std::string& relative, const std::string& content) {
  require_not_the_plan(relative);
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

std::string f64_record(const std::vector<std::int64_t>& pulses, double sample_rate_hz) {
  std::string bytes(pulses.size() * 8, '\0');
  for (std::size_t i = 0; i < pulses.size(); ++i) {
    const auto bits = std::bit_cast<std::uint64_t>(static_cast<double>(pulses[i]) * sample_rate_hz);
    for (int b = 0; b < 8; ++b) bytes[i * 8 + b] = static_cast<char>((bits >> (8 * b)) & 0xffu);  // little-endian
  }
  return bytes;
}

double mean_output(const std::vector<std::int64_t>& pulses, double sample_rate_hz) {
  long double total = 0.0L;
  for (const auto p : pulses) total += static_cast<long double>(p);
  return static_cast<double>(total * static_cast<long double>(sample_rate_hz) / static_cast<long double>(pulses.size()));
}

namespace {

// Variance of the mean over T of the stationary noise processes (rad/s)², without the random walk.
double stationary_mean_variance(const GyroParameters& gyro, double seconds) {
  const NoiseParameters n = gyro.noise();
  const double dt = 1.0 / gyro.sample_rate_hz;
  // White rate noise N²/T; white angle noise Q at both ends, 2Q²/T².
  double variance = n.angle_random_walk * n.angle_random_walk / seconds + 2.0 * n.quantization * n.quantization / (seconds * seconds);
  if (n.bias_instability > 0.0) {
    // The generator's Gauss-Markov grid (noise.h): variance s² = B²·ln r/π each, correlation time T_i;
    // the mean over T has variance 2s²·(T_i/T)²·(T/T_i − 1 + e^(−T/T_i)).
    const double ratio = std::pow(10.0, 1.0 / 3.0);
    const double s2 = n.bias_instability * n.bias_instability * std::log(ratio) / constants::kPi;
    for (double t = std::max(n.flicker_shortest_s, dt); t <= n.flicker_longest_s * 1.0001; t *= ratio) {
      const double x = seconds / t;
      variance += 2.0 * s2 * (x - 1.0 + std::exp(-x)) / (x * x);
    }
  }
  return variance;
}

}  // namespace

double noise_of_record_mean_deg_s(const GyroParameters& gyro, double seconds) {
  const NoiseParameters n = gyro.noise();
  // Rate random walk from zero at the start: the mean of K·W(t) over T has variance K²T/3.
  const double variance = stationary_mean_variance(gyro, seconds) + n.rate_random_walk * n.rate_random_walk * seconds / 3.0 +
                          n.rate_ramp * n.rate_ramp * seconds * seconds / 4.0;
  // Pulse counter: the remainder at each end is uniform over one pulse, variance 2·(1/12)/(K0·T)².
  const double counter = 1.0 / (std::abs(gyro.scale_factor) * seconds) / std::sqrt(6.0);
  return std::sqrt(variance / (constants::kDegree * constants::kDegree) + counter * counter);
}

double expected_window_sd_deg_s(const GyroParameters& gyro, double tau, double windows) {
  const NoiseParameters n = gyro.noise();
  const double counter = 1.0 / (std::abs(gyro.scale_factor) * tau) / std::sqrt(6.0) * constants::kDegree;
  const double stationary = stationary_mean_variance(gyro, tau) + counter * counter -
                            stationary_mean_variance(gyro, windows * tau);
  const double variance = windows / (windows - 1.0) * stationary +
                          windows * n.rate_random_walk * n.rate_random_walk * tau / 6.0;
  return std::sqrt(variance) / constants::kDegree;
}

std::vector<std::vector<double>> interval_mean_covariance(const GyroParameters& gyro,
                                                          const std::vector<std::array<double, 2>>& intervals,
                                                          double t0) {
  const NoiseParameters n = gyro.noise();
  const std::size_t m = intervals.size();
  std::vector<std::vector<double>> cov(m, std::vector<double>(m, 0.0));
  std::vector<double> correlation_times;
  const double ratio = std::pow(10.0, 1.0 / 3.0);
  const double s2 = n.bias_instability * n.bias_instability * std::log(ratio) / constants::kPi;
  if (n.bias_instability > 0.0) {
    for (double t = std::max(n.flicker_shortest_s, 1.0 / gyro.sample_rate_hz); t <= n.flicker_longest_s * 1.0001;
         t *= ratio) {
      correlation_times.push_back(t);
    }
  }
  const double k2 = n.rate_random_walk * n.rate_random_walk;
  const double counter = constants::kDegree / std::abs(gyro.scale_factor);  // one pulse, rad
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t j = 0; j < m; ++j) {
      const auto& p = intervals[i][0] <= intervals[j][0] ? intervals[i] : intervals[j];  // the earlier
      const auto& q = intervals[i][0] <= intervals[j][0] ? intervals[j] : intervals[i];
      const double lp = p[1] - p[0];
      const double lq = q[1] - q[0];
      double c = 0.0;
      if (i == j) {
        c = n.angle_random_walk * n.angle_random_walk / lp + 2.0 * n.quantization * n.quantization / (lp * lp) +
            2.0 / 12.0 * counter * counter / (lp * lp) + k2 * (p[0] - t0 + lp / 3.0);
        for (const double t : correlation_times) {
          const double x = lp / t;
          c += 2.0 * s2 * (x - 1.0 + std::exp(-x)) / (x * x);
        }
      } else {
        const double gap = std::max(0.0, q[0] - p[1]);
        c = k2 * (0.5 * (p[0] + p[1]) - t0);
        for (const double t : correlation_times) {
          c += s2 * t * t * (1.0 - std::exp(-lp / t)) * (1.0 - std::exp(-lq / t)) * std::exp(-gap / t) / (lp * lq);
        }
      }
      cov[i][j] = c / (constants::kDegree * constants::kDegree);
    }
  }
  return cov;
}

double window_sd_sigma_deg_s(const GyroParameters& gyro, double tau, double windows) {
  const NoiseParameters n = gyro.noise();
  const auto count = static_cast<std::size_t>(windows);
  const double pulse = constants::kDegree / std::abs(gyro.scale_factor);  // rad
  const double counter = pulse * pulse / 12.0 / (tau * tau);              // (rad/s)² per remainder
  // γ(k), rad²/s²: white parts at k = 0, the counter at k = 0 (two remainders) and k = 1 (one shared).
  std::vector<double> gamma(count, 0.0);
  gamma[0] = n.angle_random_walk * n.angle_random_walk / tau + 2.0 * n.quantization * n.quantization / (tau * tau) +
             2.0 * counter;
  if (count > 1) gamma[1] -= counter;
  if (n.bias_instability > 0.0) {
    const double ratio = std::pow(10.0, 1.0 / 3.0);
    const double s2 = n.bias_instability * n.bias_instability * std::log(ratio) / constants::kPi;
    for (double t = std::max(n.flicker_shortest_s, 1.0 / gyro.sample_rate_hz); t <= n.flicker_longest_s * 1.0001;
         t *= ratio) {
      const double x = tau / t;
      gamma[0] += 2.0 * s2 * (x - 1.0 + std::exp(-x)) / (x * x);
      const double edge = s2 * (1.0 - std::exp(-x)) * (1.0 - std::exp(-x)) / (x * x);
      for (std::size_t k = 1; k < count; ++k) {
        const double term = edge * std::exp(-static_cast<double>(k - 1) * x);
        gamma[k] += term;
      }
    }
  }
  // The sample variance is about the record's mean, which removes the covariance every pair of
  // windows shares (the slow flicker that is constant over the record): centre γ on its mean over
  // all pairs, γ̄ = (1/n)·[γ(0) + 2·Σ(1 − k/n)·γ(k)], the variance of the grand mean.
  double mean = gamma[0];
  for (std::size_t k = 1; k < count; ++k) mean += 2.0 * (1.0 - static_cast<double>(k) / windows) * gamma[k];
  mean /= windows;
  double sum = (gamma[0] - mean) * (gamma[0] - mean);
  for (std::size_t k = 1; k < count; ++k) {
    sum += 2.0 * (1.0 - static_cast<double>(k) / windows) * (gamma[k] - mean) * (gamma[k] - mean);
  }
  const double walk = windows * n.rate_random_walk * n.rate_random_walk * tau / 6.0;  // E[s²] of the random walk
  const double variance_of_s2 = 2.0 / windows * sum + walk * walk;
  const double s = expected_window_sd_deg_s(gyro, tau, windows) * constants::kDegree;
  return std::sqrt(variance_of_s2) / (2.0 * s) / constants::kDegree;
}

double sample_sd_bound(double sigma, double count, double z) {
  // Wilson & Hilferty (1931): χ²_k quantile ≈ k·(1 − 2/(9k) + z·√(2/(9k)))³.
  const double k = count - 1.0;
  const double c = 2.0 / (9.0 * k);
  const double quantile = k * std::pow(1.0 - c + z * std::sqrt(c), 3.0);
  return sigma * std::sqrt(quantile / k);
}

std::vector<std::vector<double>> invert(std::vector<std::vector<double>> a) {
  const std::size_t n = a.size();
  std::vector<std::vector<double>> inv(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) inv[i][i] = 1.0;
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < n; ++r) {
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    }
    if (a[pivot][c] == 0.0) throw Error("simulation: singular normal matrix (the test cannot identify its parameters)");
    std::swap(a[c], a[pivot]);
    std::swap(inv[c], inv[pivot]);
    const double d = a[c][c];
    for (std::size_t j = 0; j < n; ++j) {
      a[c][j] /= d;
      inv[c][j] /= d;
    }
    for (std::size_t r = 0; r < n; ++r) {
      if (r == c || a[r][c] == 0.0) continue;
      const double f = a[r][c];
      for (std::size_t j = 0; j < n; ++j) {
        a[r][j] -= f * a[c][j];
        inv[r][j] -= f * inv[c][j];
      }
    }
  }
  return inv;
}

std::string exact(double value) { return fmt::format("{}", value); }

}  // namespace inertest::sim
