#include "inertest/numerics/least_squares.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "inertest/core/error.h"
#include "inertest/numerics/statistics.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

TEST(FitLine, ExactLineIsRecovered) {
  const std::vector<double> x = {-3, -1, 0.5, 2, 7};
  std::vector<double> y;
  for (double v : x) y.push_back(2.5 * v - 4.0);
  const LineFit fit = fit_line(x, y);
  EXPECT_NEAR_RELATIVE(fit.slope, 2.5, 1e-14);
  EXPECT_NEAR_RELATIVE(fit.intercept, -4.0, 1e-14);
  EXPECT_NEAR(fit.residual_rms, 0.0, 1e-13);
}

TEST(FitLine, HandComputedStandardErrors) {
  // x = 0,1,2,3; y = 0,2,1,3: slope 0.8, intercept 0.3, residuals -0.3,0.9,-0.9,0.3 (RSS 1.8),
  // s^2 = 0.9, Sxx = 5: se(slope) = sqrt(0.18), se(intercept) = sqrt(0.9 (1/4 + 2.25/5)).
  const std::vector<double> x = {0, 1, 2, 3};
  const std::vector<double> y = {0, 2, 1, 3};
  const LineFit fit = fit_line(x, y);
  EXPECT_NEAR_RELATIVE(fit.slope, 0.8, 1e-14);
  EXPECT_NEAR_RELATIVE(fit.intercept, 0.3, 1e-14);
  EXPECT_NEAR_RELATIVE(fit.slope_standard_error, std::sqrt(0.18), 1e-14);
  EXPECT_NEAR_RELATIVE(fit.intercept_standard_error, std::sqrt(0.9 * (0.25 + 0.45)), 1e-14);
}

TEST(FitLine, LargeOffsetDoesNotCancel) {
  // x near 1e8: the textbook sums of eq. (5) would lose every digit; the centred form does not.
  std::vector<double> x;
  std::vector<double> y;
  for (int i = 0; i < 100; ++i) {
    x.push_back(1e8 + i);
    y.push_back(3.0 * i + 1.0);
  }
  EXPECT_NEAR_RELATIVE(fit_line(x, y).slope, 3.0, 1e-12);
}

TEST(FitLine, DegenerateInputIsAnError) {
  const std::vector<double> one = {1.0};
  EXPECT_THROW(fit_line(one, one), Error);
  const std::vector<double> same = {2.0, 2.0, 2.0};
  const std::vector<double> y = {1.0, 2.0, 3.0};
  EXPECT_THROW(fit_line(same, y), Error);
}

TEST(LeastSquares, AgreesWithLineFitIncludingCovariance) {
  const std::vector<double> x = {0, 1, 2, 3};
  const std::vector<double> y = {0, 2, 1, 3};
  Matrix a(4, 2);
  for (std::size_t i = 0; i < 4; ++i) {
    a(i, 0) = x[i];
    a(i, 1) = 1.0;
  }
  const auto result = solve_least_squares(a, y);
  const LineFit fit = fit_line(x, y);
  EXPECT_NEAR_RELATIVE(result.parameters[0], fit.slope, 1e-13);
  EXPECT_NEAR_RELATIVE(result.parameters[1], fit.intercept, 1e-13);
  EXPECT_NEAR_RELATIVE(result.standard_error(0), fit.slope_standard_error, 1e-12);
  EXPECT_NEAR_RELATIVE(result.standard_error(1), fit.intercept_standard_error, 1e-12);
  EXPECT_EQ(result.degrees_of_freedom, 2u);
  EXPECT_EQ(result.rank, 2u);
}

// The variance a + b x² fitted to e_j² / (1 - h_j) (8 rounds of least squares weighted by 1/V²),
// then the slope's and the intercept's errors through it: numpy's lstsq of the same steps gives
// a = 0.0176047, b = 1.20886e-3 and the values below. Points whose scatter grows with x, so both a
// and b are positive.
TEST(FitLine, HeteroscedasticStandardErrorsByHand) {
  const std::vector<double> x = {-50, -20, -5, 0.5, 5, 20, 50, 100};
  const std::vector<double> y = {-101, -39.5, -10.2, 1.1, 9.9, 40.6, 98.2, 203.5};
  const LineFit fit = fit_line(x, y, true);
  EXPECT_NEAR_RELATIVE(fit.slope, fit_line(x, y).slope, 1e-15);
  EXPECT_NEAR_RELATIVE(fit.slope_standard_error, 0.02266258783144189, 1e-10);
  EXPECT_NEAR_RELATIVE(fit.intercept_standard_error, 0.4173781219040717, 1e-10);
  // Scatter that does not grow with x: b = 0, and the errors are the pooled ones.
  const std::vector<double> flat_x = {0, 1, 2, 3};
  const std::vector<double> flat_y = {0, 2, 1, 3};
  EXPECT_NEAR_RELATIVE(fit_line(flat_x, flat_y, true).slope_standard_error, std::sqrt(0.18), 1e-12);
}

// The design of a slope over time and an offset, at samples 0, 1/m, ... (m samples).
Matrix slope_over_time(std::size_t m) {
  Matrix design(m, 2);
  for (std::size_t t = 0; t < m; ++t) {
    design(t, 0) = static_cast<double>(t) / static_cast<double>(m);
    design(t, 1) = 1.0;
  }
  return design;
}

// How often a slope over time, fitted to `samples` errors of an AR(1) drift of unit variance and
// persistence phi plus white noise of sigma `white`, lies within its standard error of the truth.
double slope_coverage(std::size_t samples, double phi, double white, int trials, bool correlated,
                      std::mt19937_64& random) {
  const Matrix design = slope_over_time(samples);
  std::normal_distribution<double> normal(0.0, 1.0);
  LeastSquaresOptions options;
  options.serially_correlated = correlated;
  int within = 0;
  for (int trial = 0; trial < trials; ++trial) {
    std::vector<double> y(samples);
    double drift = normal(random);
    for (std::size_t t = 0; t < samples; ++t) {
      drift = phi * drift + std::sqrt(1.0 - phi * phi) * normal(random);
      y[t] = 2.0 * design(t, 0) + 1.0 + drift + (white > 0.0 ? white * normal(random) : 0.0);
    }
    const LeastSquaresResult fit = solve_least_squares(design, y, options);
    within += std::abs(fit.parameters[0] - 2.0) <= fit.standard_error(0) ? 1 : 0;
  }
  return within / double(trials);
}

// A slope over time under AR(1) errors of correlation 0.8 from sample to sample (a drift of a few
// samples' memory), 1000 trials of 400 samples: the white-noise covariance holds the truth within
// 1 sigma in about 35 % of trials; serially_correlated in about two thirds. On white errors it
// stays the white one (the test for correlation passes it in 2.5 % of trials, and only widens it).
TEST(LeastSquares, SeriallyCorrelatedCovarianceCoversTheTruth) {
  std::mt19937_64 random(1987);
  EXPECT_LT(slope_coverage(400, 0.8, 0.0, 1000, false, random), 0.45);
  EXPECT_NEAR(slope_coverage(400, 0.8, 0.0, 1000, true, random), 0.683, 0.06);
  EXPECT_NEAR(slope_coverage(400, 0.0, 0.0, 1000, true, random), 0.683, 0.04);
}

// A drift under white noise (a gyro's record): the lag-1 correlation is the drift's persistence
// diluted by the white variance, and prewhitening by it alone held the slope within ±1σ in 28 % of
// these trials (51 % with a Newey-West bandwidth from the persistence instead). White noise plus
// AR(1), its persistence and variance from lags 1 and 2, gives the covariance.
TEST(LeastSquares, ADriftUnderWhiteNoiseIsCounted) {
  std::mt19937_64 random(2026);
  // A correlation time of 50 samples under white noise of three times the drift's sigma.
  EXPECT_NEAR(slope_coverage(4000, 0.98, 3.0, 400, true, random), 0.683, 0.06);
}

// Relative variances keep the unweighted estimate and give its covariance through them, the common
// factor c = RSS / Σ (1 - h_i) v_i: numpy's sandwich of the same line gives the values below.
TEST(LeastSquares, RelativeVariancesGiveTheUnweightedFitsCovariance) {
  const std::vector<double> x = {0, 1, 2, 3, 4};
  const std::vector<double> y = {0.1, 1.3, 1.8, 3.4, 3.7};
  Matrix design(5, 2);
  for (std::size_t i = 0; i < 5; ++i) {
    design(i, 0) = x[i];
    design(i, 1) = 1.0;
  }
  LeastSquaresOptions options;
  options.relative_variances = {1, 2, 1, 2, 1};
  const LeastSquaresResult fit = solve_least_squares(design, y, options);
  EXPECT_NEAR_RELATIVE(fit.parameters[0], solve_least_squares(design, y).parameters[0], 1e-14);
  EXPECT_NEAR_RELATIVE(fit.covariance(0, 0), 0.008809090909090905, 1e-12);
  EXPECT_NEAR_RELATIVE(fit.covariance(1, 1), 0.055790909090909065, 1e-12);
  options.weights = {1, 1, 1, 1, 1};
  EXPECT_THROW(solve_least_squares(design, y, options), Error);
}

TEST(LeastSquares, RankDeficiencyNamesTheParameter) {
  // Third column = first + second: "c" cannot be told from the others.
  Matrix a(4, 3);
  for (std::size_t i = 0; i < 4; ++i) {
    a(i, 0) = static_cast<double>(i);
    a(i, 1) = 1.0;
    a(i, 2) = static_cast<double>(i) + 1.0;
  }
  const std::vector<double> y = {1, 2, 3, 4};
  LeastSquaresOptions options;
  options.parameter_names = {"a", "b", "c"};
  try {
    solve_least_squares(a, y, options);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("cannot identify"));
  }
  options.require_full_rank = false;
  const auto result = solve_least_squares(a, y, options);
  EXPECT_EQ(result.rank, 2u);
  EXPECT_EQ(result.unidentifiable.size(), 1u);
}

TEST(LeastSquares, WeightsActAsRepeatedObservations) {
  // Weight 2 on a point equals the point given twice.
  Matrix a(3, 2);
  Matrix b(4, 2);
  const std::vector<double> x = {0, 1, 2};
  const std::vector<double> y = {0.0, 1.5, 1.9};
  for (std::size_t i = 0; i < 3; ++i) {
    a(i, 0) = x[i];
    a(i, 1) = 1.0;
    b(i, 0) = x[i];
    b(i, 1) = 1.0;
  }
  b(3, 0) = x[2];
  b(3, 1) = 1.0;
  LeastSquaresOptions weighted;
  weighted.weights = {1.0, 1.0, 2.0};
  const auto w = solve_least_squares(a, y, weighted);
  const std::vector<double> y4 = {0.0, 1.5, 1.9, 1.9};
  const auto r = solve_least_squares(b, y4);
  EXPECT_NEAR_RELATIVE(w.parameters[0], r.parameters[0], 1e-13);
  EXPECT_NEAR_RELATIVE(w.parameters[1], r.parameters[1], 1e-13);
}

// HC3 by hand for the mean of 1, 2, 4, 7 (design a column of ones, leverage 1/4 each): residuals
// -2.5, -1.5, 0.5, 3.5, so the variance is sum e^2 / (1 - 1/4)^2 / 4^2 = 21 / 0.5625 / 16, against
// the classical s^2 / n = 7 / 4.
TEST(LeastSquares, HeteroscedasticCovarianceByHand) {
  Matrix design(4, 1);
  for (std::size_t i = 0; i < 4; ++i) design(i, 0) = 1.0;
  const std::vector<double> y = {1.0, 2.0, 4.0, 7.0};
  EXPECT_NEAR(solve_least_squares(design, y).covariance(0, 0), 7.0 / 4.0, 1e-12);
  LeastSquaresOptions options;
  options.heteroscedastic = true;
  const LeastSquaresResult fit = solve_least_squares(design, y, options);
  EXPECT_NEAR(fit.parameters[0], 3.5, 1e-12);
  EXPECT_NEAR(fit.covariance(0, 0), 21.0 / 0.5625 / 16.0, 1e-12);
}

TEST(Statistics, StandardDeviationSurvivesLargeOffset) {
  // 1, 2, 3, 4 has sample standard deviation sqrt(5/3); add 1e12 to every value.
  const std::vector<double> values = {1e12 + 1, 1e12 + 2, 1e12 + 3, 1e12 + 4};
  EXPECT_NEAR_RELATIVE(sample_standard_deviation(values), std::sqrt(5.0 / 3.0), 1e-12);
}

TEST(Statistics, WindowMeansDropThePartialWindow) {
  const std::vector<double> values = {1, 3, 5, 7, 9};
  const auto means = window_means(values, 2);
  ASSERT_EQ(means.size(), 2u);
  EXPECT_EQ(means[0], 2.0);
  EXPECT_EQ(means[1], 6.0);
  EXPECT_THROW(window_means(values, 6), Error);
  EXPECT_THROW(window_means(values, 0), Error);
}

}  // namespace
}  // namespace inertest
