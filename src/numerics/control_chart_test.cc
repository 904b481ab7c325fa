#include "inertest/numerics/control_chart.h"

#include <gtest/gtest.h>

#include <vector>

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

// Hand case: 10, 12, 11, 13, 10 → x̄ = 11.2, moving ranges 2, 1, 2, 3 → MR̄ = 2,
// σ = 2/1.128379 = 1.772454, UCL = 11.2 + 5.317362 = 16.517362, LCL = 5.882638.
TEST(ControlChart, IndividualsAndMovingRangeByHand) {
  const std::vector<double> values = {10, 12, 11, 13, 10};
  const ControlChart chart = individuals_control_chart(values);
  EXPECT_NEAR(chart.center, 11.2, 1e-12);
  EXPECT_NEAR(chart.moving_range_mean, 2.0, 1e-12);
  EXPECT_NEAR(chart.sigma, 1.7724538509055159, 1e-12);  // 2 / (2/√π) = √π
  EXPECT_NEAR(chart.ucl, 11.2 + 3 * 1.7724538509055159, 1e-12);
  EXPECT_NEAR(chart.lcl, 11.2 - 3 * 1.7724538509055159, 1e-12);
  EXPECT_TRUE(chart.out_of_control.empty());
}

// 19 points alternating 0 and 1, then 10: the point 10 lies beyond 3σ.
TEST(ControlChart, FlagsAPointBeyondThreeSigma) {
  std::vector<double> values;
  for (int i = 0; i < 19; ++i) values.push_back(i % 2);
  values.push_back(10);
  // x̄ = (9 + 10)/20 = 0.95; MR̄ = (18·1 + 10)/19 = 28/19; UCL = 0.95 + 3·(28/19)/1.128379 = 4.868.
  const ControlChart chart = individuals_control_chart(values);
  ASSERT_EQ(chart.out_of_control.size(), 1u);
  EXPECT_EQ(chart.out_of_control[0].index, 19u);
  EXPECT_EQ(chart.out_of_control[0].rule, "beyond_3_sigma");
}

// Eight values above the center in a row (a drifted batch), within the limits: rule 4 flags
// the eighth. x̄ = 0; MR̄ = (5·2 + 1.5 + 2.5)/15 = 14/15, 3σ = 2.48: every point within.
TEST(ControlChart, FlagsEightOnOneSide) {
  const std::vector<double> values = {1, -1, 1, -1, 1, -1, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, -2, -2};
  const ControlChart chart = individuals_control_chart(values);
  ASSERT_EQ(chart.out_of_control.size(), 1u);
  EXPECT_EQ(chart.out_of_control[0].index, 13u);
  EXPECT_EQ(chart.out_of_control[0].rule, "8_on_one_side");
}

TEST(ControlChart, NeedsTwoValues) {
  const std::vector<double> one = {1.0};
  EXPECT_THROW(individuals_control_chart(one), Error);
}

// Cp = (12 − 8)/(6·0.5) = 4/3; Cpk = min(12 − 10.5, 10.5 − 8)/(3·0.5) = 1.5/1.5 = 1.
TEST(ProcessCapability, TwoSidedAndOneSided) {
  const ProcessCapability both = process_capability(10.5, 0.5, 8.0, 12.0);
  EXPECT_NEAR(*both.cp, 4.0 / 3.0, 1e-15);
  EXPECT_NEAR(*both.cpk, 1.0, 1e-15);
  const ProcessCapability upper = process_capability(10.5, 0.5, std::nullopt, 12.0);
  EXPECT_FALSE(upper.cp);
  EXPECT_NEAR(*upper.cpk, 1.0, 1e-15);
  const ProcessCapability none = process_capability(10.5, 0.5, std::nullopt, std::nullopt);
  EXPECT_FALSE(none.cp);
  EXPECT_FALSE(none.cpk);
  EXPECT_THROW(process_capability(10.5, 0.0, 8.0, 12.0), Error);
}

}  // namespace
}  // namespace inertest
