#include "inertest/procedures/random_walk_normalisation.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/numerics/statistics.h"
#include "inertest/procedures/bias_stability.h"

namespace inertest {

std::vector<NormalisedStabilityPoint> normalised_stability_curve(std::span<const double> output, double sample_rate_hz) {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw Error(fmt::format("random walk coefficient: the sample rate must be positive, got {} Hz", sample_rate_hz));
  }
  if (output.size() < 2) {
    throw Error(fmt::format("random walk coefficient: the record holds {} sample(s); at least 2 are needed",
                            output.size()));
  }
  std::vector<NormalisedStabilityPoint> curve;
  double tau = 1.0 / sample_rate_hz;
  curve.push_back({tau, sample_standard_deviation(output)});
  // Eq. (23): each level averages adjacent pairs of the level before, about the first sample (the
  // deviations do not depend on it; a pair's mean near an offset of 1e9 is rounded to 1.2e-7 at
  // every level: 2.4e-2 of the curve's last point with noise of 1e-3).
  const double reference = output.front();
  std::vector<double> sequence(output.size() / 2);
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    sequence[i] = 0.5 * ((output[2 * i] - reference) + (output[2 * i + 1] - reference));
  }
  while (sequence.size() >= 2) {
    tau *= 2.0;
    curve.push_back({tau, sample_standard_deviation(sequence)});
    const std::size_t half = sequence.size() / 2;
    for (std::size_t i = 0; i < half; ++i) sequence[i] = 0.5 * (sequence[2 * i] + sequence[2 * i + 1]);
    sequence.resize(half);
  }
  return curve;
}

double noise_equivalent_rate(std::span<const double> output, double sample_rate_hz) {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw Error(fmt::format("random walk coefficient: the sample rate must be positive, got {} Hz", sample_rate_hz));
  }
  const double per_second = sample_rate_hz;
  if (per_second < 1.0) {
    throw Error(fmt::format("random walk coefficient: the sample interval {} s is longer than 1 s; NER = Bs(1 s) "
                            "(GJB 2426A 5.12.5.4.1 c) needs samples at least every second",
                            1.0 / sample_rate_hz));
  }
  if (static_cast<double>(output.size()) < 2.0 * per_second) {
    throw Error(fmt::format("random walk coefficient: the record lasts {} s; NER = Bs(1 s) needs at least two whole "
                            "1 s windows",
                            static_cast<double>(output.size()) / sample_rate_hz));
  }
  if (std::abs(per_second - std::round(per_second)) <= 1e-6 * per_second) {
    return output_stability(output, sample_rate_hz, 1.0).stability;
  }
  const auto curve = normalised_stability_curve(output, sample_rate_hz);
  for (std::size_t i = 1; i < curve.size(); ++i) {
    if (curve[i].tau_s >= 1.0) {
      const auto& a = curve[i - 1];
      const auto& b = curve[i];
      const double t = (std::log(1.0) - std::log(a.tau_s)) / (std::log(b.tau_s) - std::log(a.tau_s));
      if (a.stability <= 0.0 || b.stability <= 0.0) return a.stability + t * (b.stability - a.stability);
      return std::exp(std::log(a.stability) + t * (std::log(b.stability) - std::log(a.stability)));
    }
  }
  throw Error("random walk coefficient: the record is too short for τ = 1 s in the sequence of eq. (23)");
}

}  // namespace inertest
