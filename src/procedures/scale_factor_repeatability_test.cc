#include "inertest/procedures/scale_factor_repeatability.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "procedures/scale_factor_series_test_util.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;
using testing::linear_run;

TEST(ScaleFactorRepeatability, HandComputedSixRuns) {
  // K̄ = 100; deviations 0, 1, −1, 0, 2, −2: Σ = 10, /(Q − 1) = 2, Kr = √2/100 (eq. 12).
  const std::vector<double> k = {100, 101, 99, 100, 102, 98};
  const auto result = scale_factor_repeatability(k, "pulse/s/(deg/s)");
  EXPECT_NEAR_RELATIVE(result.scale_factor_repeatability.value, std::sqrt(2.0) / 100.0 * 1e6, 1e-12);
  EXPECT_EQ(result.scale_factor_repeatability.unit, "ppm");
  EXPECT_NEAR_RELATIVE(result.mean_scale_factor.value, 100.0, 1e-15);
  EXPECT_TRUE(result.warnings.empty());
}

TEST(ScaleFactorRepeatability, FromTheTestPointsOfEachRun) {
  const std::vector<double> k = {4999.0, 5001.5, 5000.2, 4998.7, 5000.9, 5000.0};
  std::vector<std::vector<ScaleFactorPoint>> runs;
  for (double ki : k) runs.push_back(linear_run(ki, 0.1 * ki));
  const auto result = scale_factor_repeatability(runs);
  double mean = 0;
  for (double ki : k) mean += ki / 6.0;
  double ss = 0;
  for (double ki : k) ss += (ki - mean) * (ki - mean);
  EXPECT_NEAR_RELATIVE(result.scale_factor_repeatability.value, std::sqrt(ss / 5.0) / mean * 1e6, 1e-9);
  ASSERT_EQ(result.run_scale_factors.size(), 6u);
  EXPECT_NEAR_RELATIVE(result.run_scale_factors[1].value, 5001.5, 1e-12);
  const auto fields = find_procedure_spec("scale_factor_repeatability")->fields_of(&result);
  EXPECT_EQ(fields.at("scale_factor_repeatability").at("unit"), "ppm");
  EXPECT_EQ(fields.at("runs"), 6);
}

TEST(ScaleFactorRepeatability, FewerThanSixRunsIsAnErrorUnlessAllowed) {
  const std::vector<double> k = {100, 101, 99};
  try {
    scale_factor_repeatability(k, "1");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("Q >= 6"));
  }
  ScaleFactorRepeatabilityOptions options;
  options.minimum_runs = 3;
  const auto result = scale_factor_repeatability(k, "1", options);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], HasSubstr("at least 6"));
  options.minimum_runs = 1;
  EXPECT_THROW(scale_factor_repeatability(k, "1", options), Error);
}

TEST(ScaleFactorRepeatability, ABadRunIsNamed) {
  std::vector<std::vector<ScaleFactorPoint>> runs(6, linear_run(10.0));
  runs[3].erase(runs[3].begin());  // no static run at the start
  try {
    scale_factor_repeatability(runs);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("run 4"));
    EXPECT_THAT(e.message(), HasSubstr("static run at the start"));
  }
}

// A run of the other sign is reversed, not scatter (one of six gave Kr = 1 224 741 ppm, unsaid).
TEST(ScaleFactorRepeatability, ARunOfTheOtherSignIsAnError) {
  std::vector<std::vector<ScaleFactorPoint>> runs(6, linear_run(36000.0));
  runs[4] = linear_run(-36000.0);
  try {
    scale_factor_repeatability(runs);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.message(), "scale factor repeatability: run 5 has K = -36000 and run 1 K = 36000: a run of the other "
                           "sign (or zero) is reversed (the rates' or the output's sign), not scatter");
  }
  // Every run reversed alike is one sign convention: Kr as before.
  const std::vector<double> negative = {-100, -101, -99, -100, -102, -98};
  EXPECT_NEAR_RELATIVE(scale_factor_repeatability(negative, "pulse/s/(deg/s)").scale_factor_repeatability.value,
                       std::sqrt(2.0) / 100.0 * 1e6, 1e-12);
}

}  // namespace
}  // namespace inertest
