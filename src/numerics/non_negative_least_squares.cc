#include "numerics/non_negative_least_squares.h"

#include <algorithm>

namespace inertest::detail {

Eigen::VectorXd non_negative_least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, std::vector<bool>& free) {
  const Eigen::Index n = a.cols();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  free.assign(static_cast<std::size_t>(n), false);
  const double tolerance = 1e-12 * a.norm() * std::max(1.0, b.norm());
  for (Eigen::Index outer = 0; outer < 3 * n * n; ++outer) {
    const Eigen::VectorXd gradient = a.transpose() * (b - a * x);
    Eigen::Index best = -1;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (!free[static_cast<std::size_t>(j)] && gradient(j) > tolerance && (best < 0 || gradient(j) > gradient(best))) {
        best = j;
      }
    }
    if (best < 0) break;
    free[static_cast<std::size_t>(best)] = true;
    for (Eigen::Index inner = 0; inner < 3 * n; ++inner) {
      std::vector<Eigen::Index> columns;
      for (Eigen::Index j = 0; j < n; ++j) {
        if (free[static_cast<std::size_t>(j)]) columns.push_back(j);
      }
      Eigen::MatrixXd sub(a.rows(), static_cast<Eigen::Index>(columns.size()));
      for (std::size_t c = 0; c < columns.size(); ++c) sub.col(static_cast<Eigen::Index>(c)) = a.col(columns[c]);
      const Eigen::VectorXd solution = sub.colPivHouseholderQr().solve(b);
      Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
      for (std::size_t c = 0; c < columns.size(); ++c) z(columns[c]) = solution(static_cast<Eigen::Index>(c));
      bool feasible = true;
      double step = 1.0;
      for (Eigen::Index j : columns) {
        if (z(j) <= 0.0) {
          feasible = false;
          step = std::min(step, x(j) / (x(j) - z(j)));
        }
      }
      if (feasible) {
        x = z;
        break;
      }
      x += step * (z - x);
      for (Eigen::Index j : columns) {
        if (x(j) <= 1e-15 * std::max(1.0, x.cwiseAbs().maxCoeff())) {
          x(j) = 0.0;
          free[static_cast<std::size_t>(j)] = false;
        }
      }
    }
  }
  return x;
}

Eigen::VectorXd solve_scaled_non_negative(const Eigen::MatrixXd& design, const Eigen::VectorXd& observed,
                                          const std::vector<bool>& allowed, std::vector<bool>& free) {
  Eigen::MatrixXd scaled = design;
  Eigen::VectorXd column_scale(design.cols());
  for (Eigen::Index j = 0; j < design.cols(); ++j) {
    if (!allowed[static_cast<std::size_t>(j)]) scaled.col(j).setZero();  // held at zero: never enters
    column_scale(j) = scaled.col(j).norm();
    if (!(column_scale(j) > 0.0)) column_scale(j) = 1.0;
    scaled.col(j) /= column_scale(j);
  }
  return non_negative_least_squares(scaled, observed, free).cwiseQuotient(column_scale);
}

Eigen::MatrixXd coefficient_covariance(const Eigen::MatrixXd& whitened_design, const std::vector<Eigen::Index>& columns) {
  Eigen::MatrixXd sub(whitened_design.rows(), static_cast<Eigen::Index>(columns.size()));
  for (std::size_t c = 0; c < columns.size(); ++c) sub.col(static_cast<Eigen::Index>(c)) = whitened_design.col(columns[c]);
  Eigen::VectorXd scale(sub.cols());
  for (Eigen::Index c = 0; c < sub.cols(); ++c) {
    scale(c) = sub.col(c).norm() > 0.0 ? sub.col(c).norm() : 1.0;
    sub.col(c) /= scale(c);
  }
  const Eigen::MatrixXd inverse = (sub.transpose() * sub).completeOrthogonalDecomposition().pseudoInverse();
  return scale.cwiseInverse().asDiagonal() * inverse * scale.cwiseInverse().asDiagonal();
}

}  // namespace inertest::detail
