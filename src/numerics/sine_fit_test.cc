#include "inertest/numerics/sine_fit.h"

#include <cmath>
#include <vector>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using constants::kPi;

struct Record {
  std::vector<double> time;
  std::vector<double> samples;
};

Record sine_record(double amplitude, double phase, double offset, double frequency_hz, double sample_rate_hz,
                   std::size_t count) {
  Record record;
  for (std::size_t i = 0; i < count; ++i) {
    const double t = static_cast<double>(i) / sample_rate_hz;
    record.time.push_back(t);
    record.samples.push_back(amplitude * std::sin(2 * kPi * frequency_hz * t + phase) + offset);
  }
  return record;
}

TEST(SineFit, RecoversAmplitudePhaseAndOffsetOfAnExactSine) {
  // 37.5 Hz sampled at 1 kHz for 0.3 s: not a whole number of periods, so the fit must not rely on
  // orthogonality of the regressors.
  const Record r = sine_record(2.5, -1.2, 0.75, 37.5, 1000.0, 300);
  const SineFit fit = fit_sine(r.time, r.samples, 2 * kPi * 37.5);
  EXPECT_NEAR_RELATIVE(fit.amplitude, 2.5, 1e-12);
  EXPECT_NEAR(fit.phase, -1.2, 1e-12);
  EXPECT_NEAR(fit.offset, 0.75, 1e-12);
  EXPECT_LT(fit.residual_rms, 1e-12);
}

TEST(SineFit, PhaseComesBackInMinusPiToPi) {
  // A phase of 3π/2 is the same sine as −π/2.
  const Record r = sine_record(1.0, 1.5 * kPi, 0.0, 5.0, 200.0, 400);
  const SineFit fit = fit_sine(r.time, r.samples, 2 * kPi * 5.0);
  EXPECT_NEAR(fit.phase, -0.5 * kPi, 1e-12);
}

TEST(SineFit, HandComputedFourSamplesPerPeriod) {
  // y at ωt = 0, π/2, π, 3π/2 is (c + k, c + s, c − k, c − s) with y = s·sin + k·cos + c.
  // y = 1, 3, −1, −3 → c = 0, k = 1, s = 3: A = √10, φ = atan2(1, 3).
  const std::vector<double> time = {0.0, 0.25, 0.5, 0.75};
  const std::vector<double> y = {1.0, 3.0, -1.0, -3.0};
  const SineFit fit = fit_sine(time, y, 2 * kPi);
  EXPECT_NEAR_RELATIVE(fit.amplitude, std::sqrt(10.0), 1e-12);
  EXPECT_NEAR(fit.phase, std::atan2(1.0, 3.0), 1e-12);
  EXPECT_NEAR(fit.offset, 0.0, 1e-12);
}

TEST(SineFit, NoisyRecordGivesUncertainties) {
  Record r = sine_record(1.0, 0.3, 0.0, 10.0, 1000.0, 1000);
  for (std::size_t i = 0; i < r.samples.size(); ++i) r.samples[i] += (i % 2 == 0 ? 1e-3 : -1e-3);
  const SineFit fit = fit_sine(r.time, r.samples, 2 * kPi * 10.0);
  EXPECT_GT(fit.amplitude_standard_error, 0.0);
  EXPECT_GT(fit.phase_standard_error, 0.0);
  EXPECT_NEAR(fit.amplitude, 1.0, 1e-3);
}

TEST(SineFit, BadInputIsAnError) {
  const std::vector<double> three = {0.0, 0.1, 0.2};
  EXPECT_THROW(fit_sine(three, three, 1.0), Error);
  const std::vector<double> time = {0.0, 0.1, 0.2, 0.3};
  const std::vector<double> five = {0.0, 0.1, 0.2, 0.3, 0.4};
  EXPECT_THROW(fit_sine(time, five, 1.0), Error);
  EXPECT_THROW(fit_sine(time, time, 0.0), Error);
  const std::vector<double> same_time = {1.0, 1.0, 1.0, 1.0};
  EXPECT_THROW(fit_sine(same_time, time, 3.0), Error);  // one phase only: rank deficient
  const std::vector<double> with_nan = {0.0, std::nan(""), 0.2, 0.3};
  EXPECT_THROW(fit_sine(time, with_nan, 1.0), Error);
}

}  // namespace
}  // namespace inertest
