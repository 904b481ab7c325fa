#include "inertest/procedures/maximum_input_rate.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "procedures/scale_factor_series_test_util.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;

// Linear (K = 10) up to |Ω| = 100 deg/s, then the output saturates: 1 % low at 200, 5 % at 500.
std::vector<ScaleFactorPoint> saturating_run() {
  std::vector<ScaleFactorPoint> points = {{0.0, 0.0}};
  for (double r : {1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0}) {
    const double loss = r == 200.0 ? 0.01 : (r == 500.0 ? 0.05 : 0.0);
    points.push_back({r, 10.0 * r * (1 - loss)});
    points.push_back({-r, -10.0 * r * (1 - loss)});
  }
  points.push_back({0.0, 0.0});
  return points;
}

TEST(MaximumInputRate, LargestRangeThatMeetsTheNonlinearityRequirement) {
  MaximumInputRateOptions options;
  options.nonlinearity_limit_ppm = 100.0;
  const auto result = maximum_input_rate(saturating_run(), options);
  // Exactly linear up to 100 deg/s (Kn = 0); the 1 % loss at 200 is far above 100 ppm.
  EXPECT_EQ(result.maximum_input_rate.value, 100.0);
  EXPECT_EQ(result.maximum_input_rate.unit, "deg/s");
  EXPECT_NEAR(result.nonlinearity.value, 0.0, 1e-6);
  EXPECT_NEAR_RELATIVE(result.scale_factor.value, 10.0, 1e-12);
  ASSERT_EQ(result.ranges.size(), 8u);  // R = 2 (two rates each way), 5, 10, 20, 50, 100, 200, 500
  EXPECT_EQ(result.ranges.front().rate, 2.0);
  EXPECT_FALSE(result.ranges[6].meets_requirement);
  EXPECT_TRUE(result.warnings.empty());
}

TEST(MaximumInputRate, AllRangesPassGivesTheLargestTestedRateAndAWarning) {
  MaximumInputRateOptions options;
  options.nonlinearity_limit_ppm = 1e6;
  const auto result = maximum_input_rate(saturating_run(), options);
  EXPECT_EQ(result.maximum_input_rate.value, 500.0);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], HasSubstr("may be higher"));
}

// GJB 2426A 5.9 judges the characteristic at the maximum input rate: small ranges whose noise is
// most of their nonlinearity (in ppm of a small full scale) do not stop the scan, they are said. The
// README's own record (scale factor 5000 pulse/s/(deg/s), Kn 17 ppm over +-300 deg/s) was refused:
// 34 ppm over |rate| <= 0.2 deg/s.
TEST(MaximumInputRate, SmallRangesThatMissTheRequirementAreAWarning) {
  std::vector<ScaleFactorPoint> points = {{0.0, 0.0}};
  for (double r : {0.1, 0.2, 0.5, 1.0, 10.0, 100.0, 300.0}) {
    const double noise = r == 0.1 ? 0.05 : (r == 0.2 ? -0.05 : 0.0);  // pulse/s, both ways: no slope absorbs it
    points.push_back({r, 5000.0 * r + noise});
    points.push_back({-r, -5000.0 * r + noise});
  }
  points.push_back({0.0, 0.0});
  MaximumInputRateOptions options;
  options.nonlinearity_limit_ppm = 20.0;
  const auto result = maximum_input_rate(points, options);
  EXPECT_EQ(result.maximum_input_rate.value, 300.0);
  EXPECT_FALSE(result.ranges.front().meets_requirement);  // |rate| <= 0.2
  EXPECT_TRUE(result.ranges.back().meets_requirement);
  ASSERT_GE(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], HasSubstr("the nonlinearity over the smaller ranges |rate| <= 0.2 deg/s ("));
  EXPECT_THAT(result.warnings[0], HasSubstr("ppm) is above the requirement"));
}

// Ranges must be tested both ways: with the negative rates stopping at 5 deg/s, a point at 400
// deg/s (positive only) gave a maximum input rate of 400 deg/s, never tested in the negative.
TEST(MaximumInputRate, OnlyRangesTestedInBothDirectionsCount) {
  std::vector<ScaleFactorPoint> points = {{0.0, 0.0}};
  for (double r : {1.0, 2.0, 5.0}) {
    points.push_back({r, 100.0 * r});
    points.push_back({-r, -100.0 * r});
  }
  points.push_back({400.0, 40000.0});
  points.push_back({0.0, 0.0});
  MaximumInputRateOptions options;
  options.nonlinearity_limit_ppm = 100.0;
  const auto result = maximum_input_rate(points, options);
  EXPECT_EQ(result.maximum_input_rate.value, 5.0);
  ASSERT_EQ(result.ranges.size(), 2u);  // R = 2, 5
  ASSERT_EQ(result.warnings.size(), 2u);
  EXPECT_THAT(result.warnings[1], HasSubstr("400 deg/s in the positive direction and -5 deg/s in the negative"));
}

TEST(MaximumInputRate, RequirementMetNowhereIsAnError) {
  std::vector<ScaleFactorPoint> points = {{0.0, 0.0}};
  for (double r : {1.0, 2.0, 5.0}) {
    points.push_back({r, r + 0.01 * r * r * r});  // cubic: nonlinear at every range
    points.push_back({-r, -r - 0.01 * r * r * r});
  }
  points.push_back({0.0, 0.0});
  MaximumInputRateOptions options;
  options.nonlinearity_limit_ppm = 1.0;
  try {
    maximum_input_rate(points, options);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("holds at no tested rate"));
  }
}

TEST(MaximumInputRate, BadInputIsAnError) {
  MaximumInputRateOptions options;
  EXPECT_THROW(maximum_input_rate(saturating_run(), options), Error);  // no requirement given
  options.nonlinearity_limit_ppm = 100.0;
  auto no_static = saturating_run();
  no_static.pop_back();
  EXPECT_THROW(maximum_input_rate(no_static, options), Error);
  // Rates not bracketing zero.
  std::vector<ScaleFactorPoint> positive_only = {{0, 0}, {1, 10}, {2, 20}, {5, 50}, {0, 0}};
  EXPECT_THROW(maximum_input_rate(positive_only, options), Error);
}

}  // namespace
}  // namespace inertest
