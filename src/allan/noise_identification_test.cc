#include "inertest/allan/noise_identification.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <span>
#include <vector>

#include "inertest/allan/allan.h"
#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

TEST(Lag1Sums, HandCase) {
  // 1 2 3 4: mean 2.5, deviations -1.5 -0.5 0.5 1.5; sum of squares 5, lag-1 products 0.75 - 0.25 + 0.75.
  Lag1Sums sums;
  for (double w : {1.0, 2.0, 3.0, 4.0}) sums.add(w);
  EXPECT_EQ(sums.count(), 4u);
  EXPECT_NEAR(sums.autocorrelation(), 1.25 / 5.0, 1e-15);
  EXPECT_NEAR(sums.sample_variance(), 5.0 / 3.0, 1e-15);
  EXPECT_NEAR(sums.mean_square(), 30.0 / 4.0, 1e-15);  // about zero: (1 + 4 + 9 + 16) / 4
  // A large offset changes nothing (the sums are kept relative to the first value).
  Lag1Sums shifted;
  for (double w : {1.0, 2.0, 3.0, 4.0}) shifted.add(w + 1e12);
  EXPECT_NEAR(shifted.autocorrelation(), 0.25, 1e-15);
  Lag1Sums negative;  // -2 1 3: (4 + 1 + 9) / 3, the first value not 0
  for (double w : {-2.0, 1.0, 3.0}) negative.add(w);
  EXPECT_NEAR(negative.mean_square(), 14.0 / 3.0, 1e-15);
  // Too short or constant: no autocorrelation.
  Lag1Sums one;
  one.add(3.0);
  EXPECT_TRUE(std::isnan(one.autocorrelation()));
  EXPECT_NEAR(one.mean_square(), 9.0, 1e-15);
  EXPECT_TRUE(std::isnan(Lag1Sums{}.mean_square()));
  Lag1Sums constant;
  for (int i = 0; i < 5; ++i) constant.add(2.0);
  EXPECT_TRUE(std::isnan(constant.autocorrelation()));
}

TEST(AveragedFrequencySeries, KeepsTheDifferences) {
  // 1 2 4 7 -> first differences 1 2 3 -> second differences 1 1.
  AveragedFrequencySeries series;
  for (double v : {1.0, 2.0, 4.0, 7.0}) series.add(v);
  EXPECT_EQ(series.series(0).count(), 4u);
  EXPECT_EQ(series.series(1).count(), 3u);
  EXPECT_EQ(series.series(2).count(), 2u);
  EXPECT_NEAR(series.series(1).sample_variance(), 1.0, 1e-15);  // 1 2 3
  EXPECT_NEAR(series.series(1).autocorrelation(), 0.0, 1e-15);  // (-1)(0) + (0)(1)
  EXPECT_NEAR(series.series(2).sample_variance(), 0.0, 1e-15);
}

// The engine's averages are the non-overlapping means of the rate less the offset, in the streaming
// pass and in the second pass alike.
TEST(AveragedFrequencySeries, EngineAveragesAreTheBlockMeans) {
  const std::size_t n = 50000;
  const std::vector<double> y = testing::uniform_noise(7.0, n);
  for (std::size_t ring_limit : {std::size_t{0}, std::size_t{40000}}) {
    AllanEngineOptions options;
    options.averaging_factors = {1, 10, 999, 16000};
    options.estimators = EstimatorSet::parse("oadev");
    options.ring_capacity_limit = ring_limit;
    options.block_size = 4096;
    AllanEngine engine(n, 7.0, options);
    engine.push(y);
    const auto sums = engine.finish([&](std::size_t first, std::span<double> out) {
      std::copy_n(y.begin() + static_cast<std::ptrdiff_t>(first), out.size(), out.begin());
    });
    if (ring_limit != 0) {
      EXPECT_GT(engine.deferred_factor_count(), 0u);
    }
    for (const AllanSums& s : sums) {
      const std::size_t m = s.averaging_factor;
      Lag1Sums direct;
      for (std::size_t j = 0; j + m <= n; j += m) {
        double total = 0.0;
        for (std::size_t i = j; i < j + m; ++i) total += y[i] - 7.0;
        direct.add(total / static_cast<double>(m));
      }
      const Lag1Sums& streamed = s.averages.series(0);
      ASSERT_EQ(streamed.count(), n / m) << m;
      EXPECT_NEAR_RELATIVE(streamed.sample_variance(), direct.sample_variance(), 1e-9) << m;
      EXPECT_NEAR(streamed.autocorrelation(), direct.autocorrelation(), 1e-9) << m;
    }
  }
}

// The bounded prefix: at m = 1 of 2^16 + 5000 samples the engine stops at 2^16 averages, whose
// sums are those of the first 2^16 samples.
TEST(AveragedFrequencySeries, EngineKeepsABoundedPrefix) {
  const std::size_t cap = AveragedFrequencySeries::kMaximumAverages;
  const std::vector<double> y = testing::uniform_noise(0.0, cap + 5000);
  AllanEngineOptions options;
  options.averaging_factors = {1, 64};
  options.estimators = EstimatorSet::parse("oadev");
  AllanEngine engine(y.size(), 0.0, options);
  engine.push(y);
  const auto sums = engine.finish();
  EXPECT_EQ(sums[0].averages.series(0).count(), cap);
  EXPECT_EQ(sums[1].averages.series(0).count(), y.size() / 64);
  AveragedFrequencySeries prefix;
  for (std::size_t i = 0; i < cap + 1; ++i) prefix.add(y[i]);
  EXPECT_EQ(prefix.series(0).count(), cap);
  EXPECT_NEAR_RELATIVE(sums[0].averages.series(0).sample_variance(), prefix.series(0).sample_variance(), 1e-12);
}

TEST(B1Ratio, ExpectationsAndTheirBoundaries) {
  // Howe et al. (2000) Table 3 at N = 16.
  EXPECT_DOUBLE_EQ(b1_expected(16, 2), 16.0 * 17.0 / 6.0);
  EXPECT_DOUBLE_EQ(b1_expected(16, 1), 8.0);
  EXPECT_DOUBLE_EQ(b1_expected(16, 0), 16.0 * std::log(16.0) / (30.0 * std::log(2.0)));  // 32/15
  EXPECT_DOUBLE_EQ(b1_expected(16, -1), 1.0);
  EXPECT_DOUBLE_EQ(b1_expected(16, -2), 255.0 / 360.0);
  for (double n : {5.0, 16.0, 1000.0}) {
    for (int mu = -2; mu <= 2; ++mu) EXPECT_EQ(b1_mu(b1_expected(n, mu), n), mu) << n << " " << mu;
  }
  // Between white FM (1) and flicker FM (32/15) the boundary is their geometric mean.
  EXPECT_EQ(b1_mu(std::sqrt(32.0 / 15.0) * 1.001, 16), 0);
  EXPECT_EQ(b1_mu(std::sqrt(32.0 / 15.0) * 0.999, 16), -1);
  EXPECT_THROW(b1_expected(16, 3), Error);
}

// Records whose noise follows from how they are made: white rate (white FM), its running sum
// (random walk FM) and its first difference (white PM). Where 30 averages or more remain the lag-1
// autocorrelation is the method; with 300 or more (r1 then scatters by 1/sqrt(300) = 0.06, a
// quarter of the 0.25 that separates two types) it names the type, for every estimator.
std::vector<double> white_rate(std::size_t n) { return testing::uniform_noise(0.0, n); }

std::vector<double> random_walk_rate(std::size_t n) {
  std::vector<double> y = testing::uniform_noise(0.0, n);
  for (std::size_t i = 1; i < n; ++i) y[i] += y[i - 1];
  return y;
}

std::vector<double> white_phase_rate(std::size_t n) {
  const std::vector<double> x = testing::uniform_noise(0.0, n + 1);
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) y[i] = x[i + 1] - x[i];
  return y;
}

void expect_lag1_identifies(const std::vector<double>& y, NoiseType expected) {
  AllanOptions options;
  options.sample_rate_hz = 1.0;
  const AllanResult result = allan_variance(y, options);
  std::size_t checked = 0;
  for (const auto& [estimator, curve] : result.curves) {
    for (std::size_t i = 0; i < curve.values.size(); ++i) {
      if (y.size() / result.averaging_factors[i] < kLag1MinimumAverages) {
        EXPECT_NE(curve.noise_methods[i], NoiseIdentificationMethod::kLag1Autocorrelation);
        continue;
      }
      EXPECT_EQ(curve.noise_methods[i], NoiseIdentificationMethod::kLag1Autocorrelation);
      if (y.size() / result.averaging_factors[i] < 10 * kLag1MinimumAverages) continue;
      EXPECT_EQ(curve.noise_types[i], expected)
          << estimator_name(estimator) << " m=" << result.averaging_factors[i];
      ++checked;
    }
  }
  EXPECT_GT(checked, 40u);
  const nlohmann::json json = result.to_json();
  EXPECT_EQ(json["alpha"][0], static_cast<int>(expected));
  EXPECT_EQ(json["oadev"]["alpha"][0], static_cast<int>(expected));
  EXPECT_EQ(json["oadev"]["noise_type"][0], noise_type_name(expected));
  EXPECT_EQ(json["oadev"]["noise_identification"][0], "lag1_autocorrelation");
}

TEST(Lag1NoiseIdentification, WhiteFrequency) { expect_lag1_identifies(white_rate(1 << 16), NoiseType::kWhiteFrequency); }

TEST(Lag1NoiseIdentification, RandomWalkFrequency) {
  expect_lag1_identifies(random_walk_rate(1 << 16), NoiseType::kRandomWalkFrequency);
}

TEST(Lag1NoiseIdentification, WhitePhase) { expect_lag1_identifies(white_phase_rate(1 << 16), NoiseType::kWhitePhase); }

// Riley & Greenhall's estimate on the averages themselves: white FM has r1 = 0 (p = 0), white PM
// r1 = -1/2 (delta = -1, p = 2), random walk FM needs one difference (p = -2). Over the bounded
// prefix of n = 2^16 averages r1 scatters by 1/sqrt(n); p = -2 delta - 2d with delta = r1 / (1 + r1)
// scatters by 2/sqrt(n) = 0.008 at r1 = 0 and by 2 * 4/sqrt(n) = 0.031 at r1 = -1/2: 3 sigma each.
TEST(Lag1NoiseIdentification, UnroundedEstimates) {
  const auto series_of = [](const std::vector<double>& y) {
    AveragedFrequencySeries series;
    for (double v : y) series.add(v);
    return series;
  };
  EXPECT_NEAR(*lag1_alpha(series_of(white_rate(100000)), 1), 0.0, 0.024);
  EXPECT_NEAR(*lag1_alpha(series_of(white_phase_rate(100000)), 1), 2.0, 0.094);
  EXPECT_NEAR(*lag1_alpha(series_of(random_walk_rate(100000)), 1), -2.0, 0.024);
  EXPECT_FALSE(lag1_alpha(series_of({1.0, 1.0, 1.0}), 1).has_value());
  EXPECT_THROW(lag1_alpha(series_of({1.0, 2.0}), 3), Error);
}

// Fewer than 30 averages: white PM at m = 1024 of 20000 samples (19 averages). B1 is expected at
// 0.70 (Howe et al. Table 3, N = 18), below its boundary with white FM (0.82 for MDEV's N, 0.84
// for ADEV's), but the Allan variance of 18 differences in its denominator scatters by about a
// third, so some records cross it (Stable32 shares this: identify_power_law_noise). Over 40
// records: whenever B1 points to PM, MDEV's R(n) names white PM (its expectation 1/1024 against
// 0.13 for flicker PM); B1 points to PM for most records; the unmodified estimators, which cannot
// tell PM noises apart, report white FM (as Stable32 does) in every record.
TEST(B1NoiseIdentification, RnNamesWhitePhaseForMdevOnly) {
  AllanOptions options;
  options.sample_rate_hz = 1.0;
  options.taus = "1024";
  constexpr int kRecords = 40;
  int phase_noise = 0;
  for (int seed = 0; seed < kRecords; ++seed) {
    std::mt19937_64 generator(static_cast<std::uint64_t>(seed));
    std::normal_distribution<double> normal;
    std::vector<double> y(20000);
    double previous = normal(generator);
    for (double& v : y) {
      const double x = normal(generator);
      v = x - previous;
      previous = x;
    }
    const AllanResult result = allan_variance(y, options);
    const DeviationCurve& mdev = result.curves.at(Estimator::kMdev);
    if (mdev.noise_methods[0] == NoiseIdentificationMethod::kB1RatioAndRn) {
      ++phase_noise;
      EXPECT_EQ(mdev.noise_types[0], NoiseType::kWhitePhase) << "seed " << seed;
    } else {
      EXPECT_EQ(mdev.noise_methods[0], NoiseIdentificationMethod::kB1Ratio) << "seed " << seed;
      EXPECT_EQ(mdev.noise_types[0], NoiseType::kWhiteFrequency) << "seed " << seed;
    }
    for (Estimator e : {Estimator::kAdev, Estimator::kOadev, Estimator::kHdev, Estimator::kOhdev, Estimator::kTotdev}) {
      EXPECT_EQ(result.curves.at(e).noise_methods[0], NoiseIdentificationMethod::kB1Ratio) << estimator_name(e);
      EXPECT_EQ(result.curves.at(e).noise_types[0], NoiseType::kWhiteFrequency) << estimator_name(e) << " seed " << seed;
    }
  }
  RecordProperty("records_b1_points_to_phase_noise", phase_noise);
  EXPECT_GT(phase_noise, kRecords / 2);
}

// The longest averaging time of a run with fewer than 30 averages takes the identification of the
// next shorter one (identify_along_taus, as Stable32); one with more is identified on its own, and
// so is a run of one averaging time.
TEST(NoiseIdentificationAlongTaus, LongestTauWithFewAveragesTakesTheShorterOnes) {
  const std::vector<double> y = random_walk_rate(20000);
  AllanOptions options;
  options.sample_rate_hz = 1.0;
  options.taus = "64,1024";  // 312 and 19 averages
  const AllanResult few = allan_variance(y, options);
  for (const auto& [estimator, curve] : few.curves) {
    EXPECT_EQ(curve.noise_methods[0], NoiseIdentificationMethod::kLag1Autocorrelation) << estimator_name(estimator);
    EXPECT_EQ(curve.noise_methods[1], NoiseIdentificationMethod::kShorterTau) << estimator_name(estimator);
    EXPECT_EQ(curve.noise_types[1], curve.noise_types[0]) << estimator_name(estimator);
  }
  EXPECT_EQ(few.to_json()["oadev"]["noise_identification"][1], "shorter_tau");
  options.taus = "1,64";  // 20000 and 312 averages
  for (const auto& [estimator, curve] : allan_variance(y, options).curves) {
    EXPECT_EQ(curve.noise_methods[1], NoiseIdentificationMethod::kLag1Autocorrelation) << estimator_name(estimator);
  }
  options.taus = "1024";
  for (const auto& [estimator, curve] : allan_variance(y, options).curves) {
    EXPECT_NE(curve.noise_methods[0], NoiseIdentificationMethod::kShorterTau) << estimator_name(estimator);
  }
}

}  // namespace
}  // namespace inertest
