#include "misalignment/misalignment_fit.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>

#include "inertest/core/units.h"
#include "inertest/numerics/statistics.h"

namespace inertest::misalignment_detail {
namespace {

// The quarter turn of an angle in deg when it is an exact multiple of 90 deg (0..3), else -1.
int exact_quarter(double degrees) {
  const double turns = std::fmod(degrees, 360.0);
  const double quarters = (turns < 0.0 ? turns + 360.0 : turns) / 90.0;
  if (quarters != std::floor(quarters)) return -1;
  return static_cast<int>(quarters) % 4;
}

}  // namespace

double sin_deg(double degrees) {
  switch (exact_quarter(degrees)) {
    case 0:
      return 0.0;
    case 1:
      return 1.0;
    case 2:
      return 0.0;
    case 3:
      return -1.0;
    default:
      return std::sin(degrees * constants::kDegree);
  }
}

double cos_deg(double degrees) {
  switch (exact_quarter(degrees)) {
    case 0:
      return 1.0;
    case 1:
      return 0.0;
    case 2:
      return -1.0;
    case 3:
      return 0.0;
    default:
      return std::cos(degrees * constants::kDegree);
  }
}

LeastSquaresResult solve_separating(const Matrix& design, std::span<const double> observations,
                                    const std::vector<std::string>& names, const SourceLocation& where,
                                    const std::string& what, const std::string& hint) {
  LeastSquaresOptions options;
  options.parameter_names = names;
  options.require_full_rank = false;
  // With fewer equations than unknowns, zero rows let the rank check name what is missing.
  Matrix padded = design;
  std::vector<double> padded_observations(observations.begin(), observations.end());
  if (design.rows < design.cols) {
    padded = Matrix(design.cols, design.cols);
    std::copy(design.data.begin(), design.data.end(), padded.data.begin());
    padded_observations.resize(design.cols, 0.0);
  }
  const LeastSquaresResult result = solve_least_squares(padded, padded_observations, options);
  if (design.rows < design.cols || !result.unidentifiable.empty()) {
    std::string unidentified;
    for (std::size_t index : result.unidentifiable) {
      if (!unidentified.empty()) unidentified += ", ";
      unidentified += names.at(index);
    }
    throw Error(where, fmt::format("{} ({} equation(s) for {} unknowns) cannot separate {}; {}", what, design.rows,
                                   design.cols, unidentified, hint));
  }
  return result;
}

Figure arcsec_figure(double radians, std::optional<double> sigma_radians) {
  Figure figure{radians / constants::kArcsecond, "arcsec", std::nullopt};
  if (sigma_radians) figure.uncertainty = *sigma_radians / constants::kArcsecond;
  return figure;
}

Figure misalignment_figure(double delta_theta_y2, double delta_theta_z2,
                           std::optional<AnglePairCovariance> covariance) {
  // Misalignment paper: γ = √(Δθy2² + Δθz2²).
  const double gamma = std::hypot(delta_theta_y2, delta_theta_z2);
  std::optional<double> sigma;
  if (covariance && gamma > 0.0) {
    // First order: ∂γ/∂Δθy2 = Δθy2/γ, ∂γ/∂Δθz2 = Δθz2/γ.
    const double a = delta_theta_y2 / gamma;
    const double b = delta_theta_z2 / gamma;
    const double variance =
        a * a * covariance->var_y2 + b * b * covariance->var_z2 + 2.0 * a * b * covariance->cov_y2_z2;
    sigma = std::sqrt(std::max(variance, 0.0));
  }
  return arcsec_figure(gamma, sigma);
}

std::vector<std::string> constant_output_warnings(std::span<const double> outputs, const std::string& output_unit) {
  if (!is_constant(outputs)) return {};
  return {fmt::format("every position's output equals {:.10g} {} (a stuck channel?); angles of 0 arcsec from it are "
                      "not a measurement",
                      outputs.front(), output_unit)};
}

}  // namespace inertest::misalignment_detail
