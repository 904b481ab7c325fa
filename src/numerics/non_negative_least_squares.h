// Non-negative least squares on Eigen matrices, shared by the noise-term fits of the Allan variance
// (src/allan/noise_terms.cc) and of the power spectral density (src/allan/power_spectral_density.cc).
// Internal: the public numerics API (least_squares.h) does not expose Eigen.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace inertest::detail {

// Lawson-Hanson NNLS (Lawson & Hanson, "Solving Least Squares Problems", 1974, ch. 23, active set):
// min ||A x - b|| subject to x >= 0. Returns x; `free` is set to the columns left free (x_j > 0).
Eigen::VectorXd non_negative_least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, std::vector<bool>& free);

// The NNLS solution of the (whitened) system with its columns scaled to unit norm, so that columns
// many decades apart stay well conditioned; a column whose `allowed` is false is held at zero and
// never enters. Returns x in the unscaled columns; `free` as above.
Eigen::VectorXd solve_scaled_non_negative(const Eigen::MatrixXd& design, const Eigen::VectorXd& observed,
                                          const std::vector<bool>& allowed, std::vector<bool>& free);

// The covariance of the coefficients in `columns`, (J^T V^-1 J)^-1 on the whitened design J
// (columns scaled to unit norm for the inversion; a pseudo-inverse where they are dependent).
Eigen::MatrixXd coefficient_covariance(const Eigen::MatrixXd& whitened_design, const std::vector<Eigen::Index>& columns);

}  // namespace inertest::detail
