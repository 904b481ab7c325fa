// Linear least squares with covariance, residuals and a rank check that names what a design
// cannot identify. Solved by QR with column pivoting (Golub & Van Loan, 4th ed., 5.4.2), so that a
// rank-deficient design is detected instead of producing huge, meaningless parameters.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace inertest {

// A dense row-major matrix, the interchange type of the public numerics API.
struct Matrix {
  Matrix() = default;
  Matrix(std::size_t row_count, std::size_t col_count)
      : rows(row_count), cols(col_count), data(row_count * col_count, 0.0) {}
  double& operator()(std::size_t r, std::size_t c) { return data[r * cols + c]; }
  double operator()(std::size_t r, std::size_t c) const { return data[r * cols + c]; }

  std::size_t rows = 0;
  std::size_t cols = 0;
  std::vector<double> data;
};

struct LeastSquaresOptions {
  // Optional names of the parameters, used in the rank-deficiency message.
  std::vector<std::string> parameter_names;
  // Optional weights (1/sigma^2 of each observation); empty means all ones.
  std::vector<double> weights;
  // Relative threshold on |R_ii| / |R_00| below which a column counts as dependent.
  double rank_tolerance = 1e-10;
  // Throw Error when the design is rank deficient (otherwise report it in the result).
  bool require_full_rank = true;
  // The covariance from each observation's own residual, for observations whose variances differ in
  // a way the weights do not give: HC3, (A^T W A)^-1 A^T W diag(e_i^2 / (1 - h_i)^2) W A (A^T W A)^-1,
  // h_i the leverage (MacKinnon and White 1985; Long and Ervin 2000 for small samples). Otherwise
  // one residual variance for all.
  bool heteroscedastic = false;
  // Observations in time order whose errors may be correlated (a gyro's drift from interval to
  // interval): where the residuals' lag-1 autocorrelation is above 2/sqrt(m), the covariance of
  // Newey and West (1987) with Andrews' (1991) bandwidth, if larger than the white one. The
  // white-noise covariance s² (AᵀWA)⁻¹ otherwise.
  bool serially_correlated = false;
  // The observations' variances up to one common factor c, for a fit the estimator keeps unweighted
  // (a published method's equations): the covariance (AᵀA)⁻¹ Aᵀ diag(c·v) A (AᵀA)⁻¹, c = RSS /
  // Σ (1 - h_i) v_i (the residuals' expectation). Empty: one variance for all. Not with weights.
  std::vector<double> relative_variances;
};

struct LeastSquaresResult {
  std::vector<double> parameters;
  // Covariance of the parameters, row-major n x n: s^2 (A^T W A)^-1 with s^2 the residual variance
  // RSS / (m - n) (weights taken as relative), or HC3 (LeastSquaresOptions::heteroscedastic).
  // Zero-filled when m == n.
  Matrix covariance;
  std::vector<double> residuals;  // y - A x
  double residual_rms = 0.0;      // sqrt(sum r^2 / m)
  std::size_t degrees_of_freedom = 0;
  std::size_t rank = 0;
  // Parameters the design cannot separate from the others (empty when full rank).
  std::vector<std::size_t> unidentifiable;

  double standard_error(std::size_t i) const;
};

// Solves min || W^(1/2) (A x - y) ||. Throws Error if A has fewer rows than columns, if sizes
// disagree, or (with require_full_rank) if the design is rank deficient, naming the parameters.
LeastSquaresResult solve_least_squares(const Matrix& design, std::span<const double> observations,
                                       const LeastSquaresOptions& options = {});

// Straight-line fit y = slope * x + intercept (GJB 2426A eqs. 4-6), computed on centred sums,
// which equals eqs. (5)-(6) algebraically but does not cancel when |x| is large. The standard
// errors are from one residual variance RSS / (m - 2), or with `heteroscedastic` from a variance
// a + b x² per point (a, b >= 0: a constant noise and one proportional to x, as a rate table's rate
// error), fitted to e_j² / (1 - h_j), h_j = 1/m + (x_j - x̄)²/Sxx, by least squares weighted as a
// gamma GLM's. Two parameters from all the points: HC3's one residual per point made the slope's
// error rest on the few largest |x|, and a chi-squared over several such fits (K(T)) failed 5 times
// too often. A variance `given` (another fit's, of more points of the same noise) is used as is.
struct PointVariance {
  double at_zero = 0.0;  // a: RSS / (m - 2) when one variance for all
  double per_x2 = 0.0;   // b
};
struct LineFit {
  double slope = 0.0;
  double intercept = 0.0;
  double slope_standard_error = 0.0;      // 0 when only two points (and no variance given)
  double intercept_standard_error = 0.0;
  double residual_rms = 0.0;
  PointVariance point_variance;           // the variance the errors were taken from
  // Each point's squared residual over 1 - h_j, unbiased for its variance (empty for two points).
  std::vector<double> scaled_squares;
};
LineFit fit_line(std::span<const double> x, std::span<const double> y, bool heteroscedastic = false,
                 const std::optional<PointVariance>& given = std::nullopt);

// The variance a + b x² (a, b >= 0) of points of abscissa x whose scaled squared residuals
// (LineFit::scaled_squares, of one line or several) are z, as fit_line's heteroscedastic errors
// take it; one variance for all, `pooled`, where b would not be positive.
PointVariance point_variance_of(std::span<const double> x, std::span<const double> z, double pooled);

}  // namespace inertest
