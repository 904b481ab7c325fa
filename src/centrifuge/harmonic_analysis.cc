#include "inertest/centrifuge/harmonic_analysis.h"

#include <cmath>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "inertest/core/error.h"
#include "inertest/numerics/compensated_sum.h"
#include "inertest/numerics/least_squares.h"
#include "inertest/numerics/statistics.h"

namespace inertest::centrifuge {
namespace {

// Tolerance on angles (rad) when deciding that samples are equally spaced over whole revolutions:
// far above the rounding of angles read from text in degrees, far below any real sampling step.
constexpr double kAngleTolerance = 1e-9;

bool near_multiple_of_turn(double angle) {
  const double turns = angle / (2.0 * constants::kPi);
  return std::abs(turns - std::round(turns)) * 2.0 * constants::kPi <= kAngleTolerance;
}

// The whole number of revolutions the samples cover if they are equally spaced with no harmonic
// 1..4 aliased onto zero; 0 otherwise.
double whole_revolutions(std::span<const double> gamma) {
  const std::size_t n = gamma.size();
  const double step = (gamma[n - 1] - gamma[0]) / static_cast<double>(n - 1);
  if (step == 0.0) return 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::abs(gamma[i] - (gamma[0] + static_cast<double>(i) * step)) > kAngleTolerance) return 0.0;
  }
  const double span = std::abs(step) * static_cast<double>(n);
  if (!near_multiple_of_turn(span)) return 0.0;
  // Orthogonality of 1, cos g, sin g, cos 2g, sin 2g over the samples needs m * step to be no
  // multiple of 2 pi for every difference or sum m of two harmonic orders (m = 1..4).
  for (int m = 1; m <= 4; ++m) {
    if (near_multiple_of_turn(m * step)) return 0.0;
  }
  return std::round(span / (2.0 * constants::kPi));
}

// The angles made continuous: a record that wraps them into [0, 360) deg (or any turn) is unwrapped,
// each step taken as the one of magnitude below half a turn, so that the span covered is counted in
// revolutions (eq. (11)'s harmonics are periodic: the fit does not change).
std::vector<double> unwrapped(std::span<const double> gamma) {
  std::vector<double> angles(gamma.begin(), gamma.end());
  const double turn = 2.0 * constants::kPi;
  double shift = 0.0;
  for (std::size_t i = 1; i < angles.size(); ++i) {
    const double step = gamma[i] - gamma[i - 1];
    shift -= turn * std::round(step / turn);
    angles[i] = gamma[i] + shift;
  }
  return angles;
}

double rms_about_fit(std::span<const double> gamma, std::span<const double> output, const HarmonicAmplitudes& a) {
  CompensatedSum sum;
  for (std::size_t i = 0; i < gamma.size(); ++i) {
    double fitted = 0.0;
    for (std::size_t h = 0; h < kHarmonicCount; ++h) fitted += a[h] * harmonic_basis(h, gamma[i]);
    const double r = output[i] - fitted;
    sum.add(r * r);
  }
  return std::sqrt(sum.value() / static_cast<double>(gamma.size()));
}

}  // namespace

const char* to_string(HarmonicFit::Method method) {
  return method == HarmonicFit::Method::kDiscreteFourier ? "dft" : "least_squares";
}

HarmonicFit analyse_harmonics(std::span<const double> gamma_rad, std::span<const double> output) {
  if (gamma_rad.size() != output.size()) {
    throw Error(fmt::format("harmonic analysis: {} angles but {} outputs", gamma_rad.size(), output.size()));
  }
  const std::size_t n = gamma_rad.size();
  if (n < kHarmonicCount) {
    throw Error(fmt::format("harmonic analysis: {} samples cannot determine the 5 amplitudes of eq. (11)", n));
  }
  HarmonicFit fit;
  fit.sample_count = n;
  fit.constant_output = is_constant(output);
  const std::vector<double> continuous = unwrapped(gamma_rad);
  const double revolutions = whole_revolutions(continuous);
  if (revolutions > 0.0) {
    // Exact DFT bins over whole revolutions.
    std::array<CompensatedSum, kHarmonicCount> sums;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t h = 0; h < kHarmonicCount; ++h) sums[h].add(output[i] * harmonic_basis(h, gamma_rad[i]));
    }
    for (std::size_t h = 0; h < kHarmonicCount; ++h) {
      fit.amplitudes[h] = (h == kK0 ? 1.0 : 2.0) * sums[h].value() / static_cast<double>(n);
    }
    fit.method = HarmonicFit::Method::kDiscreteFourier;
    fit.revolutions = revolutions;
  } else {
    Matrix design(n, kHarmonicCount);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t h = 0; h < kHarmonicCount; ++h) design(i, h) = harmonic_basis(h, gamma_rad[i]);
    }
    LeastSquaresOptions options;
    for (std::size_t h = 0; h < kHarmonicCount; ++h) options.parameter_names.emplace_back(harmonic_name(h));
    options.rank_tolerance = 1e-8;
    try {
      const LeastSquaresResult solved = solve_least_squares(design, output, options);
      for (std::size_t h = 0; h < kHarmonicCount; ++h) fit.amplitudes[h] = solved.parameters[h];
    } catch (const Error& e) {
      throw Error("harmonic analysis: the sampling angles cannot separate the terms of eq. (11): " + e.message());
    }
    fit.method = HarmonicFit::Method::kLeastSquares;
    // The span of the first to the last sample, and the mean step the last one stands for.
    fit.revolutions = std::abs(continuous[n - 1] - continuous[0]) * static_cast<double>(n) /
                      static_cast<double>(n - 1) / (2.0 * constants::kPi);
    const auto step_sign = [&](std::size_t i) { return continuous[i] > continuous[i - 1] ? 1 : -1; };
    bool one_way = true;
    for (std::size_t i = 2; i < n && one_way; ++i) one_way = step_sign(i) == step_sign(1);
    fit.part_of_a_revolution = one_way && fit.revolutions < 1.0 - 1e-6;
  }
  fit.residual_rms = rms_about_fit(gamma_rad, output, fit.amplitudes);
  return fit;
}

}  // namespace inertest::centrifuge
