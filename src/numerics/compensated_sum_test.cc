#include "inertest/numerics/compensated_sum.h"

#include <vector>

#include <gtest/gtest.h>

namespace inertest {
namespace {

TEST(CompensatedSum, KeepsASmallTermBetweenTwoLargeOnes) {
  // Naively 1e16 + 1 rounds to 1e16 and the sum ends at 0; Neumaier's correction keeps the 1.
  EXPECT_EQ(compensated_sum(std::vector<double>{1e16, 1.0, -1e16}), 1.0);
}

TEST(CompensatedSum, KeepsTermsSmallerThanTheRunningSumsUlp) {
  // 1 + 10^6 · 1e-17: each term is below half an ulp of 1 and a naive sum never moves.
  std::vector<double> values(1'000'001, 1e-17);
  values.front() = 1.0;
  EXPECT_DOUBLE_EQ(compensated_sum(values), 1.0 + 1e-11);
}

TEST(CompensatedSum, MergedPartsEqualTheWhole) {
  // How threads combine their chunks: the parts' compensations are carried over.
  std::vector<double> values;
  for (int i = 0; i < 100'000; ++i) values.push_back(1e8 + 0.1 * (i % 7));
  CompensatedSum whole;
  CompensatedSum first;
  CompensatedSum second;
  for (std::size_t i = 0; i < values.size(); ++i) {
    whole += values[i];
    (i < values.size() / 3 ? first : second) += values[i];
  }
  first.merge(second);
  EXPECT_DOUBLE_EQ(first.value(), whole.value());
}

}  // namespace
}  // namespace inertest
