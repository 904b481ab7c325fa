// Helpers shared by the gyro and accelerometer misalignment separations: exact trigonometry of
// position angles, a least-squares solve whose rank failure names the angles, and angle figures.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "inertest/core/error.h"
#include "inertest/core/figure.h"
#include "inertest/numerics/least_squares.h"

namespace inertest::misalignment_detail {

// sin and cos of an angle in deg, exact (0, ±1) at multiples of 90 deg, so that the paper's
// positions give designs with exact zeros (sin(π) in double is 1.2e-16, not 0).
double sin_deg(double degrees);
double cos_deg(double degrees);

// Solves the design by least squares. When the equations cannot determine every parameter (too
// few equations, or dependent columns) throws Error "<what> cannot separate <names>; <hint>" at
// `where`, naming the parameters the design leaves unidentified.
LeastSquaresResult solve_separating(const Matrix& design, std::span<const double> observations,
                                    const std::vector<std::string>& names, const SourceLocation& where,
                                    const std::string& what, const std::string& hint);

// An angle in rad as a Figure in arcsec, with its 1-sigma uncertainty when given.
Figure arcsec_figure(double radians, std::optional<double> sigma_radians);

// γ = √(Δθy2² + Δθz2²) (misalignment paper) in arcsec; its uncertainty by first-order propagation of the
// covariance of (Δθy2, Δθz2) when given (variances and covariance in rad²).
struct AnglePairCovariance {
  double var_y2 = 0.0;
  double var_z2 = 0.0;
  double cov_y2_z2 = 0.0;
};
Figure misalignment_figure(double delta_theta_y2, double delta_theta_z2, std::optional<AnglePairCovariance> covariance);

// The result's warnings for its outputs: one when every position gave the same output (a stuck
// channel), whose angles of 0 arcsec are then not a measurement; none otherwise.
std::vector<std::string> constant_output_warnings(std::span<const double> outputs, const std::string& output_unit);

}  // namespace inertest::misalignment_detail
