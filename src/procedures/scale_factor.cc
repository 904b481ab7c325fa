#include "inertest/procedures/scale_factor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <boost/math/distributions/fisher_f.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/numerics/least_squares.h"
#include "inertest/numerics/statistics.h"

namespace inertest {
namespace {

constexpr double kPpm = 1e6;

struct DirectionFit {
  LineFit fit;
  std::vector<double> x;
  std::vector<double> y;
};

// The line through one direction's rates (eqs. 5-6 over them alone), its errors from one variance.
DirectionFit direction_line(const std::vector<double>& rates, const std::vector<double>& outputs, bool positive) {
  DirectionFit direction;
  for (std::size_t j = 0; j < rates.size(); ++j) {
    if ((rates[j] > 0.0) == positive) {
      direction.x.push_back(rates[j]);
      direction.y.push_back(outputs[j]);
    }
  }
  const std::vector<double>& x = direction.x;
  if (x.size() < 2) {
    throw Error(fmt::format("scale factor: {} {} rate(s); the asymmetry (GJB 2426A eq. 10) needs at least 2 "
                            "rates on each side of zero",
                            x.size(), positive ? "positive" : "negative"));
  }
  if (std::all_of(x.begin(), x.end(), [&](double v) { return v == x.front(); })) {
    throw Error(fmt::format("scale factor: the {} rates are all equal; a slope needs two distinct rates",
                            positive ? "positive" : "negative"));
  }
  direction.fit = fit_line(direction.x, direction.y);
  return direction;
}

// The shapes the test points' noise is taken about, each the one before and two columns more: the
// line through both directions; each direction's own line (the asymmetry); then each direction's
// polynomial of degree 2 and 3 (the nonlinearity's smooth shape). A shape is taken where the
// columns it adds are significant at kShapeSignificance against the shape chosen (Wald's test) and
// it leaves 3 degrees of freedom.
constexpr std::size_t kShapes = 4;
constexpr double kShapeSignificance = 0.01;

// The design of shape `shape` (0 to kShapes - 1) at the rates, over the largest |rate|.
Matrix shape_design(const std::vector<double>& rates, std::size_t shape) {
  double largest = 0.0;
  for (double v : rates) largest = std::max(largest, std::abs(v));
  Matrix design(rates.size(), 2 * shape + 2);
  for (std::size_t j = 0; j < rates.size(); ++j) {
    const double x = rates[j] / largest;
    const double negative = rates[j] < 0.0 ? 1.0 : 0.0;
    design(j, 0) = 1.0;
    design(j, 1) = x;
    if (shape >= 1) {  // the negative direction's own offset and slope
      design(j, 2) = negative;
      design(j, 3) = negative * x;
    }
    for (std::size_t power = 2; power <= shape; ++power) {  // each direction's x², x³
      design(j, 2 * power) = (1.0 - negative) * std::pow(x, static_cast<double>(power));
      design(j, 2 * power + 1) = negative * std::pow(x, static_cast<double>(power));
    }
  }
  return design;
}

// Wald's statistic βᵀ V⁻¹ β of a fit's parameters from `first` on (V their covariance block), by
// Gauss-Jordan elimination on the small block; 0 where the block is singular.
double added_columns_wald(const LeastSquaresResult& fit, std::size_t first) {
  const std::size_t q = fit.parameters.size() - first;
  std::vector<std::vector<double>> v(q, std::vector<double>(q + 1));
  for (std::size_t i = 0; i < q; ++i) {
    for (std::size_t j = 0; j < q; ++j) v[i][j] = fit.covariance(first + i, first + j);
    v[i][q] = fit.parameters[first + i];
  }
  for (std::size_t c = 0; c < q; ++c) {  // V x = β, partial pivoting
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < q; ++r) {
      if (std::abs(v[r][c]) > std::abs(v[pivot][c])) pivot = r;
    }
    if (!(std::abs(v[pivot][c]) > 0.0)) return 0.0;
    std::swap(v[c], v[pivot]);
    for (std::size_t r = 0; r < q; ++r) {
      if (r == c) continue;
      const double factor = v[r][c] / v[c][c];
      for (std::size_t k = c; k <= q; ++k) v[r][k] -= factor * v[c][k];
    }
  }
  double wald = 0.0;
  for (std::size_t i = 0; i < q; ++i) wald += fit.parameters[first + i] * v[i][q] / v[i][i];
  return wald;
}

// The points' squared residuals about the shape the tests choose, weighted by `variance`, each
// scaled by 1/(1 - h_j), h_j its leverage, unbiased for its point's variance; and the shape. Empty
// without a residual.
std::pair<std::vector<double>, std::size_t> residuals_about_shape(const std::vector<double>& rates,
                                                                  const std::vector<double>& outputs,
                                                                  const PointVariance& variance) {
  std::vector<double> weights;
  for (double rate : rates) {
    const double v = variance.at_zero + variance.per_x2 * rate * rate;
    weights.push_back(v > 0.0 ? 1.0 / v : 1.0);
  }
  // Each shape's fit with the covariance HC3's, for Wald's test of the columns it adds over the shape
  // chosen so far, not only over the one before (a cubic is not a quadratic first): weights that are
  // not the points' variances (a noise growing with the rate, guessed from few points) do not make
  // it too sure, as they made an F-test (K's ±1σ then held its truth in 45-57 % of trials).
  const auto fit = [&](const Matrix& design, bool heteroscedastic) {
    LeastSquaresOptions options;
    options.require_full_rank = false;
    options.weights = weights;
    options.heteroscedastic = heteroscedastic;
    return solve_least_squares(design, outputs, options);
  };
  std::size_t shape = 0;
  Matrix design = shape_design(rates, 0);
  for (std::size_t next_shape = 1; next_shape < kShapes && rates.size() >= 2 * next_shape + 2 + 3; ++next_shape) {
    Matrix next_design = shape_design(rates, next_shape);
    const LeastSquaresResult next = fit(next_design, true);
    if (next.rank < next_design.cols) break;
    const std::size_t q = next_design.cols - design.cols;
    const double critical = static_cast<double>(q) *
                            boost::math::quantile(boost::math::fisher_f_distribution<double>(
                                                      static_cast<double>(q), static_cast<double>(next.degrees_of_freedom)),
                                                  1.0 - kShapeSignificance);
    if (!(added_columns_wald(next, design.cols) > critical)) continue;
    shape = next_shape;
    design = std::move(next_design);
  }
  // The shape chosen, its covariance s² (AᵀWA)⁻¹ for the leverages.
  const LeastSquaresResult chosen = fit(design, false);
  double rss = 0.0;  // weighted
  for (std::size_t j = 0; j < rates.size(); ++j) rss += weights[j] * chosen.residuals[j] * chosen.residuals[j];
  if (chosen.degrees_of_freedom == 0 || chosen.rank < design.cols || !(rss > 0.0)) return {{}, shape};
  const double s2 = rss / static_cast<double>(chosen.degrees_of_freedom);
  std::vector<double> z;
  for (std::size_t j = 0; j < rates.size(); ++j) {
    double leverage = 0.0;  // w_j a_j (AᵀWA)⁻¹ a_jᵀ
    for (std::size_t p = 0; p < design.cols; ++p) {
      for (std::size_t r = 0; r < design.cols; ++r) leverage += design(j, p) * chosen.covariance(p, r) * design(j, r) / s2;
    }
    z.push_back(chosen.residuals[j] * chosen.residuals[j] / std::max(1.0 - weights[j] * leverage, 1e-12));
  }
  return {z, shape};
}

// The test points' noise variance a + b Ω², from their residuals about the shape chosen (each
// squared and scaled by 1/(1 - h_j), h_j its leverage, unbiased for its point's variance); nothing
// without a residual. About the line through both directions alone, the asymmetry and the
// nonlinearity, which a repeat of the test gives again, counted as noise: on the demo's scale
// factor test (Kn 4.3 ppm, Ka 6.0 ppm) u(K) was 2.1 ppm where K scatters by 0.005 ppm over 40
// simulated tests (now 0.0044 ppm), and K's ±1σ held its truth in every trial of a gyro of 1 ppm
// asymmetry or of a cubic of 8 ppm. With 4 rates a direction only the asymmetry can be told from
// the noise: a nonlinearity stays in u(K) (3.2 ppm on the demo's repeatability runs).
std::optional<PointVariance> point_noise(const std::vector<double>& rates, const std::vector<double>& outputs) {
  if (rates.size() < 3) return std::nullopt;
  // The fits weigh the points by their variance a + b Ω²: first the one about the line through both
  // directions, then the one about the shape chosen, until the shape stays. Weights from the
  // residuals about the most flexible shape, whose largest rates' residuals their leverage leaves
  // near zero, made noise growing with the rate look like shapes (K's ±1σ held its truth in 48 %).
  PointVariance variance = fit_line(rates, outputs, true).point_variance;
  std::optional<std::size_t> shape;
  for (int pass = 0; pass < 4; ++pass) {
    const auto [z, chosen] = residuals_about_shape(rates, outputs, variance);
    if (z.empty()) return std::nullopt;
    double pooled = 0.0;
    for (double v : z) pooled += v / static_cast<double>(z.size());
    variance = point_variance_of(rates, z, pooled);
    if (shape == chosen) break;
    shape = chosen;
  }
  return variance;
}

// K(+) and K(−): each direction's own line, their errors from the points' noise (point_noise). One
// direction's alone, half the points, held K(+) in 59 % of trials; the line through both counts the
// asymmetry's V as noise, and stated K(+)'s error 24 times too large at 2000 ppm.
std::array<DirectionFit, 2> direction_lines(const std::vector<double>& rates, const std::vector<double>& outputs,
                                            const std::optional<PointVariance>& noise) {
  std::array<DirectionFit, 2> lines = {direction_line(rates, outputs, true), direction_line(rates, outputs, false)};
  if (noise) {
    for (DirectionFit& line : lines) line.fit = fit_line(line.x, line.y, true, noise);
  }
  return lines;
}

// u(F̄r) of eq. (2). F0 is the line's intercept for F_j = F̄_j − F̄r (eq. 3), so F̄r's error moves
// it one for one, and u²(F0) = u²(intercept) + u²(F̄r): without it F0's ±1σ held the truth in 28 %
// of trials. u²(F̄r) = s²(1/ns + 1/ne)/4, s² the static points' scatter about their common mean (a
// drift from the start to the end counted in it: ns + ne − 1 degrees of freedom). The one point
// each way that 5.8.1.3 d) asks for gives it one degree of freedom alone; then the fit's variance at
// zero rate is pooled in (its a of a + b Ω², with about m − 2), not its residual variance, which the
// noise and the nonlinearity of the high rates make larger than at rest (3.6 times in the demo).
double static_mean_standard_error(const std::vector<double>& start, const std::vector<double>& end, const LineFit& fit,
                                  std::size_t fit_points) {
  std::vector<double> all = start;
  all.insert(all.end(), end.begin(), end.end());
  const double static_degrees = static_cast<double>(all.size() - 1);
  const double spread = sample_standard_deviation(all);
  double variance = spread * spread;
  if (static_degrees < 2.0 && fit_points > 2) {
    const auto fit_degrees = static_cast<double>(fit_points - 2);
    variance = (static_degrees * variance + fit_degrees * fit.point_variance.at_zero) / (static_degrees + fit_degrees);
  }
  const auto ns = static_cast<double>(start.size());
  const auto ne = static_cast<double>(end.size());
  return 0.5 * std::sqrt(variance * (1.0 / ns + 1.0 / ne));
}

}  // namespace

void ScaleFactorOptions::validate() const {
  const Unit rate = Unit::parse(rate_unit);
  if (rate.dimension() != Unit::parse("rad/s").dimension()) {
    throw Error("scale factor: rate unit '" + rate_unit + "' is not an angular rate");
  }
  Unit::parse(output_unit);
}

ScaleFactorResult scale_factor(std::span<const ScaleFactorPoint> points, const ScaleFactorOptions& options) {
  options.validate();
  const auto first_moving = std::find_if(points.begin(), points.end(), [](const auto& p) { return p.rate != 0.0; });
  if (first_moving == points.end()) throw Error("scale factor: no nonzero rate among the test points");
  const auto last_moving =
      std::find_if(points.rbegin(), points.rend(), [](const auto& p) { return p.rate != 0.0; }).base();
  if (first_moving == points.begin()) {
    throw Error("scale factor: missing the static run at the start (zero-rate points before the first rate, "
                "GJB 2426A 5.8.1.3 d)");
  }
  if (last_moving == points.end()) {
    throw Error("scale factor: missing the static run at the end (zero-rate points after the last rate, "
                "GJB 2426A 5.8.1.3 d)");
  }

  std::vector<double> start_outputs;
  std::vector<double> end_outputs;
  for (auto it = points.begin(); it != first_moving; ++it) start_outputs.push_back(it->output);
  for (auto it = last_moving; it != points.end(); ++it) end_outputs.push_back(it->output);
  const double static_start = mean(start_outputs);  // F̄s
  const double static_end = mean(end_outputs);      // F̄e
  const double static_mean = 0.5 * (static_start + static_end);  // F̄r, eq. (2)

  std::vector<double> rates;
  std::vector<double> outputs;  // F_j = F̄_j - F̄r, eq. (3)
  std::vector<std::size_t> inner_zeros;  // 1-based places of zero rates between the first and last rate
  for (auto it = first_moving; it != last_moving; ++it) {
    // A zero rate inside the sequence (a stop between the directions) is no test point of eqs. (3)-(6),
    // which fit the input rates; the static runs of eq. (2) are those at the start and the end. Said.
    if (it->rate == 0.0) {
      inner_zeros.push_back(static_cast<std::size_t>(it - points.begin()) + 1);
      continue;
    }
    rates.push_back(it->rate);
    outputs.push_back(it->output - static_mean);
  }

  // eqs. (4)-(6). The standard errors allow a noise growing with the rate (the table's rate error,
  // the scale factor's own): one residual variance for all gave K's ±1σ a coverage of 35 % under
  // noise of 0.5 pulse/s + 5 ppm of the output.
  const std::optional<PointVariance> noise = point_noise(rates, outputs);
  const LineFit fit = fit_line(rates, outputs, true, noise);
  const auto [positive, negative] = direction_lines(rates, outputs, noise);
  const double k = fit.slope;
  if (k == 0.0) throw Error("scale factor: the fitted scale factor is zero; the output does not follow the rate");

  // Eqs. (7)-(9): deviation of each point from the line, relative to the largest |F_j|.
  double largest_output = 0.0;
  for (double f : outputs) largest_output = std::max(largest_output, std::abs(f));
  ScaleFactorResult result;
  double largest_deviation = 0.0;
  for (std::size_t j = 0; j < rates.size(); ++j) {
    const double fitted = k * rates[j] + fit.intercept;               // eq. (7)
    const double alpha = (fitted - outputs[j]) / largest_output;      // eq. (8)
    largest_deviation = std::max(largest_deviation, std::abs(alpha));  // eq. (9)
    result.nonlinearity_curve.push_back({rates[j], alpha * kPpm});
  }

  // Eqs. (10)-(11).
  const double k_positive = positive.fit.slope;
  const double k_negative = negative.fit.slope;
  // K(+) and K(-) of opposite signs (or one zero) mean an output that does not follow the rate alike
  // on both sides of zero; K(+) = -K(-) makes K-bar = 0 and eq. (10) infinite or NaN.
  if (!(k_positive * k_negative > 0.0)) {
    throw Error(
        fmt::format("scale factor: K(+) = {:.6g} and K(-) = {:.6g} have opposite signs (or one is zero): "
                    "the output does not follow the rate alike on both sides of zero, so the asymmetry of "
                    "eq. (10), relative to K-bar = (K(+) + K(-))/2 = {:.6g} (eq. 11), has no meaning; check "
                    "the signs of the negative rates and of the output",
                    k_positive, k_negative, 0.5 * (k_positive + k_negative)));
  }
  const double k_mean = 0.5 * (k_positive + k_negative);
  const double asymmetry = std::abs(k_positive - k_negative) / std::abs(k_mean);

  const std::string k_unit = options.output_unit + "/(" + options.rate_unit + ")";
  // A standard error of zero means "not estimable" (two points only): reported as unknown.
  // Outputs near 1e300 overflow the fit's sums of squares: its standard errors came out NaN and K
  // was given without an uncertainty (by the temperature series, which write no JSON to refuse).
  for (double value : {fit.residual_rms, fit.slope_standard_error, fit.intercept_standard_error, k, asymmetry}) {
    if (!std::isfinite(value)) {
      throw Error("scale factor: the fit overflows a double: the outputs are too large (give them in a larger unit)");
    }
  }
  auto with_error = [](double error) { return error > 0.0 ? std::optional<double>(error) : std::nullopt; };
  result.rate_unit = options.rate_unit;
  result.scale_factor = {k, k_unit, with_error(fit.slope_standard_error)};
  result.zero_offset = {fit.intercept, options.output_unit,
                        with_error(std::hypot(fit.intercept_standard_error,
                                              static_mean_standard_error(start_outputs, end_outputs, fit, rates.size())))};
  result.nonlinearity = {largest_deviation * kPpm, "ppm", std::nullopt};
  result.asymmetry = {asymmetry * kPpm, "ppm", std::nullopt};
  result.scale_factor_positive = {k_positive, k_unit, with_error(positive.fit.slope_standard_error)};
  result.scale_factor_negative = {k_negative, k_unit, with_error(negative.fit.slope_standard_error)};
  result.static_output_start = {static_start, options.output_unit, std::nullopt};
  result.static_output_end = {static_end, options.output_unit, std::nullopt};
  result.fit_residual_rms = {fit.residual_rms, options.output_unit, std::nullopt};

  for (const auto* direction : {&positive, &negative}) {
    if (direction->x.size() < options.recommended_rates_per_direction) {
      result.warnings.push_back(fmt::format("{} {} rates; GJB 2426A 5.8.1.3 asks for at least {} each way",
                                            direction->x.size(), direction == &positive ? "positive" : "negative",
                                            options.recommended_rates_per_direction));
    }
  }
  if (!inner_zeros.empty()) {
    result.warnings.push_back(fmt::format(
        "test point{} {} (counted from 1 among the test points, not the file's lines) {} at zero rate inside the "
        "sequence and left out of the fit: the static runs of eq. (2) are those at the start and the end (GJB 2426A "
        "5.8.1.3 d)",
        inner_zeros.size() == 1 ? "" : "s", fmt::join(inner_zeros, ", "), inner_zeros.size() == 1 ? "is" : "are"));
  }
  return result;
}

}  // namespace inertest
