#include "inertest/procedures/rate_segments.h"

#include <cmath>
#include <string>
#include <vector>

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;

constexpr double kSampleRate = 10.0;  // Hz
constexpr double kScale = 3.0;        // output per deg/s
constexpr double kBias = 0.5;

struct Record {
  std::vector<double> rate;
  std::vector<double> output;
};

// A segment of `seconds` at `rate`: the first second carries a start-up transient of +100 that the
// settling time must remove; the rest is exactly kScale·rate + kBias.
void add_segment(Record& record, double rate, double seconds) {
  const auto count = static_cast<std::size_t>(seconds * kSampleRate);
  for (std::size_t i = 0; i < count; ++i) {
    record.rate.push_back(rate);
    record.output.push_back(kScale * rate + kBias + (i < kSampleRate ? 100.0 : 0.0));
  }
}

// A ramp between two rates, one sample per step: no sample stays within the tolerance long enough.
void add_ramp(Record& record, double from, double to) {
  for (int i = 1; i < 10; ++i) {
    const double rate = from + (to - from) * i / 10.0;
    record.rate.push_back(rate);
    record.output.push_back(kScale * rate + kBias);
  }
}

RateSegmentOptions options() {
  RateSegmentOptions o;
  o.timing = {kSampleRate, 1.0};
  o.minimum_segment_s = 2.0;
  o.rate_tolerance = 1e-3;
  return o;
}

TEST(RecordMean, DropsTheSettlingTime) {
  // Eq. (1) after dropping 0.3 s at 10 Hz = 3 samples: mean of 4, 5, 6 = 5.
  const std::vector<double> output = {100, 100, 100, 4, 5, 6};
  EXPECT_DOUBLE_EQ(record_mean(output, {10.0, 0.3}), 5.0);
  EXPECT_DOUBLE_EQ(record_mean(output, {10.0, 0.0}), 315.0 / 6.0);
}

TEST(RecordMean, SettlingTimeLongerThanTheRecordIsAnError) {
  const std::vector<double> output = {1, 2, 3};
  try {
    record_mean(output, {10.0, 0.3});
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("not shorter than the record"));
  }
  EXPECT_THROW(record_mean(output, {0.0, 0.0}), Error);
  EXPECT_THROW(record_mean(output, {10.0, -1.0}), Error);
}

TEST(RateSegments, CutsARecordIntoConstantRatePointsInTestOrder) {
  Record record;
  add_segment(record, 0.0, 5.0);
  add_ramp(record, 0.0, 10.0);
  add_segment(record, 10.0, 4.0);
  add_ramp(record, 10.0, -10.0);
  add_segment(record, -10.0, 3.0);
  add_segment(record, 20.0, 3.0);
  add_segment(record, -20.0, 3.0);
  add_segment(record, 0.0, 5.0);
  // Rest-rate jitter of the table within the tolerance is still rest.
  record.rate[3] = 4e-4;

  const std::vector<RateSegment> segments = segment_by_rate(record.rate, record.output, options());
  ASSERT_EQ(segments.size(), 6u);
  const std::vector<double> rates = {0.0, 10.0, -10.0, 20.0, -20.0, 0.0};
  for (std::size_t i = 0; i < rates.size(); ++i) {
    EXPECT_NEAR(segments[i].rate, rates[i], 1e-4) << i;
    EXPECT_NEAR(segments[i].mean_output, kScale * segments[i].rate + kBias, 1e-12) << i;
  }
  EXPECT_EQ(segments[0].rate, 0.0);  // a static run is exactly zero
  EXPECT_EQ(segments[1].first_sample, 59u);   // 50 samples at rest, 9 ramp samples
  EXPECT_EQ(segments[1].first_used, 69u);     // + 1 s settling
  EXPECT_EQ(segments[1].end_sample, 99u);

  const std::vector<ScaleFactorPoint> points = scale_factor_points(segments);
  ASSERT_EQ(points.size(), 6u);
  const ScaleFactorResult result = scale_factor(points);
  EXPECT_NEAR_RELATIVE(result.scale_factor.value, kScale, 1e-9);
}

TEST(RateSegments, NoiseOfTheMeasuredRateWithinTheToleranceKeepsEachPlateauWhole) {
  // A measured table-rate column: uniform noise of half-width 0.9 x tolerance. Against a segment's
  // first sample two samples differ by up to 1.8 x tolerance, which cut the plateaus into pieces
  // (points added, short pieces dropped); against the running mean each plateau is one segment.
  Record record;
  for (const double rate : {0.0, 10.0, -10.0, 20.0, -20.0, 0.0}) {
    add_segment(record, rate, 30.0);
    add_ramp(record, rate, rate == 0.0 ? 10.0 : 0.0);
  }
  testing::UniformSequence noise(7);
  for (double& rate : record.rate) rate += 1.8 * options().rate_tolerance * noise.next();
  // A lone glitch of the rate column is no change of rate.
  record.rate[100] += 0.5;
  const std::vector<RateSegment> segments = segment_by_rate(record.rate, record.output, options());
  const std::vector<double> rates = {0.0, 10.0, -10.0, 20.0, -20.0, 0.0};
  ASSERT_EQ(segments.size(), rates.size());
  for (std::size_t i = 0; i < rates.size(); ++i) {
    EXPECT_NEAR(segments[i].rate, rates[i], 0.5 / 290.0 + 1e-3) << i;
    EXPECT_EQ(segments[i].end_sample - segments[i].first_sample, 300u) << i;
  }
}

TEST(RateSegments, AGlitchOfTheMeasuredRateIsLeftOutOfThePoint) {
  // One rate sample of the 300 deg/s plateau drops to 0 (the output does not): no change of rate,
  // and no part of the point's rate (kept in its mean, it moved K by 0.15 %).
  Record record;
  add_segment(record, 0.0, 3.0);
  add_segment(record, 300.0, 3.0);
  add_segment(record, 0.0, 3.0);
  record.rate[45] = 0.0;
  const std::vector<RateSegment> segments = segment_by_rate(record.rate, record.output, options());
  ASSERT_EQ(segments.size(), 3u);
  EXPECT_EQ(segments[1].rate, 300.0);
  EXPECT_EQ(segments[1].mean_output, kScale * 300.0 + kBias);
  EXPECT_EQ(segments[1].end_sample - segments[1].first_sample, 30u);
}

TEST(RateSegments, PiecesOfASlowRampAreNoTestPoints) {
  // 1 deg/s^2 ramps at 10 Hz with a tolerance of 1 deg/s: a piece stays within the tolerance of its
  // running mean for about 2 s, the minimum segment, but its rate moves by about 1 deg/s across it.
  RateSegmentOptions slow = options();
  slow.rate_tolerance = 1.0;
  Record record;
  const auto ramp = [&](double from, double to) {
    const int steps = static_cast<int>(std::abs(to - from) * kSampleRate);
    for (int i = 1; i < steps; ++i) {
      const double rate = from + (to - from) * i / steps;
      record.rate.push_back(rate);
      record.output.push_back(kScale * rate + kBias);
    }
  };
  add_segment(record, 0.0, 5.0);
  ramp(0.0, 10.0);
  add_segment(record, 10.0, 5.0);
  ramp(10.0, -10.0);
  add_segment(record, -10.0, 5.0);
  ramp(-10.0, 0.0);
  add_segment(record, 0.0, 5.0);
  const std::vector<RateSegment> segments = segment_by_rate(record.rate, record.output, slow);
  const std::vector<double> rates = {0.0, 10.0, -10.0, 0.0};
  ASSERT_EQ(segments.size(), rates.size());
  for (std::size_t i = 0; i < rates.size(); ++i) EXPECT_NEAR(segments[i].rate, rates[i], 0.2) << i;
}

TEST(RateSegments, ShortSegmentsAreSkipped) {
  Record record;
  add_segment(record, 0.0, 3.0);
  add_segment(record, 5.0, 1.5);  // shorter than the 2 s minimum
  add_segment(record, 10.0, 3.0);
  const auto segments = segment_by_rate(record.rate, record.output, options());
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_EQ(segments[1].rate, 10.0);
}

// Test rates of +-0.001 deg/s at the tolerance 0.001 joined the static runs (F̄s moved by half
// their output, F0 by 1000 sigma) and two test points vanished: the next rate, 0.002, within 2.5
// tolerances of zero, says so; a tolerance below the smallest rate / 2.5 keeps them all.
TEST(RateSegments, ATestRateWithinAFewTolerancesOfZeroIsAnError) {
  Record record;
  add_segment(record, 0.0, 3.0);
  for (double rate : {-0.001, -0.002, -10.0, 0.001, 0.002, 10.0}) add_segment(record, rate, 3.0);
  add_segment(record, 0.0, 3.0);
  try {
    segment_by_rate(record.rate, record.output, options());
    FAIL() << "the +-0.001 deg/s plateaus were taken for static runs";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("rate segments: the test rate -0.002 lies within 2.5 rate tolerances (0.001) of "
                                       "zero: a smaller test rate may have been taken for a static run"));
  }
  auto fine = options();
  fine.rate_tolerance = 2e-4;
  EXPECT_EQ(segment_by_rate(record.rate, record.output, fine).size(), 8u);
  // A small rate well clear of the tolerance is a test point: 0.004 at 0.0015.
  Record clear;
  add_segment(clear, 0.0, 3.0);
  for (double rate : {-0.004, -10.0, 0.004, 10.0}) add_segment(clear, rate, 3.0);
  add_segment(clear, 0.0, 3.0);
  auto wide = options();
  wide.rate_tolerance = 1.5e-3;
  EXPECT_EQ(segment_by_rate(clear.rate, clear.output, wide).size(), 6u);
}

TEST(RateSegments, RecordWithoutStaticRunsGivesTheScaleFactorError) {
  Record record;
  add_segment(record, 10.0, 3.0);
  add_segment(record, -10.0, 3.0);
  add_segment(record, 20.0, 3.0);
  add_segment(record, -20.0, 3.0);
  add_segment(record, 0.0, 3.0);
  const auto points = scale_factor_points(segment_by_rate(record.rate, record.output, options()));
  try {
    scale_factor(points);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("missing the static run at the start"));
  }
}

TEST(RateSegments, BadInputIsAnError) {
  Record record;
  add_segment(record, 0.0, 1.5);
  auto o = options();
  EXPECT_THROW(segment_by_rate(record.rate, record.output, o), Error);  // no segment of 2 s
  std::vector<double> shorter(record.output.begin(), record.output.end() - 1);
  EXPECT_THROW(segment_by_rate(record.rate, shorter, o), Error);
  o.minimum_segment_s = 1.0;  // not above the settling time
  try {
    segment_by_rate(record.rate, record.output, o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("must exceed the settling time"));
  }
  o = options();
  o.rate_tolerance = -1.0;
  EXPECT_THROW(segment_by_rate(record.rate, record.output, o), Error);
  record.rate[2] = std::nan("");
  EXPECT_THROW(segment_by_rate(record.rate, record.output, options()), Error);
}

}  // namespace
}  // namespace inertest
