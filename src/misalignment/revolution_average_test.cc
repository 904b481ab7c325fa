#include "inertest/misalignment/revolution_average.h"

#include <cmath>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

// Earth-rate terms of the gyro misalignment model (misalignment paper): ωe·cosφ·(sin(ωt)·cosβ + cos(ωt)·sinβ).
double earth_terms(double table_angle_deg, double beta_deg) {
  const double horizontal = 15.041067 / 3600.0 * std::cos(45.75 * constants::kDegree);  // deg/s
  const double angle = table_angle_deg * constants::kDegree;
  const double beta = beta_deg * constants::kDegree;
  return horizontal * (std::sin(angle) * std::cos(beta) + std::cos(angle) * std::sin(beta));
}

TEST(RevolutionAverage, ByAngleCutsWholeRevolutionsOfAWrappingAngle) {
  // 0.5 deg per sample from 30 deg, wrapped to [0, 360): 2100 samples cover 1050 deg, 2 whole turns.
  std::vector<double> angle;
  std::vector<double> output;
  for (int k = 0; k < 2100; ++k) {
    const double travelled = 30.0 + 0.5 * k;
    angle.push_back(std::fmod(travelled, 360.0));
    output.push_back(0.25 + 3.0 * earth_terms(travelled, 37.0));
  }
  const RevolutionMean mean = whole_revolution_mean_by_angle(angle, output);
  EXPECT_EQ(mean.revolutions, 2u);
  EXPECT_EQ(mean.samples_used, 1440u);
  EXPECT_NEAR(mean.mean, 0.25, 1e-15);
}

TEST(RevolutionAverage, ByAngleTurningNegativeWithSignedWrap) {
  // −0.75 deg per sample, the angle reported in (−180, 180]: 1000 samples cover 750 deg.
  std::vector<double> angle;
  std::vector<double> output;
  for (int k = 0; k < 1000; ++k) {
    const double travelled = 10.0 - 0.75 * k;
    angle.push_back(std::remainder(travelled, 360.0));
    output.push_back(-1.5 + 2.0 * earth_terms(travelled, 0.0));
  }
  const RevolutionMean mean = whole_revolution_mean_by_angle(angle, output);
  EXPECT_EQ(mean.revolutions, 2u);
  EXPECT_EQ(mean.samples_used, 960u);
  EXPECT_NEAR(mean.mean, -1.5, 1e-15);
}

TEST(RevolutionAverage, ByTimeCutsFloorOfTOmegaOver360Revolutions) {
  // 100 Hz at 20 deg/s: 18 s per revolution. 4000 samples = 40 s hold floor(40·20/360) = 2 turns.
  std::vector<double> time;
  std::vector<double> output;
  for (int k = 0; k < 4000; ++k) {
    const double t = 5.0 + 0.01 * k;
    time.push_back(t);
    output.push_back(0.125 + earth_terms(20.0 * (t - 5.0), 90.0));
  }
  const RevolutionMean mean = whole_revolution_mean_by_time(time, output, -20.0);
  EXPECT_EQ(mean.revolutions, 2u);
  EXPECT_EQ(mean.samples_used, 3600u);
  EXPECT_NEAR(mean.mean, 0.125, 1e-15);
}

TEST(RevolutionAverage, ExactlyOneRevolutionOfSamplesCounts) {
  // 360 samples of 1 deg cover exactly one turn.
  std::vector<double> angle;
  std::vector<double> output;
  for (int k = 0; k < 360; ++k) {
    angle.push_back(k);
    output.push_back(k % 2 == 0 ? 1.0 : 3.0);
  }
  const RevolutionMean mean = whole_revolution_mean_by_angle(angle, output);
  EXPECT_EQ(mean.revolutions, 1u);
  EXPECT_EQ(mean.samples_used, 360u);
  EXPECT_DOUBLE_EQ(mean.mean, 2.0);
}

TEST(RevolutionAverage, LessThanOneRevolutionIsAnError) {
  // Each sample stands for the step after it: four samples 90 deg apart cover one turn, three do not.
  const std::vector<double> angle = {0, 90, 180, 270};
  const std::vector<double> short_angle = {0, 90, 180};
  const std::vector<double> output = {1, 2, 3};
  EXPECT_THAT(
      [&] {
        whole_revolution_mean_by_angle(short_angle, output, {"rec.csv", {}});
      },
      ::testing::ThrowsMessage<Error>(::testing::HasSubstr("less than one revolution")));
  const std::vector<double> time = {0, 1, 2};
  EXPECT_THAT([&] { whole_revolution_mean_by_time(time, output, 100.0); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("less than one revolution")));
  EXPECT_EQ(whole_revolution_mean_by_angle(angle, std::vector<double>{1, 2, 3, 4}).revolutions, 1u);
}

TEST(RevolutionAverage, BadRecordsAreErrorsAtTheirLine) {
  const std::vector<double> output = {1, 2, 3, 4};
  const std::vector<std::size_t> lines = {2, 3, 4, 5};
  const std::vector<double> turning_back = {0, 10, 5, 15};
  try {
    whole_revolution_mean_by_angle(turning_back, output, {"rec.csv", lines});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.location()->line, 4u);
    EXPECT_THAT(e.message(), ::testing::HasSubstr("turns back"));
  }
  const std::vector<double> half_turn = {0, 180, 0, 180};
  EXPECT_THAT([&] { whole_revolution_mean_by_angle(half_turn, output); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("half a turn")));
  const std::vector<double> stalled_time = {0, 1, 1, 2};
  EXPECT_THAT(
      [&] {
        whole_revolution_mean_by_time(stalled_time, output, 360.0, {"rec.csv", lines});
      },
      ::testing::ThrowsMessage<Error>(::testing::HasSubstr("rec.csv:4")));
  const std::vector<double> time = {0, 1, 2, 3};
  EXPECT_THAT([&] { whole_revolution_mean_by_time(time, output, 0.0); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("nonzero")));
  EXPECT_THAT(
      [&] {
        whole_revolution_mean_by_time(time, std::vector<double>{1, 2}, 90.0);
      },
      ::testing::ThrowsMessage<Error>(::testing::HasSubstr("4 time values but 2 outputs")));
}

}  // namespace
}  // namespace inertest
