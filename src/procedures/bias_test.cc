#include "inertest/procedures/bias.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <random>

#include "inertest/core/error.h"
#include "inertest/procedures/bias_stability.h"
#include "inertest/procedures/random_walk_normalisation.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

// K = 3600 output units per deg/s makes one output unit one deg/h: the figures read as the output.
constexpr double kUnitScale = 3600.0;

BiasOptions unit_options(double rate_hz, std::vector<double> smoothing, bool random_walk = false) {
  BiasOptions options;
  options.sample_rate_hz = rate_hz;
  options.scale_factor = kUnitScale;
  options.smoothing_s = std::move(smoothing);
  options.random_walk = random_walk;
  return options;
}

// The result as the CLI, plans and Python give it: its JSON object and its text, from the spec.
nlohmann::json json_of(const BiasResult& result) { return procedure_json(bias_spec(), bias_spec().fields_of(&result)); }
std::string text_of(const BiasResult& result) { return procedure_text(bias_spec(), bias_spec().fields_of(&result)); }

TEST(BiasTest, HandComputedSmallRecord) {
  const std::vector<double> output = {1, 2, 3, 4, 5, 6, 7, 8};
  const BiasResult result = bias(output, unit_options(1.0, {2.0, 4.0}));
  EXPECT_DOUBLE_EQ(result.bias.value, 4.5);
  EXPECT_EQ(result.bias.unit, "deg/h");
  ASSERT_EQ(result.bias_stability.size(), 2u);
  // Means of 2 s windows: 1.5, 3.5, 5.5, 7.5; deviations -3, -1, 1, 3; sum of squares 20 over n - 1 = 3.
  EXPECT_EQ(result.bias_stability[0].windows, 4u);
  EXPECT_NEAR(result.bias_stability[0].value.value, std::sqrt(20.0 / 3.0), 1e-14);
  // Means of 4 s windows: 2.5, 6.5; standard deviation sqrt(8).
  EXPECT_NEAR(result.bias_stability[1].value.value, std::sqrt(8.0), 1e-14);
}

TEST(BiasTest, ScaleFactorConvertsToDegreesPerHourWithItsSign) {
  // Output 10 pulse/s at K = -20 pulse/s per deg/s: -0.5 deg/s = -1800 deg/h.
  const std::vector<double> output(10, 10.0);
  BiasOptions options = unit_options(1.0, {1.0});
  options.scale_factor = -20.0;
  EXPECT_DOUBLE_EQ(bias_deg_h(output, options), -1800.0);
  // The stability is a spread: positive whatever the sign of K.
  std::vector<double> alternating = {0, 2, 0, 2};
  EXPECT_NEAR(bias(alternating, options).bias_stability[0].value.value, std::sqrt(4.0 / 3.0) * 180.0, 1e-12);
}

TEST(BiasTest, RecordAlreadyInDegreesPerHour) {
  BiasOptions options = unit_options(1.0, {1.0});
  options.scale_factor = 0.0;
  options.input_in_deg_h = true;
  const std::vector<double> output = {0.5, 1.5};
  EXPECT_DOUBLE_EQ(bias(output, options).bias.value, 1.0);
}

TEST(BiasTest, SquareWaveOfTheWindowLengthGivesAnalyticStability) {
  // b + a·(-1)^floor(i / w): the means of w-sample windows alternate b ± a, so with n windows
  // (n even) the standard deviation is a·sqrt(n / (n - 1)); windows of 2w all average to b.
  const double b = 12.5, a = 0.75, rate = 10.0;
  const std::size_t w = 10, n = 40;
  std::vector<double> output(w * n);
  for (std::size_t i = 0; i < output.size(); ++i) output[i] = b + ((i / w) % 2 == 0 ? a : -a);
  const BiasResult result = bias(output, unit_options(rate, {1.0, 2.0}));
  EXPECT_NEAR(result.bias.value, b, 1e-12);
  EXPECT_NEAR(result.bias_stability[0].value.value, a * std::sqrt(40.0 / 39.0), 1e-12);
  EXPECT_NEAR(result.bias_stability[1].value.value, 0.0, 1e-12);
}

TEST(BiasTest, LargeOffsetDoesNotCancelTheSpread) {
  // A 1e6 offset with a ±1e-3 spread: a one-pass sum of squares (x² ~ 1e12, ulp 1e-4) would lose the
  // spread (1e-6) entirely; with the mean removed first it survives to the rounding of the stored
  // samples. The truth uses the deviations as stored (Sterbenz: the subtractions are exact).
  const double offset = 1e6;
  const double up = (offset + 1e-3) - offset;
  const double down = offset - (offset - 1e-3);
  const std::size_t w = 100, n = 1000;
  std::vector<double> output(w * n);
  for (std::size_t i = 0; i < output.size(); ++i) output[i] = (i / w) % 2 == 0 ? offset + 1e-3 : offset - 1e-3;
  const BiasResult result = bias(output, unit_options(100.0, {1.0}));
  EXPECT_NEAR_RELATIVE(result.bias_stability[0].value.value, 0.5 * (up + down) * std::sqrt(1000.0 / 999.0), 1e-12);
  EXPECT_NEAR_RELATIVE(result.bias.value, offset + 0.5 * (up - down), 1e-15);
}

// The window means (eq. 20) and the pair averages of the normalised curve (eq. 23) are taken about
// the first sample: the record at an offset of 1e9 gives the figures of the same record less 1e9
// (the subtraction exact, Sterbenz). Stored near the offset, the means were rounded to 1.2e-7: Bs(100
// s) 1.4e-3 off, the curve's last point 2.4e-2.
TEST(BiasTest, StabilityAndCurveDoNotDependOnTheOutputOffset) {
  std::mt19937_64 engine(7);
  std::normal_distribution<double> noise(0.0, 1e-3);
  std::vector<double> at_offset(1 << 18);
  std::vector<double> shifted(at_offset.size());
  for (std::size_t i = 0; i < at_offset.size(); ++i) {
    at_offset[i] = 1e9 + noise(engine);
    shifted[i] = at_offset[i] - 1e9;
  }
  const BiasOptions options = unit_options(100.0, {1.0, 10.0, 100.0}, true);
  const BiasResult big = bias(at_offset, options);
  const BiasResult small = bias(shifted, options);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR_RELATIVE(big.bias_stability[k].value.value, small.bias_stability[k].value.value, 1e-13) << k;
  }
  ASSERT_EQ(big.normalised_stability_curve.size(), small.normalised_stability_curve.size());
  for (std::size_t k = 0; k < big.normalised_stability_curve.size(); ++k) {
    EXPECT_NEAR_RELATIVE(big.normalised_stability_curve[k].stability, small.normalised_stability_curve[k].stability,
                         1e-12)
        << big.normalised_stability_curve[k].tau_s;
  }
}

TEST(BiasTest, WhiteNoiseStabilityEqualsTheWindowMeansComputedDirectly) {
  std::mt19937_64 engine(20260101);
  std::normal_distribution<double> noise(0.0, 2.0);
  const double rate = 50.0;
  std::vector<double> output(50 * 400);
  for (auto& x : output) x = 3.0 + noise(engine);
  const BiasResult result = bias(output, unit_options(rate, {1.0, 10.0}));
  for (const auto& s : result.bias_stability) {
    const std::size_t w = static_cast<std::size_t>(s.smoothing_s * rate);
    std::vector<double> means;
    for (std::size_t start = 0; start + w <= output.size(); start += w) {
      double sum = 0.0;
      for (std::size_t i = start; i < start + w; ++i) sum += output[i];
      means.push_back(sum / static_cast<double>(w));
    }
    double m = 0.0;
    for (double v : means) m += v;
    m /= static_cast<double>(means.size());
    double squares = 0.0;
    for (double v : means) squares += (v - m) * (v - m);
    EXPECT_NEAR_RELATIVE(s.value.value, std::sqrt(squares / static_cast<double>(means.size() - 1)), 1e-12);
    // And it estimates sigma / sqrt(w) within 5 standard errors of a standard deviation.
    const double expected = 2.0 / std::sqrt(static_cast<double>(w));
    EXPECT_NEAR_RELATIVE(s.value.value, expected, 5.0 / std::sqrt(2.0 * static_cast<double>(means.size() - 1)));
  }
}

TEST(BiasTest, RandomWalkCoefficientOfWhiteNoise) {
  // White noise of sigma per sample at rate r: Bs(1 s) = sigma / sqrt(r) deg/h (K = 3600), and
  // RWC = Bs(1 s) / 60 deg/sqrt(h) (eq. 24).
  std::mt19937_64 engine(7);
  std::normal_distribution<double> noise(0.0, 6.0);
  const double rate = 64.0;
  std::vector<double> output(64 * 2000);
  for (auto& x : output) x = noise(engine);
  const BiasResult result = bias(output, unit_options(rate, {1.0}, true));
  const double tolerance = 5.0 / std::sqrt(2.0 * 1999.0);
  EXPECT_NEAR_RELATIVE(result.noise_equivalent_rate->value, 6.0 / 8.0, tolerance);
  EXPECT_NEAR_RELATIVE(result.random_walk_coefficient->value, 6.0 / 8.0 / 60.0, tolerance);
  EXPECT_EQ(result.random_walk_coefficient->unit, "deg/sqrt(h)");
  // 1 s = 2^6 t0: NER is exactly the point tau = 1 s of the sequence of eq. (23).
  bool found = false;
  for (const auto& p : result.normalised_stability_curve) {
    if (p.tau_s == 1.0) {
      EXPECT_NEAR_RELATIVE(p.stability, result.noise_equivalent_rate->value, 1e-12);
      found = true;
    }
  }
  EXPECT_TRUE(found);
  EXPECT_NEAR_RELATIVE(result.normalised_stability_curve.front().stability, 6.0, 0.01);
}

TEST(BiasTest, NormalisedCurveHandComputed) {
  // Pairs of {0, 4, 2, 2, 1, 3}: level t0 all six; level 2 t0 {2, 2, 2}; then one value: stop.
  const std::vector<double> output = {0, 4, 2, 2, 1, 3};
  const auto curve = normalised_stability_curve(output, 1.0);
  ASSERT_EQ(curve.size(), 2u);
  EXPECT_DOUBLE_EQ(curve[0].tau_s, 1.0);
  EXPECT_NEAR(curve[0].stability, std::sqrt(10.0 / 5.0), 1e-14);
  EXPECT_DOUBLE_EQ(curve[1].tau_s, 2.0);
  EXPECT_NEAR(curve[1].stability, 0.0, 1e-14);
}

TEST(BiasTest, NoiseEquivalentRateInterpolatedWhenOneSecondIsNotWholeSamples) {
  std::mt19937_64 engine(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  const double rate = 102.4;  // 1 s = 102.4 samples
  std::vector<double> output(102400 * 2);
  for (auto& x : output) x = noise(engine);
  EXPECT_NEAR_RELATIVE(noise_equivalent_rate(output, rate), 1.0 / std::sqrt(rate), 0.1);
}

TEST(BiasTest, EarthRateRemovedOnlyWhenAsked) {
  const std::vector<double> output(4, 0.0);
  BiasOptions options = unit_options(1.0, {1.0});
  EXPECT_DOUBLE_EQ(bias(output, options).bias.value, 0.0);
  // IRA pointing north, horizontal, at 30 deg N: Ωe cos 30° along it, subtracted.
  options.remove_earth_rate = AxisOrientation{30.0, 0.0, 0.0};
  const double earth_deg_h = 7.2921150e-5 / (3.14159265358979323846 / 180.0) * 3600.0;
  const BiasResult result = bias(output, options);
  EXPECT_NEAR(result.bias.value, -earth_deg_h * std::cos(30.0 * 3.14159265358979323846 / 180.0), 1e-12);
  EXPECT_NEAR(result.earth_rate_removed->value, earth_deg_h * std::sqrt(3.0) / 2.0, 1e-12);
  // IRA east-west (as 5.12.1.3 mounts it): nothing to remove.
  options.remove_earth_rate = AxisOrientation{30.0, 90.0, 0.0};
  EXPECT_NEAR(bias(output, options).bias.value, 0.0, 1e-12);
}

TEST(BiasTest, JsonHasTheContractKeys) {
  const std::vector<double> output = {1.0, 3.0, 1.0, 3.0, 1.0, 3.0, 1.0, 3.0};  // means of 1 s: all 2
  const nlohmann::json json = json_of(bias(output, unit_options(4.0, {1.0}, true)));
  EXPECT_EQ(json.at("bias").at("unit"), "deg/h");
  EXPECT_EQ(json.at("bias_stability").at(0),
            (nlohmann::json{{"smoothing_s", 1.0}, {"value", 0.0}, {"unit", "deg/h"}}));  // 2 per 1 s window
  EXPECT_EQ(json.at("random_walk_coefficient").at("unit"), "deg/sqrt(h)");
}

TEST(BiasTest, AConstantRecordIsWarnedAbout) {
  // A stuck channel gives a stability of exactly 0: not a measurement, so its rows and its random
  // walk are left out (a limit on them is "not measured"; a dead gyro passed them).
  const std::vector<double> stuck(8, 1.0);
  const BiasResult result = bias(stuck, unit_options(4.0, {1.0}, true));
  EXPECT_TRUE(result.bias_stability.empty());
  ASSERT_EQ(result.smoothing_left_out.size(), 1u);
  EXPECT_THAT(result.smoothing_left_out[0].reason, ::testing::HasSubstr("all 8 samples equal 1 (a stuck channel?)"));
  EXPECT_FALSE(result.random_walk_coefficient.has_value());
  EXPECT_TRUE(json_of(result).at("bias_stability").at(0).at("value").is_null());
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], ::testing::HasSubstr("all 8 samples equal 1 (a stuck channel?): no bias stability"));
  EXPECT_EQ(json_of(result).at("warnings"), nlohmann::json(result.warnings));
  EXPECT_THAT(text_of(result), ::testing::HasSubstr("warning: the record is constant"));
  // One differing sample is a record, not a stuck channel.
  std::vector<double> moving = stuck;
  moving.back() = 1.5;
  EXPECT_TRUE(bias(moving, unit_options(4.0, {1.0}, true)).warnings.empty());
}

TEST(BiasTest, BadInputIsAnError) {
  const std::vector<double> output(10, 1.0);
  EXPECT_THROW(bias(output, unit_options(0.0, {1.0})), Error);     // non-positive rate
  EXPECT_THROW(bias(output, unit_options(-5.0, {1.0})), Error);
  BiasOptions zero_k = unit_options(1.0, {1.0});
  zero_k.scale_factor = 0.0;
  EXPECT_THROW(bias(output, zero_k), Error);                       // zero scale factor
  EXPECT_THROW(bias(output, unit_options(1.0, {})), Error);        // no smoothing time
  EXPECT_THROW(bias(output, unit_options(1.0, {-1.0})), Error);    // negative smoothing time
  EXPECT_THROW(bias(std::vector<double>{1.0}, unit_options(1.0, {1.0})), Error);  // too few samples
}

// A record shorter than the longest smoothing time still gives its bias and the stabilities it
// supports; the rest are warnings. 50 s at 10 Hz of a ramp 0, 0.1, ..., 49.9 (deg/h with K = 3600).
TEST(BiasTest, ShortRecordGivesEveryFigureItSupports) {
  std::vector<double> output(500);
  for (std::size_t i = 0; i < output.size(); ++i) output[i] = 0.1 * static_cast<double>(i);
  const BiasResult result = bias(output, unit_options(10.0, {1.0, 10.0, 30.0, 100.0, 0.15}, true));
  EXPECT_NEAR(result.bias.value, 24.95, 1e-12);
  ASSERT_EQ(result.bias_stability.size(), 2u);
  // 1 s means 0.45, 1.45, ... 49.45: a ramp of 50 steps of 1, sd = sqrt(50 * 51 / 12).
  EXPECT_EQ(result.bias_stability[0].smoothing_s, 1.0);
  EXPECT_NEAR(result.bias_stability[0].value.value, std::sqrt(50.0 * 51.0 / 12.0), 1e-10);
  // 10 s means 4.95, 14.95, ..., 44.95: sd = 10 sqrt(5 * 6 / 12).
  EXPECT_EQ(result.bias_stability[1].smoothing_s, 10.0);
  EXPECT_NEAR(result.bias_stability[1].value.value, 10.0 * std::sqrt(2.5), 1e-10);
  ASSERT_EQ(result.warnings.size(), 3u);
  EXPECT_THAT(result.warnings[0], ::testing::HasSubstr("1 whole window(s) of 30 s"));
  EXPECT_THAT(result.warnings[0], ::testing::HasSubstr("(left out)"));
  EXPECT_THAT(result.warnings[1], ::testing::HasSubstr("100 s (1000 samples) is longer than the record"));
  EXPECT_THAT(result.warnings[2], ::testing::HasSubstr("0.15 s is not a whole number of samples"));
  ASSERT_TRUE(result.random_walk_coefficient.has_value());
  // The JSON keeps a row per smoothing time asked for, in that order, those left out not measured
  // (a plan's limit on "/bias_stability/2" names 30 s, not a figure that moved up).
  const nlohmann::json rows = json_of(result).at("bias_stability");
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[1].at("smoothing_s"), 10.0);
  EXPECT_EQ(rows[2].at("smoothing_s"), 30.0);
  EXPECT_TRUE(rows[2].at("value").is_null());
  EXPECT_FALSE(rows[2].at("measured").get<bool>());
  EXPECT_THAT(rows[3].at("reason").get<std::string>(), ::testing::HasSubstr("100 s (1000 samples)"));
  EXPECT_EQ(rows[4].at("smoothing_s"), 0.15);
  EXPECT_THAT(text_of(result), ::testing::HasSubstr("smoothing_s 30: not measured (bias stability: the record holds 1 whole window(s) of 30 s"));
  // Two samples: the bias, and warnings for every smoothing time and the random walk coefficient.
  const BiasResult two = bias(std::vector<double>{1.0, 2.0}, unit_options(10.0, {1.0}, true));
  EXPECT_DOUBLE_EQ(two.bias.value, 1.5);
  EXPECT_TRUE(two.bias_stability.empty());
  EXPECT_FALSE(two.random_walk_coefficient.has_value());
  EXPECT_EQ(two.warnings.size(), 2u);
}

// Sampled below 1 Hz (every 2 s): no 1 s stability and no NER = Bs(1 s), but the bias, the
// stabilities at whole numbers of samples and the normalised curve of eq. (23).
TEST(BiasTest, RecordSampledBelowOneHertzGivesEveryFigureItSupports) {
  std::vector<double> output(200);
  for (std::size_t i = 0; i < output.size(); ++i) output[i] = i % 2 == 0 ? 1.0 : 3.0;  // square wave of 4 s
  const BiasResult result = bias(output, unit_options(0.5, {1.0, 4.0, 10.0}, true));
  EXPECT_DOUBLE_EQ(result.bias.value, 2.0);
  ASSERT_EQ(result.bias_stability.size(), 2u);
  EXPECT_EQ(result.bias_stability[0].smoothing_s, 4.0);  // whole periods: every mean is 2
  EXPECT_NEAR(result.bias_stability[0].value.value, 0.0, 1e-12);
  // 10 s = 5 samples: 40 means, 1.8 and 2.2 alternating, deviations of 0.2 over n - 1 = 39.
  EXPECT_EQ(result.bias_stability[1].smoothing_s, 10.0);
  EXPECT_NEAR(result.bias_stability[1].value.value, 0.2 * std::sqrt(40.0 / 39.0), 1e-12);
  EXPECT_FALSE(result.random_walk_coefficient.has_value());
  EXPECT_FALSE(result.noise_equivalent_rate.has_value());
  ASSERT_FALSE(result.normalised_stability_curve.empty());
  EXPECT_EQ(result.normalised_stability_curve[0].tau_s, 2.0);
  ASSERT_EQ(result.warnings.size(), 2u);
  EXPECT_THAT(result.warnings[0], ::testing::HasSubstr("1 s is not a whole number of samples at 0.5 Hz"));
  EXPECT_THAT(result.warnings[1], ::testing::HasSubstr("longer than 1 s"));
  EXPECT_THAT(text_of(result), ::testing::HasSubstr("warning: "));
}

}  // namespace
}  // namespace inertest
