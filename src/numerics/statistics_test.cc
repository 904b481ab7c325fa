#include "inertest/numerics/statistics.h"

#include <cmath>
#include <vector>

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

TEST(Mean, KeepsTheDigitsOfSmallValuesOnALargeOffset) {
  // 1e9 + {1, 2, 3}: every value is exact in a double, and so is the mean.
  const std::vector<double> values{1e9 + 1.0, 1e9 + 2.0, 1e9 + 3.0};
  EXPECT_EQ(mean(values), 1e9 + 2.0);
}

TEST(Mean, OfAMillionTenthsIsATenthToTheLastBit) {
  // A naive running sum of 10^6 copies of 0.1 drifts by ~1e-6 relative; the compensated one does not.
  const std::vector<double> values(1'000'000, 0.1);
  EXPECT_EQ(mean(values), 0.1);
}

TEST(Mean, OfNothingIsAnError) { EXPECT_THROW(mean(std::vector<double>{}), Error); }

TEST(SampleStandardDeviation, HandComputedCase) {
  // {2, 4, 4, 4, 5, 5, 7, 9}: mean 5, sum of squared deviations 32, n - 1 = 7.
  const std::vector<double> values{2, 4, 4, 4, 5, 5, 7, 9};
  EXPECT_NEAR_RELATIVE(sample_standard_deviation(values), std::sqrt(32.0 / 7.0), 1e-15);
}

TEST(SampleStandardDeviation, DoesNotCancelOnALargeOffset) {
  // The same spread on 1e9: a one-pass sum of squares would lose every digit (1e18 vs 32).
  std::vector<double> values{2, 4, 4, 4, 5, 5, 7, 9};
  for (double& v : values) v += 1e9;
  EXPECT_NEAR_RELATIVE(sample_standard_deviation(values), std::sqrt(32.0 / 7.0), 1e-15);
}

TEST(SampleStandardDeviation, NeedsTwoValues) {
  EXPECT_THROW(sample_standard_deviation(std::vector<double>{1.0}), Error);
}

TEST(WindowMeans, DropsThePartialLastWindow) {
  const std::vector<double> values{1, 2, 3, 4, 5, 6, 7};
  EXPECT_THAT(window_means(values, 3), ::testing::ElementsAre(2.0, 5.0));
  EXPECT_THAT(window_means(values, 7), ::testing::ElementsAre(4.0));
}

TEST(WindowMeans, RejectsAnEmptyOrTooLongWindow) {
  const std::vector<double> values{1, 2, 3};
  EXPECT_THROW(window_means(values, 0), Error);
  EXPECT_THROW(window_means(values, 4), Error);
}

struct ConstantCase {
  const char* name;
  std::vector<double> values;
  bool constant;
};

class IsConstant : public ::testing::TestWithParam<ConstantCase> {};

TEST_P(IsConstant, SaysWhetherEveryValueIsTheSame) {
  EXPECT_EQ(is_constant(GetParam().values), GetParam().constant);
}

INSTANTIATE_TEST_SUITE_P(
    Records, IsConstant,
    ::testing::Values(ConstantCase{"empty", {}, false}, ConstantCase{"one_value", {3.0}, false},
                      ConstantCase{"stuck", {3.0, 3.0, 3.0}, true},
                      ConstantCase{"last_differs_by_one_ulp", {3.0, 3.0, std::nextafter(3.0, 4.0)}, false},
                      ConstantCase{"first_differs", {2.0, 3.0, 3.0}, false},
                      ConstantCase{"signed_zeros_are_equal", {0.0, -0.0}, true}),
    testing::NameOfParam());

}  // namespace
}  // namespace inertest
