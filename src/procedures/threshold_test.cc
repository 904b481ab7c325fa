#include "inertest/procedures/threshold.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

constexpr double kPi = 3.14159265358979323846;
const double kEarthDegH = 7.2921150e-5 / (kPi / 180.0) * 3600.0;

// K = 3600 output units per deg/s: an input of 1 deg/h gives an output of 1.
ThresholdOptions unit_options() {
  ThresholdOptions options;
  options.scale_factor = 3600.0;
  options.rate_unit = "deg/h";
  return options;
}

TEST(ThresholdTest, MethodOneHandComputed) {
  // Zero output 10 from the zero-rate points. Relative to the expected output: positive: 10 -> F 10,
  // 5 -> 5, 2 -> 1.5 (|2-1.5|/2 = 0.25), 1 -> 0.4 (0.6 fails), 0.5 -> 0.5 (passes again, after a
  // failure: not counted). Negative: -10 -> -10, -4 -> -3 (0.25), -2 -> -0.5 (0.75 fails).
  // Threshold max(2, 4) = 4 deg/h.
  const std::vector<RateTablePoint> points = {{0, 10.0},   {10, 20.0}, {5, 15.0}, {2, 11.5}, {1, 10.4},
                                              {0.5, 10.5}, {-10, 0.0}, {-4, 7.0}, {-2, 9.5}, {0, 10.0}};
  const ThresholdResult result = threshold_rate_table(points, unit_options());
  ASSERT_EQ(result.branches.size(), 2u);
  EXPECT_DOUBLE_EQ(result.branches[0].candidate_deg_h, 2.0);
  EXPECT_TRUE(result.branches[0].bounded);
  EXPECT_DOUBLE_EQ(result.branches[1].candidate_deg_h, 4.0);
  EXPECT_DOUBLE_EQ(result.threshold.value, 4.0);
  EXPECT_EQ(result.threshold.unit, "deg/h");
  EXPECT_TRUE(result.warnings.empty());
  EXPECT_EQ(result.criterion_denominator, CriterionDenominator::kExpected);
}

TEST(ThresholdTest, DefaultCriterionIsHalfTheExpectedOutput) {
  // IEEE Std 952-1997: an output of at least 50 % of the expected one. Input 2 gives 1.2 (60 %):
  // |2 - 1.2| / 2 = 0.4 passes; input 1 gives 0.45 (45 %): 0.55 fails. Eq. (15) as printed divides
  // by the measured output, |2 - 1.2| / 1.2 = 0.67, and fails input 2 already (a 67 % criterion).
  const std::vector<RateTablePoint> points = {{4, 4.0}, {2, 1.2}, {1, 0.45}, {-4, -4.0}, {-2, -2.0}, {-1, -0.45}};
  ThresholdOptions options = unit_options();
  options.zero_output = 0.0;
  const ThresholdResult expected = threshold_rate_table(points, options);
  EXPECT_DOUBLE_EQ(expected.branches[0].candidate_deg_h, 2.0);
  EXPECT_TRUE(expected.branches[0].bounded);
  EXPECT_NEAR(expected.branches[0].points[1].relative_error, 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(expected.threshold.value, 2.0);
  const ProcedureSpec spec = threshold_spec();
  const nlohmann::json json = spec.fields_of(&expected);
  EXPECT_EQ(json.at("criterion_denominator"), "expected");
  EXPECT_THAT(json.at("criterion").get<std::string>(), ::testing::HasSubstr("IEEE Std 952-1997"));
  EXPECT_THAT(procedure_text(spec, json), ::testing::HasSubstr("IEEE Std 952-1997"));

  options.criterion_denominator = CriterionDenominator::kMeasured;
  const ThresholdResult measured = threshold_rate_table(points, options);
  EXPECT_DOUBLE_EQ(measured.branches[0].candidate_deg_h, 4.0);
  EXPECT_NEAR(measured.branches[0].points[1].relative_error, 0.8 / 1.2, 1e-12);
  EXPECT_DOUBLE_EQ(measured.threshold.value, 4.0);
  EXPECT_EQ(spec.fields_of(&measured).at("criterion_denominator"), "measured");
  EXPECT_THAT(procedure_text(spec, spec.fields_of(&measured)), ::testing::HasSubstr("eq. (15) as printed"));
}

TEST(ThresholdTest, MeasuredDenominatorIsEquationFifteenAsPrinted) {
  // Input 2 with measured 3.5: eq. (15) gives |2 - 3.5| / 3.5 = 0.43 (passes); dividing by the
  // expected output gives 0.75 (fails).
  const std::vector<RateTablePoint> points = {{4, 4.0}, {2, 3.5}, {-4, -4.0}, {-3, -3.0}};
  ThresholdOptions options = unit_options();
  options.zero_output = 0.0;
  options.criterion_denominator = CriterionDenominator::kMeasured;
  const ThresholdResult result = threshold_rate_table(points, options);
  EXPECT_DOUBLE_EQ(result.branches[0].candidate_deg_h, 2.0);
  EXPECT_FALSE(result.branches[0].bounded);
  EXPECT_EQ(result.warnings.size(), 2u);  // neither branch found a failing input
  options.criterion_denominator = CriterionDenominator::kExpected;
  EXPECT_DOUBLE_EQ(threshold_rate_table(points, options).branches[0].candidate_deg_h, 4.0);
  // A dead band: input 1 gives exactly the zero output. It misses the criterion (its error against
  // the expected output is 1), as by the expected denominator; it was an infinite error, an abort.
  const std::vector<RateTablePoint> dead = {{4, 4.0}, {2, 2.1}, {1, 0.0}, {-4, -4.0}, {-2, -2.1}, {-1, 0.0}};
  options.criterion_denominator = CriterionDenominator::kMeasured;
  const ThresholdResult with_dead_band = threshold_rate_table(dead, options);
  EXPECT_DOUBLE_EQ(with_dead_band.branches[0].candidate_deg_h, 2.0);
  EXPECT_TRUE(with_dead_band.branches[0].bounded);
  EXPECT_DOUBLE_EQ(with_dead_band.branches[0].points[2].relative_error, 1.0);
}

TEST(ThresholdTest, CriterionDenominatorParses) {
  EXPECT_EQ(parse_criterion_denominator("expected"), CriterionDenominator::kExpected);
  EXPECT_EQ(parse_criterion_denominator("measured"), CriterionDenominator::kMeasured);
  EXPECT_EQ(to_string(CriterionDenominator::kMeasured), "measured");
  EXPECT_THROW(parse_criterion_denominator("theoretical"), Error);
}

TEST(ThresholdTest, MethodTwoDeadZoneOnTheDividingHead) {
  // Latitude 60 deg: horizontal Earth rate Ωe/2. The instrument has a dead zone of 0.3 deg/h:
  // below it the output stays at the zero. Angles: cos 87° · Ωe/2 = 0.394 deg/h passes,
  // cos 88° · Ωe/2 = 0.262 fails; same toward south (93°, 92°). Threshold = Ωe cos 60° cos 87°.
  ThresholdOptions options = unit_options();
  options.latitude_deg = 60.0;
  const double zero = 5.0;
  std::vector<DividingHeadPoint> points;
  for (double angle : {0.0, 60.0, 80.0, 85.0, 87.0, 88.0, 89.0, 90.0, 91.0, 92.0, 93.0, 95.0, 100.0, 120.0, 180.0, 270.0}) {
    const double input = kEarthDegH * std::cos(60.0 * kPi / 180.0) * std::cos(angle * kPi / 180.0);
    points.push_back({angle, zero + (std::abs(input) > 0.3 ? input : 0.0)});
  }
  const ThresholdResult result = threshold_dividing_head(points, options);
  EXPECT_NEAR(result.zero_output.value, zero, 1e-12);  // from the east and west positions
  const double expected = kEarthDegH * 0.5 * std::cos(87.0 * kPi / 180.0);
  EXPECT_NEAR_RELATIVE(result.threshold.value, expected, 1e-12);
  EXPECT_NEAR_RELATIVE(result.branches[0].candidate_deg_h, expected, 1e-12);
  EXPECT_NEAR_RELATIVE(result.branches[1].candidate_deg_h, expected, 1e-12);
}

TEST(ThresholdTest, MethodTwoHeadingOffsetsTheAngles) {
  // The head's zero mark points east (heading 90): reading -90 is north.
  ThresholdOptions options = unit_options();
  options.heading_deg = 90.0;
  options.zero_output = 0.0;
  const std::vector<DividingHeadPoint> points = {{-90.0, kEarthDegH}, {90.0, -kEarthDegH}};
  // The latitude is the input's: not given, it is asked for (0 assumed gave Omega_e, not Omega_e cos ψ).
  try {
    threshold_dividing_head(points, options);
    ADD_FAILURE() << "method 2 ran without a latitude";
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.parameter, "latitude");
    EXPECT_THAT(e.message(), ::testing::HasSubstr("latitude is needed by method 2"));
  }
  options.latitude_deg = 0.0;
  EXPECT_NEAR_RELATIVE(threshold_dividing_head(points, options).threshold.value, kEarthDegH, 1e-12);
}

TEST(ThresholdTest, MethodThreeFourBranchesOfOneRevolution) {
  // One revolution at 0.1 deg/s sampled at 1 Hz: θ_j = 0.1 (j + 1) deg. Dead zone between the
  // inputs at 89.5° and 89.6° from north: each branch's candidate is at 0.5° from its crossing.
  ThresholdOptions options = unit_options();
  options.latitude_deg = 30.0;
  const double horizontal = kEarthDegH * std::cos(30.0 * kPi / 180.0);
  const double dead_zone = horizontal * 0.5 * (std::cos(89.5 * kPi / 180.0) + std::cos(89.6 * kPi / 180.0));
  const double zero = -2.0;
  std::vector<double> time, output;
  for (int j = 0; j < 3600; ++j) {
    const double t = j + 1.0;
    const double input = horizontal * std::cos(0.1 * t * kPi / 180.0);
    time.push_back(t);
    output.push_back(zero + (std::abs(input) > dead_zone ? input : 0.0));
  }
  const ThresholdResult result = threshold_rotating(time, output, 0.1, options);
  ASSERT_EQ(result.branches.size(), 4u);
  const double expected = horizontal * std::cos(89.5 * kPi / 180.0);
  for (const auto& b : result.branches) EXPECT_NEAR_RELATIVE(b.candidate_deg_h, expected, 1e-9) << b.name;
  EXPECT_NEAR_RELATIVE(result.threshold.value, expected, 1e-9);
  EXPECT_NEAR(result.zero_output.value, zero, 1e-9);  // the mean over the whole revolution
  EXPECT_TRUE(result.warnings.empty());
}

TEST(ThresholdTest, MethodThreeSamplesAtTheCrossingsBelongToNoBranch) {
  // One revolution at 1 deg/s sampled at 1 Hz from t = 0: samples at exactly 90 and 270 deg, where
  // cos gives 6e-17, not 0. An ideal instrument (no dead zone): each branch's candidate is its
  // smallest nonzero input, 1 deg from a crossing, and every input keeps its branch's sign.
  ThresholdOptions options = unit_options();
  options.zero_output = 0.0;
  options.latitude_deg = 0.0;
  const double horizontal = kEarthDegH;  // latitude 0
  std::vector<double> time, output;
  for (int j = 0; j < 360; ++j) {
    time.push_back(j);
    output.push_back(horizontal * std::cos(j * kPi / 180.0));
  }
  const ThresholdResult result = threshold_rotating(time, output, 1.0, options);
  ASSERT_EQ(result.branches.size(), 4u);
  const double expected = horizontal * std::cos(89.0 * kPi / 180.0);
  for (const auto& b : result.branches) {
    EXPECT_NEAR_RELATIVE(b.candidate_deg_h, expected, 1e-9) << b.name;
    const bool positive = b.name.starts_with("positive");
    for (const auto& p : b.points) EXPECT_EQ(p.input_deg_h > 0.0, positive) << b.name << " " << p.input_deg_h;
  }
  EXPECT_NEAR_RELATIVE(result.threshold.value, expected, 1e-9);
}

TEST(ThresholdTest, BadInputIsAnError) {
  ThresholdOptions options = unit_options();
  const std::vector<RateTablePoint> one_side = {{0, 0.0}, {1, 1.0}, {2, 2.0}};
  EXPECT_THROW(threshold_rate_table(one_side, options), Error);  // no negative rate
  const std::vector<RateTablePoint> no_zero = {{1, 1.0}, {-1, -1.0}};
  EXPECT_THROW(threshold_rate_table(no_zero, options), Error);   // no zero output
  const std::vector<RateTablePoint> dead = {{0, 0.0}, {1, 0.0}, {-1, -1.0}};
  EXPECT_THROW(threshold_rate_table(dead, options), Error);      // the largest rate already fails
  ThresholdOptions zero_k = options;
  zero_k.scale_factor = 0.0;
  EXPECT_THROW(threshold_rate_table(no_zero, zero_k), Error);
  const std::vector<double> t = {1, 2, 3, 4, 5}, f = {1, 1, 1, 1, 1};
  EXPECT_THROW(threshold_rotating(t, f, 0.0, options), Error);   // zero table rate
  EXPECT_THROW(threshold_rotating(t, f, 0.1, options), Error);   // less than one revolution
  const std::vector<DividingHeadPoint> north_only = {{0.0, 1.0}, {90.0, 0.0}};
  EXPECT_THROW(threshold_dividing_head(north_only, options), Error);
}

}  // namespace
}  // namespace inertest
