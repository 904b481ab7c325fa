#include "inertest/procedures/turn_on_time.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

constexpr double kPi = 3.14159265358979323846;
const double kEarthDegS = 7.2921150e-5 / (kPi / 180.0);

// A run whose indicated error decays as a·exp(-t/τ) (deg/s), sampled at rate from power-on, with
// sample i at (i + 1)/rate.
PowerOnRun decaying_run(double input_deg_s, double a, double tau, double k, double zero, double earth_deg_s,
                        double rate, double duration) {
  PowerOnRun run;
  run.name = "run";
  run.input_rate_deg_s = input_deg_s;
  for (int i = 0; (i + 1) / rate <= duration; ++i) {
    const double t = (i + 1) / rate;
    run.time_s.push_back(t);
    run.output.push_back(zero + k * (input_deg_s + earth_deg_s + a * std::exp(-t / tau)));
  }
  return run;
}

// The first sample time at or after τ·ln(a / band), where the error enters the band for good.
double first_sample_within(double a, double tau, double band, double rate) {
  const double settle = tau * std::log(a / band);
  return std::ceil(settle * rate) / rate;
}

TEST(TurnOnTimeTest, AtRestAndAtRateLargestOverRuns) {
  TurnOnTimeOptions options;
  options.scale_factor = 100.0;
  options.zero_output = 3.0;
  options.rest_band_deg_h = 0.5;   // 0.5 deg/h
  options.rate_band = 1e-3;
  const double rate = 10.0;
  // At rest: error 0.01 deg/s decaying with τ = 20 s into 0.5 deg/h.
  const PowerOnRun rest = decaying_run(0.0, 0.01, 20.0, 100.0, 3.0, 0.0, rate, 300.0);
  // At 10 deg/s: error 0.5 deg/s decaying with τ = 5 s into 1e-3 x 10 deg/s.
  PowerOnRun at_rate = decaying_run(10.0, 0.5, 5.0, 100.0, 3.0, 0.0, rate, 300.0);
  at_rate.name = "at rate";
  const std::vector<PowerOnRun> runs = {rest, at_rate};
  const TurnOnTimeResult result = turn_on_time(runs, options);
  const double rest_time = first_sample_within(0.01, 20.0, 0.5 / 3600.0, rate);
  const double rate_time = first_sample_within(0.5, 5.0, 1e-2, rate);
  EXPECT_NEAR(result.runs[0].time.value, rest_time, 1e-9);
  EXPECT_NEAR(result.runs[1].time.value, rate_time, 1e-9);
  EXPECT_NEAR(result.time.value, std::max(rest_time, rate_time), 1e-9);
  EXPECT_EQ(turn_on_time_spec().fields_of(&result).at("turn_on_time").at("unit"), "s");
}

// A run that settles in the record's last tenth is said: at the noise of single samples that is
// as likely the last crossing of the band as the settling (3593 s of 3600 for a gyro settled at
// 210 s). One that settles early is not.
TEST(TurnOnTimeTest, ATimeInTheRecordsLastTenthIsWarnedAbout) {
  TurnOnTimeOptions options;
  options.scale_factor = 100.0;
  options.rest_band_deg_h = 0.5;
  const PowerOnRun early = decaying_run(0.0, 0.01, 20.0, 100.0, 0.0, 0.0, 10.0, 300.0);
  EXPECT_TRUE(turn_on_time(std::vector<PowerOnRun>{early}, options).warnings.empty());
  PowerOnRun late = early;
  late.output[late.output.size() - 20] = 1.0;  // one sample out of the band 2 s before the end
  const TurnOnTimeResult result = turn_on_time(std::vector<PowerOnRun>{late}, options);
  EXPECT_NEAR(result.time.value, 298.2, 1e-9);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], ::testing::HasSubstr("run 'run' enters the band for good only at 298.2 s, 1.8 s before "
                                                       "its record ends"));
  EXPECT_THAT(result.warnings[0], ::testing::HasSubstr("smoothing_s averages it"));
}

TEST(TurnOnTimeTest, EarthRateRemovedFromTheRateTestOnly) {
  // GJB 2426A 5.5.4. At 1 deg/s with the IRA up at 45 deg N, Ωe sin 45° rides on the output:
  // unremoved it exceeds a relative band of 1e-3 (3.6 deg/h).
  TurnOnTimeOptions options;
  options.scale_factor = 1.0;
  options.rate_band = 1e-3;
  options.rest_band_deg_h = 1.0;
  const double earth = kEarthDegS * std::sin(45.0 * kPi / 180.0);
  PowerOnRun at_rate = decaying_run(1.0, 0.01, 10.0, 1.0, 0.0, earth, 1.0, 200.0);
  at_rate.name = "at rate";
  EXPECT_THROW(turn_on_time(std::vector<PowerOnRun>{at_rate}, options), Error);  // never settles with Earth rate in
  options.earth_rate = AxisOrientation{45.0, 0.0, 90.0};
  options.warm_up = true;
  const TurnOnTimeResult result = turn_on_time(std::vector<PowerOnRun>{at_rate}, options);
  EXPECT_NEAR(result.time.value, first_sample_within(0.01, 10.0, 1e-3, 1.0), 1e-9);
  EXPECT_TRUE(warm_up_time_spec().fields_of(&result).contains("warm_up_time"));
  // At rest (the position test, IRA east or west) only the calibrated zero is removed: the same
  // Earth rate subtracted from a run at rest put it 10.6 deg/h off, outside its 1 deg/h band.
  const PowerOnRun rest = decaying_run(0.0, 0.01, 10.0, 1.0, 0.0, 0.0, 1.0, 200.0);
  const TurnOnTimeResult both = turn_on_time(std::vector<PowerOnRun>{rest, at_rate}, options);
  EXPECT_NEAR(both.runs[0].time.value, first_sample_within(0.01, 10.0, 1.0 / 3600.0, 1.0), 1e-9);
  // Asked for with every run at rest it would do nothing: an error, not a silent "never settles".
  EXPECT_THAT([&] { turn_on_time(std::vector<PowerOnRun>{rest}, options); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("every run is at rest: leave out remove_earth_rate")));
}

TEST(TurnOnTimeTest, SmoothingAveragesWindowsFromPowerOn) {
  // Samples at 0.5 s steps: 9, 9, 1, -1, 0.5, 0.5, 0, 0; band 0.6 deg/h (K = 3600 per deg/s makes
  // one output unit one deg/h). Unsmoothed, the last failing sample is -1 at 2.0 s: turn-on 2.5 s.
  PowerOnRun run{"r", 0.0, {0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0}, {9, 9, 1, -1, 0.5, 0.5, 0, 0}};
  TurnOnTimeOptions options;
  options.scale_factor = 3600.0;
  options.rest_band_deg_h = 0.6;
  const std::vector<PowerOnRun> runs = {run};
  EXPECT_DOUBLE_EQ(turn_on_time(runs, options).time.value, 2.5);
  options.smoothing_s = 1.0;
  // A stamp ends its sample's interval: window (0,1] holds t = 0.5 and 1.0 -> mean 9, fails; (1,2]
  // 1.5, 2.0 -> 0; (2,3] 2.5, 3.0 -> 0.5; (3,4] 3.5, 4.0 -> 0. Turn-on at the end of (1,2]: 2 s.
  EXPECT_DOUBLE_EQ(turn_on_time(runs, options).time.value, 2.0);
  // Ten samples of 100 then ninety of 0 at 10 Hz (stamps 0.1 .. 10.0 s, 3 x 0.1 not exactly 0.3):
  // 1.1 s unsmoothed, 2 s in 1 s windows (the sample stamped 1.0 s is the first window's).
  PowerOnRun step{"step", 0.0, {}, {}};
  for (int i = 0; i < 100; ++i) {
    step.time_s.push_back((i + 1) * 0.1);
    step.output.push_back(i < 10 ? 100.0 : 0.0);
  }
  const std::vector<PowerOnRun> steps = {step};
  options.smoothing_s = 0.0;
  EXPECT_NEAR(turn_on_time(steps, options).time.value, 1.1, 1e-12);
  options.smoothing_s = 1.0;
  EXPECT_DOUBLE_EQ(turn_on_time(steps, options).time.value, 2.0);
  // A window the record ends inside is no mean of the smoothing time: with 3 s, (3,6] holds the
  // settled 3.5-4.0 s only, and stamped at 6 s it gave a turn-on time after the record's end.
  PowerOnRun late{"late", 0.0, run.time_s, {9, 9, 9, 9, 9, 0, 0, 0}};
  options.smoothing_s = 3.0;
  EXPECT_THROW(turn_on_time(std::vector<PowerOnRun>{late}, options), Error);
  options.smoothing_s = 5.0;
  try {
    turn_on_time(runs, options);
    ADD_FAILURE() << "a record shorter than one window was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.message(), "turn-on time: run 'r' ends at 4 s, inside its first smoothing window of 5 s");
  }
}

TEST(TurnOnTimeTest, BadInputIsAnError) {
  TurnOnTimeOptions options;
  options.scale_factor = 1.0;
  options.rest_band_deg_h = 1.0;
  EXPECT_THROW(turn_on_time(std::vector<PowerOnRun>{}, options), Error);  // no runs
  EXPECT_THROW(turn_on_time(std::vector<PowerOnRun>{{"r", 0.0, {1.0}, {0.0}}}, options), Error);  // one sample
  EXPECT_THROW(turn_on_time(std::vector<PowerOnRun>{{"r", 0.0, {2.0, 1.0}, {0.0, 0.0}}}, options), Error);
  EXPECT_THROW(turn_on_time(std::vector<PowerOnRun>{{"r", 5.0, {1.0, 2.0}, {5.0, 5.0}}}, options), Error);  // no rate band
  EXPECT_THROW(turn_on_time(std::vector<PowerOnRun>{{"r", 0.0, {1.0, 2.0}, {0.0, 1.0}}}, options), Error);  // never settles
  // Stamps of a clock, not from power-on: the figure was that clock's reading, 1.7e9 s.
  try {
    turn_on_time(std::vector<PowerOnRun>{{"r", 0.0, {1.7e9, 1.7e9 + 1.0, 1.7e9 + 2.0}, {0.0, 0.0, 0.0}}}, options);
    ADD_FAILURE() << "epoch stamps accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("its times start at 1.7e+09 s, later than the record lasts (2 s)"));
  }
  TurnOnTimeOptions zero_k = options;
  zero_k.scale_factor = 0.0;
  EXPECT_THROW(turn_on_time(std::vector<PowerOnRun>{{"r", 0.0, {1.0, 2.0}, {0.0, 0.0}}}, zero_k), Error);
}

}  // namespace
}  // namespace inertest
