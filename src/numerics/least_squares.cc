#include "inertest/numerics/least_squares.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "inertest/core/error.h"
#include "inertest/numerics/compensated_sum.h"

namespace inertest {

double LeastSquaresResult::standard_error(std::size_t i) const { return std::sqrt(covariance(i, i)); }

namespace {

// The autocorrelation of a series about zero at lag k, or nothing for a series of zeros.
std::optional<double> lag_correlation(const Eigen::VectorXd& e, Eigen::Index k) {
  CompensatedSum lagged, squares;
  for (Eigen::Index t = 0; t < e.size(); ++t) {
    squares.add(e(t) * e(t));
    if (t >= k) lagged.add(e(t) * e(t - k));
  }
  if (!(squares.value() > 0.0)) return std::nullopt;
  return lagged.value() / squares.value();
}
std::optional<double> lag_one_correlation(const Eigen::VectorXd& e) { return lag_correlation(e, 1); }

// Newey-West's Bartlett-kernel estimate of Var(Σ v_t) as overlapping batch means,
// m/(L(m - L + 1)) Σ_j V_j V_jᵀ, V_j the sum of L rows of v from j, with Andrews' (1991) AR(1)
// plug-in L = 1.1447 (α m)^(1/3), α = 4ρ²/((1 - ρ)²(1 + ρ)²), at most m/4.
Eigen::MatrixXd long_run_variance(const Eigen::MatrixXd& v, double rho) {
  const Eigen::Index m = v.rows();
  const double alpha = 4.0 * rho * rho / std::pow((1.0 - rho) * (1.0 + rho), 2);
  const auto length = std::clamp<Eigen::Index>(
      static_cast<Eigen::Index>(std::ceil(1.1447 * std::cbrt(alpha * static_cast<double>(m)))), 1,
      std::max<Eigen::Index>(1, m / 4));
  Eigen::MatrixXd prefix = Eigen::MatrixXd::Zero(m + 1, v.cols());
  for (Eigen::Index t = 0; t < m; ++t) prefix.row(t + 1) = prefix.row(t) + v.row(t);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(v.cols(), v.cols());
  for (Eigen::Index j = 0; j + length <= m; ++j) {
    const Eigen::RowVectorXd batch = prefix.row(j + length) - prefix.row(j);
    sum += batch.transpose() * batch;
  }
  return sum * (static_cast<double>(m) / (static_cast<double>(length) * static_cast<double>(m - length + 1)));
}

// Var(A^T e) for observations in time order whose errors are correlated, or nothing when the
// residuals' lag-1 autocorrelation rho is not above 2/sqrt(m) (white at 2 sigma). Andrews and
// Monahan's (1992) prewhitening: the scores u_t = a_t e_t less rho u_(t-1), whose long-run variance
// Newey-West's kernel then takes with little bias, recoloured by 1/(1 - rho)². With the errors taken
// as white, the temperature model's ±1σ held D_T in 16 % of trials under drift of a 60 s
// correlation time; Newey-West alone, without the prewhitening, held a slope in 56 % under AR(1)
// errors of 0.8. Of two estimates, the one whose covariance ((AᵀA)⁻¹ = inverse) is the larger.
std::optional<Eigen::MatrixXd> correlated_scores_variance(const Eigen::MatrixXd& a, const Eigen::VectorXd& e,
                                                          const Eigen::MatrixXd& inverse) {
  const Eigen::Index m = a.rows();
  if (m < 8) return std::nullopt;
  const std::optional<double> correlation = lag_one_correlation(e);
  if (!correlation || !(*correlation > 2.0 / std::sqrt(static_cast<double>(m)))) return std::nullopt;
  const double rho = std::min(*correlation, 0.99);
  Eigen::MatrixXd whitened(m - 1, a.cols());
  Eigen::VectorXd whitened_residuals(m - 1);
  for (Eigen::Index t = 1; t < m; ++t) {
    whitened.row(t - 1) = a.row(t) * e(t) - rho * a.row(t - 1) * e(t - 1);
    whitened_residuals(t - 1) = e(t) - rho * e(t - 1);
  }
  const double remaining = std::clamp(lag_one_correlation(whitened_residuals).value_or(0.0), 0.0, 0.9);
  const Eigen::MatrixXd prewhitened = long_run_variance(whitened, remaining) *
                                      (static_cast<double>(m) / static_cast<double>(m - 1)) / ((1.0 - rho) * (1.0 - rho));
  // A drift under white noise (a gyro's usual record): its lag-1 correlation is the drift's
  // persistence phi diluted by the white variance, which the prewhitening by rho and its short
  // bandwidth take for the whole (D_T's ±1σ held the truth in 13-55 % of trials under white noise
  // and drift of 60-600 s correlation times). As white plus AR(1), the autocovariances are
  // g(0) = s_w² + s_d², g(k) = s_d² phi^k: phi = g(2)/g(1) and s_d² = g(1)/phi, undiluted, and
  // Var(Aᵀe) = Σ_t Σ_s a_tᵀ a_s g(|t - s|) = g(0) AᵀA + s_d² Σ_t (a_tᵀ r_t + r_tᵀ a_t), with
  // r_t = phi (r_(t-1) + a_(t-1)). Where that covariance is the larger, it is taken.
  // Both lags significant (lag 2 of white noise alone made phi 0.999 by chance).
  const double second = lag_correlation(e, 2).value_or(0.0);
  if (!(second > 2.0 / std::sqrt(static_cast<double>(m)))) return prewhitened;
  const double phi = std::min(second / *correlation, 0.999);
  const double g0 = e.squaredNorm() / static_cast<double>(m);
  const double drift = std::min(*correlation * g0 / phi, g0);  // s_d²
  Eigen::MatrixXd meat = g0 * a.transpose() * a;
  Eigen::RowVectorXd carried = Eigen::RowVectorXd::Zero(a.cols());
  Eigen::MatrixXd cross = Eigen::MatrixXd::Zero(a.cols(), a.cols());
  for (Eigen::Index t = 1; t < m; ++t) {
    carried = phi * (carried + a.row(t - 1));
    cross += a.row(t).transpose() * carried;
  }
  meat += drift * (cross + cross.transpose());
  const auto covariance_trace = [&inverse](const Eigen::MatrixXd& variance) {
    return (inverse * variance * inverse).trace();
  };
  return covariance_trace(meat) > covariance_trace(prewhitened) ? meat : prewhitened;
}

}  // namespace

LeastSquaresResult solve_least_squares(const Matrix& design, std::span<const double> observations,
                                       const LeastSquaresOptions& options) {
  const std::size_t m = design.rows;
  const std::size_t n = design.cols;
  if (observations.size() != m) {
    throw Error("least squares: " + std::to_string(m) + " design rows but " +
                std::to_string(observations.size()) + " observations");
  }
  if (n == 0 || m < n) {
    throw Error("least squares: " + std::to_string(m) + " observations cannot determine " + std::to_string(n) +
                " parameters");
  }
  if (!options.weights.empty() && options.weights.size() != m) {
    throw Error("least squares: weights must have one entry per observation");
  }
  if (!options.relative_variances.empty() && (options.relative_variances.size() != m || !options.weights.empty())) {
    throw Error("least squares: relative variances need one entry per observation, and no weights");
  }

  const auto rows = static_cast<Eigen::Index>(m);
  const auto cols = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd a(rows, cols);
  Eigen::VectorXd y(rows);
  for (Eigen::Index r = 0; r < rows; ++r) {
    const double w = options.weights.empty() ? 1.0 : std::sqrt(options.weights[static_cast<std::size_t>(r)]);
    for (Eigen::Index c = 0; c < cols; ++c) {
      a(r, c) = w * design(static_cast<std::size_t>(r), static_cast<std::size_t>(c));
    }
    y(r) = w * observations[static_cast<std::size_t>(r)];
  }
  // Scale columns to unit norm so that the rank test does not depend on the parameters' units.
  Eigen::VectorXd scale = a.colwise().norm().transpose();
  for (Eigen::Index c = 0; c < cols; ++c) {
    if (scale(c) == 0.0) scale(c) = 1.0;
  }
  const Eigen::MatrixXd scaled = a * scale.cwiseInverse().asDiagonal();

  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled);
  qr.setThreshold(options.rank_tolerance);
  LeastSquaresResult result;
  result.rank = static_cast<std::size_t>(qr.rank());
  if (result.rank < n) {
    // The columns pivoted last are the ones that depend on the others.
    const auto& permutation = qr.colsPermutation().indices();
    std::string names;
    for (Eigen::Index k = qr.rank(); k < cols; ++k) {
      const auto index = static_cast<std::size_t>(permutation(k));
      result.unidentifiable.push_back(index);
      if (!names.empty()) names += ", ";
      names += index < options.parameter_names.size() ? options.parameter_names[index]
                                                      : "parameter " + std::to_string(index + 1);
    }
    if (options.require_full_rank) {
      throw Error("least squares: the design cannot identify " + names + " (rank " + std::to_string(result.rank) +
                  " of " + std::to_string(n) + ")");
    }
  }

  const Eigen::VectorXd x_scaled = qr.solve(y);
  const Eigen::VectorXd x = x_scaled.cwiseQuotient(scale);
  const Eigen::VectorXd weighted_residuals = y - a * x;

  result.parameters.assign(x.data(), x.data() + n);
  result.residuals.resize(m);
  CompensatedSum rss;
  CompensatedSum unweighted_rss;
  for (std::size_t r = 0; r < m; ++r) {
    double fitted = 0.0;
    for (std::size_t c = 0; c < n; ++c) fitted += design(r, c) * result.parameters[c];
    result.residuals[r] = observations[r] - fitted;
    unweighted_rss.add(result.residuals[r] * result.residuals[r]);
    const double wr = weighted_residuals(static_cast<Eigen::Index>(r));
    rss.add(wr * wr);
  }
  result.residual_rms = std::sqrt(unweighted_rss.value() / static_cast<double>(m));
  result.degrees_of_freedom = m - result.rank;

  result.covariance = Matrix(n, n);
  if (result.degrees_of_freedom > 0 && result.rank == n) {
    const double s2 = rss.value() / static_cast<double>(result.degrees_of_freedom);
    // (A^T W A)^-1 = P R^-1 R^-T P^T in scaled coordinates, then unscaled.
    const Eigen::MatrixXd r_upper = qr.matrixR().topLeftCorner(cols, cols).triangularView<Eigen::Upper>();
    const Eigen::MatrixXd r_inverse =
        r_upper.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(cols, cols));
    const Eigen::MatrixXd permuted = r_inverse * r_inverse.transpose();
    const Eigen::MatrixXd p = qr.colsPermutation();
    const Eigen::MatrixXd inverse = p * permuted * p.transpose();  // (A^T W A)^-1, scaled coordinates
    Eigen::MatrixXd scaled_covariance = s2 * inverse;
    if (options.heteroscedastic) {
      Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(cols, cols);
      for (Eigen::Index r = 0; r < rows; ++r) {
        const Eigen::RowVectorXd row = scaled.row(r);
        // A point the fit passes through by construction (leverage 1) leaves a residual of rounding
        // alone, which 1 - h would blow up: it tells nothing of the scatter.
        const double free = 1.0 - (row * inverse * row.transpose())(0, 0);
        if (free < 1e-8) continue;
        const double e = weighted_residuals(r) / free;
        meat += row.transpose() * row * (e * e);
      }
      scaled_covariance = inverse * meat * inverse;
    } else if (!options.relative_variances.empty()) {
      Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(cols, cols);
      CompensatedSum expected;  // E[RSS] / c = Σ (1 - h_i) v_i
      for (Eigen::Index r = 0; r < rows; ++r) {
        const Eigen::RowVectorXd row = scaled.row(r);
        const double v = options.relative_variances[static_cast<std::size_t>(r)];
        expected.add((1.0 - (row * inverse * row.transpose())(0, 0)) * v);
        meat += row.transpose() * row * v;
      }
      scaled_covariance = inverse * meat * inverse * (rss.value() / expected.value());
    } else if (options.serially_correlated) {
      if (const std::optional<Eigen::MatrixXd> meat = correlated_scores_variance(scaled, weighted_residuals, inverse)) {
        // Never below the white-noise covariance: the test for correlation only ever widens it.
        const Eigen::MatrixXd correlated = inverse * *meat * inverse;
        if (correlated.trace() > scaled_covariance.trace()) scaled_covariance = correlated;
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) {
        result.covariance(i, j) = scaled_covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) /
                                  (scale(static_cast<Eigen::Index>(i)) * scale(static_cast<Eigen::Index>(j)));
      }
    }
  }
  return result;
}

// z_j = e_j² / (1 - h_j) is unbiased for its point's variance V_j and scattered as V_j χ²₁: least
// squares weighted by 1/V_j², iterated from equal weights (a gamma GLM's scoring), so that the few
// largest |x| do not decide b alone. Where a would be negative, b x² alone.
PointVariance point_variance_of(std::span<const double> x, std::span<const double> z, double pooled) {
  std::vector<double> weights(x.size(), 1.0);
  double a = pooled;
  double b = 0.0;
  for (int iteration = 0; iteration < 8; ++iteration) {
    CompensatedSum w0, w2, w4, z0, z2;
    for (std::size_t j = 0; j < x.size(); ++j) {
      const double x2 = x[j] * x[j];
      w0.add(weights[j]);
      w2.add(weights[j] * x2);
      w4.add(weights[j] * x2 * x2);
      z0.add(weights[j] * z[j]);
      z2.add(weights[j] * z[j] * x2);
    }
    const double determinant = w0.value() * w4.value() - w2.value() * w2.value();
    b = determinant > 0.0 ? (w0.value() * z2.value() - w2.value() * z0.value()) / determinant : 0.0;
    if (!(b > 0.0)) return {pooled, 0.0};
    a = (z0.value() - b * w2.value()) / w0.value();
    if (a < 0.0) {
      a = 0.0;
      b = z2.value() / w4.value();
    }
    for (std::size_t j = 0; j < x.size(); ++j) {
      const double variance = a + b * x[j] * x[j];
      weights[j] = variance > 0.0 ? 1.0 / (variance * variance) : 0.0;
    }
  }
  return {a, b};
}

LineFit fit_line(std::span<const double> x, std::span<const double> y, bool heteroscedastic,
                 const std::optional<PointVariance>& given) {
  if (x.size() != y.size()) throw Error("line fit: x and y differ in length");
  if (x.size() < 2) throw Error("line fit: needs at least 2 points, got " + std::to_string(x.size()));
  const auto m = static_cast<double>(x.size());
  const double x_mean = compensated_sum(x) / m;
  const double y_mean = compensated_sum(y) / m;
  CompensatedSum sxx;
  CompensatedSum sxy;
  for (std::size_t j = 0; j < x.size(); ++j) {
    sxx.add((x[j] - x_mean) * (x[j] - x_mean));
    sxy.add((x[j] - x_mean) * (y[j] - y_mean));
  }
  if (sxx.value() == 0.0) throw Error("line fit: all x values are equal");
  LineFit fit;
  fit.slope = sxy.value() / sxx.value();          // eq. (5), centred form
  fit.intercept = y_mean - fit.slope * x_mean;    // eq. (6)
  CompensatedSum rss;
  for (std::size_t j = 0; j < x.size(); ++j) {
    const double r = y[j] - (fit.slope * x[j] + fit.intercept);
    rss.add(r * r);
  }
  fit.residual_rms = std::sqrt(rss.value() / m);
  if (x.size() > 2) {
    for (std::size_t j = 0; j < x.size(); ++j) {
      const double r = y[j] - (fit.slope * x[j] + fit.intercept);
      const double leverage = 1.0 / m + (x[j] - x_mean) * (x[j] - x_mean) / sxx.value();
      fit.scaled_squares.push_back(r * r / std::max(1.0 - leverage, 1e-8));
    }
  }
  if (given) {
    fit.point_variance = *given;
  } else if (x.size() <= 2) {
    return fit;
  } else if (const double pooled = rss.value() / (m - 2.0); !heteroscedastic) {
    fit.point_variance = {pooled, 0.0};
  } else {
    fit.point_variance = point_variance_of(x, fit.scaled_squares, pooled);
  }
  // slope = sum w_j y_j, intercept = sum c_j y_j, each point of its variance.
  CompensatedSum slope_variance;
  CompensatedSum intercept_variance;
  for (std::size_t j = 0; j < x.size(); ++j) {
    const double w = (x[j] - x_mean) / sxx.value();
    const double c = 1.0 / m - x_mean * w;
    const double variance = fit.point_variance.at_zero + fit.point_variance.per_x2 * x[j] * x[j];
    slope_variance.add(w * w * variance);
    intercept_variance.add(c * c * variance);
  }
  fit.slope_standard_error = std::sqrt(slope_variance.value());
  fit.intercept_standard_error = std::sqrt(intercept_variance.value());
  return fit;
}

}  // namespace inertest
