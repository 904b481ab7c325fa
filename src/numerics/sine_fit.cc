#include "inertest/numerics/sine_fit.h"

#include <cmath>
#include <string>

#include "inertest/core/error.h"
#include "inertest/numerics/least_squares.h"

namespace inertest {

SineFit fit_sine(std::span<const double> time, std::span<const double> samples, double omega) {
  if (time.size() != samples.size()) {
    throw Error("sine fit: " + std::to_string(time.size()) + " times but " + std::to_string(samples.size()) +
                " samples");
  }
  if (samples.size() < 4) throw Error("sine fit: needs at least 4 samples, got " + std::to_string(samples.size()));
  if (!std::isfinite(omega) || omega <= 0.0) throw Error("sine fit: the frequency must be positive and finite");
  Matrix design(samples.size(), 3);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!std::isfinite(time[i]) || !std::isfinite(samples[i])) {
      throw Error("sine fit: sample " + std::to_string(i + 1) + " is not finite");
    }
    design(i, 0) = std::sin(omega * time[i]);
    design(i, 1) = std::cos(omega * time[i]);
    design(i, 2) = 1.0;
  }
  LeastSquaresOptions options;
  options.parameter_names = {"sine coefficient", "cosine coefficient", "offset"};
  const LeastSquaresResult fit = solve_least_squares(design, samples, options);
  const double s = fit.parameters[0];
  const double k = fit.parameters[1];
  SineFit result;
  result.amplitude = std::hypot(s, k);
  result.phase = std::atan2(k, s);
  result.offset = fit.parameters[2];
  result.residual_rms = fit.residual_rms;
  // First-order propagation of the (s, k) covariance into A and φ.
  if (result.amplitude > 0.0) {
    const double a2 = result.amplitude * result.amplitude;
    const double vss = fit.covariance(0, 0);
    const double vkk = fit.covariance(1, 1);
    const double vsk = fit.covariance(0, 1);
    result.amplitude_standard_error = std::sqrt(std::max(0.0, (s * s * vss + k * k * vkk + 2 * s * k * vsk) / a2));
    result.phase_standard_error = std::sqrt(std::max(0.0, (k * k * vss + s * s * vkk - 2 * s * k * vsk) / (a2 * a2)));
  }
  return result;
}

}  // namespace inertest
