#include "inertest/procedures/resolution.h"

#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

ResolutionOptions unit_options() {
  ResolutionOptions options;
  options.scale_factor = 3600.0;  // 1 output unit per deg/h
  options.rate_unit = "deg/h";
  return options;
}

TEST(ResolutionTest, HandComputed) {
  // Forward (base 36000 deg/h, output 36000 + 7): increments 10 -> 10, 5 -> 5.5, 2 -> 1.2
  // (|2-1.2|/2 = 0.4), 1 -> 0.4 (0.6 fails). Reverse: -10 -> -10, -4 -> -2.5 (0.375), -3 -> -1
  // (0.67 fails). Resolution max(2, 4) = 4 deg/h.
  const double b = 36000.0, f0 = 36007.0;
  const std::vector<ResolutionStep> steps = {
      {b, f0, b + 10, f0 + 10},   {b, f0, b + 5, f0 + 5.5},   {b, f0, b + 2, f0 + 1.2},  {b, f0, b + 1, f0 + 0.4},
      {-b, -f0, -b - 10, -f0 - 10}, {-b, -f0, -b - 4, -f0 - 2.5}, {-b, -f0, -b - 3, -f0 - 1}};
  const ResolutionResult result = resolution(steps, unit_options());
  ASSERT_EQ(result.branches.size(), 2u);
  EXPECT_DOUBLE_EQ(result.branches[0].candidate_deg_h, 2.0);
  EXPECT_DOUBLE_EQ(result.branches[1].candidate_deg_h, 4.0);
  EXPECT_DOUBLE_EQ(result.resolution.value, 4.0);
  EXPECT_EQ(result.resolution.unit, "deg/h");
}

TEST(ResolutionTest, DenominatorIsThePredictedIncrement) {
  // Increment 2 with output increment 3.5: eq. (18) gives |2 - 3.5| / 2 = 0.75 (fails), where
  // eq. (15)'s denominator would give 0.43.
  const std::vector<ResolutionStep> steps = {{100, 0, 104, 4}, {100, 0, 102, 3.5}, {-100, 0, -104, -4}};
  const ResolutionResult result = resolution(steps, unit_options());
  EXPECT_DOUBLE_EQ(result.branches[0].candidate_deg_h, 4.0);
  EXPECT_TRUE(result.branches[0].bounded);
}

TEST(ResolutionTest, BadInputIsAnError) {
  const auto options = unit_options();
  EXPECT_THROW(resolution(std::vector<ResolutionStep>{{100, 0, 101, 1}}, options), Error);  // no reverse steps
  EXPECT_THROW(resolution(std::vector<ResolutionStep>{{0, 0, 1, 1}, {-100, 0, -101, -1}}, options), Error);
  EXPECT_THROW(resolution(std::vector<ResolutionStep>{{100, 0, 100, 1}, {-100, 0, -101, -1}}, options), Error);
  EXPECT_THROW(resolution(std::vector<ResolutionStep>{{100, 0, 101, -1}, {-100, 0, -101, -1}}, options), Error);
  ResolutionOptions zero_k = options;
  zero_k.scale_factor = 0.0;
  EXPECT_THROW(resolution(std::vector<ResolutionStep>{{100, 0, 101, 1}, {-100, 0, -101, -1}}, zero_k), Error);
}

}  // namespace
}  // namespace inertest
