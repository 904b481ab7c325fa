#include "inertest/procedures/scale_factor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>

#include "inertest/core/error.h"
#include "inertest/io/text_table.h"
#include "inertest/numerics/least_squares.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;

std::vector<ScaleFactorPoint> points(std::initializer_list<std::pair<double, double>> pairs) {
  std::vector<ScaleFactorPoint> result;
  for (const auto& [rate, output] : pairs) result.push_back({rate, output});
  return result;
}

TEST(ScaleFactor, HandComputedCase) {
  // F̄s = 1, F̄e = 3, so F̄r = 2 (eq. 2); after subtraction F = -4.1, -2.0, 2.1, 4.0 at -2,-1,1,2.
  // Eq. (5): sum x = 0, sum x^2 = 10, sum xF = 20.3 -> K = 2.03; eq. (6): F0 = 0.
  // Eq. (8): F̂ - F = 0.04, -0.03, -0.07, 0.06 over |Fm| = 4.1 -> Kn = 0.07/4.1.
  // K(+) = (4.0 - 2.1)/1 = 1.9, K(-) = (-2.0 + 4.1)/1 = 2.1, K̄ = 2.0 -> Ka = 0.1 (eqs. 10-11).
  const auto data = points({{0, 1.0}, {-2, -2.1}, {-1, 0.0}, {1, 4.1}, {2, 6.0}, {0, 3.0}});
  const ScaleFactorResult r = scale_factor(data);
  EXPECT_NEAR_RELATIVE(r.scale_factor.value, 2.03, 1e-14);
  EXPECT_NEAR(r.zero_offset.value, 0.0, 1e-14);
  EXPECT_NEAR_RELATIVE(r.nonlinearity.value, 0.07 / 4.1 * 1e6, 1e-12);
  EXPECT_NEAR_RELATIVE(r.scale_factor_positive.value, 1.9, 1e-14);
  EXPECT_NEAR_RELATIVE(r.scale_factor_negative.value, 2.1, 1e-14);
  EXPECT_NEAR_RELATIVE(r.asymmetry.value, 1e5, 1e-12);
  EXPECT_EQ(r.static_output_start.value, 1.0);
  EXPECT_EQ(r.static_output_end.value, 3.0);
  ASSERT_EQ(r.nonlinearity_curve.size(), 4u);
  EXPECT_NEAR_RELATIVE(r.nonlinearity_curve[0].deviation, 0.04 / 4.1 * 1e6, 1e-11);
  EXPECT_NEAR_RELATIVE(r.nonlinearity_curve[2].deviation, -0.07 / 4.1 * 1e6, 1e-11);
  EXPECT_EQ(r.warnings.size(), 2u);  // 2 rates each way, the standard asks for 11
}

// A stop between the directions (a zero rate inside the sequence) is no test point: the figures are
// those of the hand case without it, and the point is named in a warning.
TEST(ScaleFactor, AZeroRateInsideTheSequenceIsLeftOutAndSaid) {
  const auto data = points({{0, 1.0}, {-2, -2.1}, {-1, 0.0}, {0, 2.5}, {1, 4.1}, {2, 6.0}, {0, 3.0}});
  const ScaleFactorResult r = scale_factor(data);
  EXPECT_NEAR_RELATIVE(r.scale_factor.value, 2.03, 1e-14);
  EXPECT_NEAR_RELATIVE(r.nonlinearity.value, 0.07 / 4.1 * 1e6, 1e-12);
  EXPECT_EQ(r.nonlinearity_curve.size(), 4u);
  ASSERT_EQ(r.warnings.size(), 3u);
  EXPECT_THAT(r.warnings[2], HasSubstr("test point 4 (counted from 1 among the test points, not the file's lines) is at "
                                       "zero rate inside the sequence and left out of the fit"));
}

TEST(ScaleFactor, ExactLineHasNoNonlinearityOrAsymmetry) {
  std::vector<ScaleFactorPoint> data = {{0, 7.0}};
  for (double rate : {1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 300.0, 400.0, 500.0}) {
    data.push_back({rate, 7.0 + 1234.5 * rate});
    data.push_back({-rate, 7.0 - 1234.5 * rate});
  }
  data.push_back({0, 7.0});
  ScaleFactorOptions options;
  options.output_unit = "pulse/s";
  const ScaleFactorResult r = scale_factor(data, options);
  EXPECT_NEAR_RELATIVE(r.scale_factor.value, 1234.5, 1e-13);
  EXPECT_EQ(r.scale_factor.unit, "pulse/s/(deg/s)");
  EXPECT_NEAR(r.nonlinearity.value, 0.0, 1e-6);
  EXPECT_NEAR(r.asymmetry.value, 0.0, 1e-6);
  EXPECT_TRUE(r.warnings.empty());
}

// Eqs. (1)-(11) written literally as printed (uncentred sums of eq. 5), independent of the
// library's implementation.
struct LiteralStandard {
  double k, f0, kn, ka, k_pos, k_neg;
};

std::pair<double, double> literal_fit(const std::vector<double>& w, const std::vector<double>& f) {
  const double m = static_cast<double>(w.size());
  double sw = 0, sf = 0, swf = 0, sww = 0;
  for (std::size_t j = 0; j < w.size(); ++j) {
    sw += w[j];
    sf += f[j];
    swf += w[j] * f[j];
    sww += w[j] * w[j];
  }
  const double k = (swf - sw * sf / m) / (sww - sw * sw / m);  // eq. (5)
  return {k, sf / m - k / m * sw};                             // eq. (6)
}

LiteralStandard literal_standard(const std::vector<ScaleFactorPoint>& data) {
  std::size_t first = 0;
  while (data[first].rate == 0) ++first;
  std::size_t last = data.size() - 1;
  while (data[last].rate == 0) --last;
  double fs = 0, fe = 0;
  for (std::size_t i = 0; i < first; ++i) fs += data[i].output / static_cast<double>(first);
  for (std::size_t i = last + 1; i < data.size(); ++i) fe += data[i].output / static_cast<double>(data.size() - 1 - last);
  const double fr = (fs + fe) / 2;  // eq. (2)
  std::vector<double> w, f, wp, fp, wn, fn;
  for (std::size_t i = first; i <= last; ++i) {
    w.push_back(data[i].rate);
    f.push_back(data[i].output - fr);  // eq. (3)
    (data[i].rate > 0 ? wp : wn).push_back(data[i].rate);
    (data[i].rate > 0 ? fp : fn).push_back(data[i].output - fr);
  }
  const auto [k, f0] = literal_fit(w, f);
  double fm = 0, kn = 0;
  for (double v : f) fm = std::max(fm, std::abs(v));
  for (std::size_t j = 0; j < w.size(); ++j) kn = std::max(kn, std::abs((k * w[j] + f0 - f[j]) / fm));  // eqs. (7)-(9)
  const double kp = literal_fit(wp, fp).first;
  const double kneg = literal_fit(wn, fn).first;
  const double ka = std::abs(kp - kneg) / ((kp + kneg) / 2);  // eqs. (10)-(11)
  return {k, f0, kn * 1e6, ka * 1e6, kp, kneg};
}

TEST(ScaleFactor, AgreesWithTheLiteralEquationsOnTheBundledExample) {
  TextTableOptions read;
  read.columns = {ColumnSelector{"rate"}, ColumnSelector{"output"}};
  const TextTable table = read_text_table(testing::source_path("examples/scale_factor/points.csv"), read);
  std::vector<ScaleFactorPoint> data;
  for (std::size_t i = 0; i < table.rows(); ++i) data.push_back({table.columns[0][i], table.columns[1][i]});
  const ScaleFactorResult r = scale_factor(data);
  const LiteralStandard expected = literal_standard(data);
  EXPECT_NEAR_RELATIVE(r.scale_factor.value, expected.k, 1e-9);
  EXPECT_NEAR_RELATIVE(r.zero_offset.value, expected.f0, 1e-9);
  EXPECT_NEAR_RELATIVE(r.nonlinearity.value, expected.kn, 1e-9);
  EXPECT_NEAR_RELATIVE(r.asymmetry.value, expected.ka, 1e-9);
  EXPECT_NEAR_RELATIVE(r.scale_factor_positive.value, expected.k_pos, 1e-9);
  EXPECT_NEAR_RELATIVE(r.scale_factor_negative.value, expected.k_neg, 1e-9);
}

TEST(ScaleFactor, SyntheticQuadraticNonlinearityFollowsAnalytically) {
  // F = K w + c w|w| on symmetric rates: odd-symmetric c w|w| has zero intercept and its
  // least-squares slope is c sum|w|^3 / sum w^2, so the deviation at every point is known.
  const double k = 100.0;
  const double c = 1e-3;
  const std::vector<double> rates = {1, 2, 4, 8, 16};
  std::vector<ScaleFactorPoint> data = {{0, 0.0}};
  for (double w : rates) {
    data.push_back({w, k * w + c * w * w});
    data.push_back({-w, -k * w - c * w * w});
  }
  data.push_back({0, 0.0});
  double s2 = 0, s3 = 0;
  for (double w : rates) {
    s2 += 2 * w * w;
    s3 += 2 * w * w * w;
  }
  const double slope = k + c * s3 / s2;
  const ScaleFactorResult r = scale_factor(data);
  EXPECT_NEAR_RELATIVE(r.scale_factor.value, slope, 1e-12);
  const double fm = k * 16 + c * 256;
  double kn = 0;
  for (double w : rates) kn = std::max(kn, std::abs(slope * w - (k * w + c * w * w)) / fm);
  EXPECT_NEAR_RELATIVE(r.nonlinearity.value, kn * 1e6, 1e-9);
  EXPECT_NEAR(r.asymmetry.value, 0.0, 1e-6);
}

// Monte Carlo coverage of K's and F0's ±1σ over 1000 simulated tests (11 rates each way, 2 static
// points at each end), with noise of one size at every point and with noise growing with the rate
// (0.5 + 5 ppm of the output, a table's rate error). One residual variance for all held K in 35 % of
// trials under the second; F0's, without the static runs' error, in 28 % under the first; K(+)'s,
// its spread fitted from its own direction's points, in 59 % under the second.
struct CoverageCase {
  const char* name;
  double constant_noise;
  double relative_noise;
  double asymmetry_ppm = 0.0;  // K(+) and K(-) this far apart
  double cubic_ppm = 0.0;      // a cubic nonlinearity, this much of the full-scale output at full scale
  // The coverage's upper end: a gyro's shape that the test misses in a trial counts as noise there
  // (0.75-0.82 measured over 1000 trials for these; 1.00 before the shape was taken out).
  double most = 0.743;
};

class ScaleFactorCoverage : public ::testing::TestWithParam<CoverageCase> {};

TEST_P(ScaleFactorCoverage, OneSigmaHoldsTheTruthInAboutTwoThirdsOfTrials) {
  const double k = 5000.0;  // pulse/s per deg/s; F0 = 0: the bias is the same at rest and turning
  const std::vector<double> magnitudes = {1, 2, 5, 10, 20, 50, 100, 150, 200, 300, 400};
  std::mt19937_64 random(20261127);
  std::normal_distribution<double> unit(0.0, 1.0);
  constexpr int kTrials = 1000;
  int k_within = 0;
  int f0_within = 0;
  int k_positive_within = 0;
  // The gyro's output without noise; the truth is what the procedure gives of it (the asymmetry and
  // the nonlinearity are the gyro's, the same in every test: no uncertainty of K is theirs).
  const CoverageCase& c = GetParam();
  const auto output = [&](double rate) {
    const double asymmetric = k * (1.0 + (rate > 0.0 ? 0.5 : -0.5) * c.asymmetry_ppm * 1e-6) * rate;
    return 10.0 + asymmetric + c.cubic_ppm * 1e-6 * k * 400.0 * std::pow(rate / 400.0, 3);
  };
  const auto test = [&](const auto& reading) {
    std::vector<ScaleFactorPoint> data = {{0, reading(0)}, {0, reading(0)}};
    for (double sign : {1.0, -1.0}) {
      for (double w : magnitudes) data.push_back({sign * w, reading(sign * w)});
    }
    data.insert(data.end(), {{0, reading(0)}, {0, reading(0)}});
    return scale_factor(data);
  };
  const ScaleFactorResult truth = test(output);
  for (int trial = 0; trial < kTrials; ++trial) {
    const ScaleFactorResult r = test([&](double rate) {
      return output(rate) + (c.constant_noise + c.relative_noise * k * std::abs(rate)) * unit(random);
    });
    k_within += std::abs(r.scale_factor.value - truth.scale_factor.value) <= r.scale_factor.uncertainty.value() ? 1 : 0;
    f0_within += std::abs(r.zero_offset.value - truth.zero_offset.value) <= r.zero_offset.uncertainty.value() ? 1 : 0;
    k_positive_within += std::abs(r.scale_factor_positive.value - truth.scale_factor_positive.value) <=
                                 r.scale_factor_positive.uncertainty.value()
                             ? 1
                             : 0;
  }
  // 68.3 % expected; the binomial spread of 1000 trials is 1.5 %, HC3's own scatter widens it.
  for (const auto& [name, within] : {std::pair{"K", k_within}, std::pair{"F0", f0_within}, std::pair{"K+", k_positive_within}}) {
    EXPECT_GE(within / double(kTrials), 0.683 - 0.06) << c.name << " " << name;
    EXPECT_LE(within / double(kTrials), c.most) << c.name << " " << name;
  }
}

// A gyro of 2000 ppm asymmetry (K(+) 100.1, K(-) 99.9): K(+)'s error is its own line's, not the
// misfit of the line through both directions, which stated it 24 times too large.
TEST(ScaleFactor, AsymmetryIsNoNoiseInKPositivesError) {
  std::vector<ScaleFactorPoint> data = {{0, 0.3}, {0, -0.2}};
  const double wobble[] = {0.4, -0.3, 0.1, -0.5, 0.2, 0.3, -0.1, -0.4, 0.5, -0.2, 0.0};
  const std::vector<double> magnitudes = {1, 2, 5, 10, 20, 50, 100, 150, 200, 300, 400};
  for (std::size_t i = 0; i < magnitudes.size(); ++i) {
    data.push_back({magnitudes[i], 100.1 * magnitudes[i] + wobble[i]});
    data.push_back({-magnitudes[i], -99.9 * magnitudes[i] - wobble[10 - i]});
  }
  data.insert(data.end(), {{0, 0.1}, {0, -0.3}});
  const ScaleFactorResult r = scale_factor(data);
  std::vector<double> x, y;
  for (const auto& p : data) {
    if (p.rate > 0) x.push_back(p.rate), y.push_back(p.output);
  }
  const double own = fit_line(x, y).slope_standard_error;  // the positive line's own, one variance
  EXPECT_LT(r.scale_factor_positive.uncertainty.value(), 2.0 * own);
  EXPECT_GT(r.scale_factor_positive.uncertainty.value(), 0.5 * own);
}

INSTANTIATE_TEST_SUITE_P(Noise, ScaleFactorCoverage,
                         ::testing::Values(CoverageCase{"constant", 2.0, 0.0}, CoverageCase{"growing", 0.5, 5e-6},
                                           // a gyro's own shape: it was counted as noise (coverage 100 %)
                                           CoverageCase{"asymmetric", 2.0, 0.0, 6.0, 0.0, 0.85},
                                           CoverageCase{"curved", 2.0, 0.0, 6.0, 8.0, 0.85}),
                         [](const auto& test) { return std::string(test.param.name); });

struct BadCase {
  const char* name;
  std::vector<ScaleFactorPoint> data;
  const char* message;
};

class ScaleFactorErrors : public ::testing::TestWithParam<BadCase> {};

TEST_P(ScaleFactorErrors, SayWhatIsMissing) {
  try {
    scale_factor(GetParam().data);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(GetParam().message));
  }
}

INSTANTIATE_TEST_SUITE_P(
    ScaleFactor, ScaleFactorErrors,
    ::testing::Values(
        BadCase{"no_start_static", points({{-1, -1}, {-2, -2}, {1, 1}, {2, 2}, {0, 0}}), "static run at the start"},
        BadCase{"no_end_static", points({{0, 0}, {-1, -1}, {-2, -2}, {1, 1}, {2, 2}}), "static run at the end"},
        BadCase{"not_bracketing_zero", points({{0, 0}, {1, 1}, {2, 2}, {3, 3}, {0, 0}}), "0 negative rate(s)"},
        BadCase{"one_negative", points({{0, 0}, {-1, -1}, {1, 1}, {2, 2}, {0, 0}}), "1 negative rate(s)"},
        BadCase{"all_static", points({{0, 0}, {0, 0}}), "no nonzero rate"},
        BadCase{"no_response", points({{0, 0}, {-1, 5}, {-2, 5}, {1, 5}, {2, 5}, {0, 5}}), "scale factor is zero"},
        // F = |rate|: K(+) = 1, K(-) = -1, K-bar of eq. (11) = 0 (was inf ppm).
        BadCase{"opposite_slopes", points({{0, 0}, {1, 1}, {2, 2}, {3, 3}, {-1, 1}, {-2, 2}, {0, 0}}),
                "K(+) = 1 and K(-) = -1 have opposite signs"},
        // K(+) = 1, K(-) = -0.5: opposite signs, an asymmetry of 600 % would mean nothing.
        BadCase{"opposite_signs", points({{0, 0}, {1, 1}, {2, 2}, {3, 3}, {-2, 1}, {-4, 2}, {0, 0}}),
                "have opposite signs"}),
    testing::NameOfParam());

TEST(ScaleFactor, OptionsAreValidated) {
  const auto data = points({{0, 1.0}, {-2, -2.1}, {-1, 0.0}, {1, 4.1}, {2, 6.0}, {0, 3.0}});
  ScaleFactorOptions options;
  options.rate_unit = "deg";
  EXPECT_THROW(scale_factor(data, options), Error);
  options.rate_unit = "deg/s";
  options.output_unit = "bananas";
  EXPECT_THROW(scale_factor(data, options), Error);
}

TEST(ScaleFactor, JsonHasEveryFigureWithItsUnit) {
  const auto data = points({{0, 1.0}, {-2, -2.1}, {-1, 0.0}, {1, 4.1}, {2, 6.0}, {0, 3.0}});
  const ScaleFactorResult result = scale_factor(data);
  const nlohmann::json json = scale_factor_spec().fields_of(&result);
  for (const char* key : {"scale_factor", "zero_offset", "nonlinearity", "asymmetry", "scale_factor_positive",
                          "scale_factor_negative"}) {
    ASSERT_TRUE(json.contains(key)) << key;
    EXPECT_TRUE(json[key].contains("value")) << key;
    EXPECT_TRUE(json[key].contains("unit")) << key;
  }
  EXPECT_EQ(json["nonlinearity"]["unit"], "ppm");
  ASSERT_EQ(json["nonlinearity_curve"].size(), 4u);
  EXPECT_EQ(json["nonlinearity_curve"][0]["rate"]["unit"], "deg/s");
  EXPECT_EQ(json["nonlinearity_curve"][0]["rate"]["value"], -2.0);
}

}  // namespace
}  // namespace inertest
