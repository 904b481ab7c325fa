#include "inertest/procedures/bandwidth_and_delay.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/sim/random.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using constants::kPi;
using ::testing::ContainsRegex;
using ::testing::HasSubstr;
using ::testing::Not;

// The result's fields as its spec writes them (JSON and text).
nlohmann::json fields_of(const BandwidthResult& result) { return find_procedure_spec("bandwidth")->fields_of(&result); }

// First-order lag with a pure delay (eq. 42): G(jω) = K/(jωT + 1)·e^(−jωTd).
struct Lag {
  double k = 1.0;
  double bandwidth_hz = 300.0;
  double delay_s = 2e-4;
  double t() const { return 1.0 / (2 * kPi * bandwidth_hz); }
  double gain(double f) const { return k / std::sqrt(1 + std::pow(2 * kPi * f * t(), 2)); }
  double phase(double f) const { return -std::atan(2 * kPi * f * t()) - 2 * kPi * f * delay_s; }
};

std::vector<double> log_spaced(double from, double to, std::size_t n) {
  std::vector<double> f;
  for (std::size_t i = 0; i < n; ++i) f.push_back(from * std::pow(to / from, static_cast<double>(i) / (n - 1)));
  return f;
}

std::vector<FrequencyResponsePoint> response(const Lag& lag, const std::vector<double>& frequencies) {
  std::vector<FrequencyResponsePoint> points;
  for (double f : frequencies) points.push_back({f, lag.gain(f), lag.phase(f)});
  return points;
}

TEST(BandwidthAndDelay, FirstOrderLagWithDelayGivesItsParametersBack) {
  const Lag lag{1.3, 300.0, 2e-4};
  const auto result = bandwidth_and_delay(response(lag, log_spaced(10.0, 1000.0, 12)));
  EXPECT_NEAR_RELATIVE(result.bandwidth.value, 300.0, 1e-9);
  EXPECT_EQ(result.bandwidth.unit, "Hz");
  EXPECT_NEAR_RELATIVE(result.delay.value, 2e-4, 1e-9);
  EXPECT_EQ(result.delay.unit, "s");
  EXPECT_NEAR_RELATIVE(result.dc_gain.value, 1.3, 1e-9);
  EXPECT_NEAR_RELATIVE(result.time_constant.value, lag.t(), 1e-9);
  ASSERT_TRUE(result.bandwidth.uncertainty.has_value());
  EXPECT_LT(*result.bandwidth.uncertainty, 1e-9);  // exact data: no scatter
  ASSERT_EQ(result.bode.size(), 12u);
  for (const auto& p : result.bode) {
    EXPECT_NEAR_RELATIVE(p.fitted_gain, p.gain, 1e-9);
    EXPECT_NEAR(p.fitted_phase_deg, p.phase_deg, 1e-7);
  }
  EXPECT_TRUE(result.warnings.empty());
}

// Phases that are not eq. (43)'s give a negative delay or a poor phase fit: each is said (the
// delay came out -0.3 ms with a 69 deg rms residual and no word).
TEST(BandwidthAndDelay, PhasesThatAreNotTheOutputsLagAreSaid) {
  const Lag lag{1.0, 300.0, 2e-4};
  const auto frequencies = log_spaced(10.0, 1000.0, 12);
  std::vector<FrequencyResponsePoint> lead = response(lag, frequencies);  // a lag entered as a positive number
  for (auto& p : lead) p.phase_rad = -p.phase_rad;
  std::vector<FrequencyResponsePoint> angle = response(lag, frequencies);  // against the angle: +90 deg
  for (auto& p : angle) p.phase_rad += kPi / 2.0;
  const auto reversed = bandwidth_and_delay(lead);
  EXPECT_LT(reversed.delay.value, 0.0);
  EXPECT_THAT(fields_of(reversed)["warnings"].dump(), HasSubstr("is negative (the output would lead the input)"));
  const auto against_angle = bandwidth_and_delay(angle);
  EXPECT_GT(against_angle.phase_fit_residual_rms.value, 10.0);
  EXPECT_THAT(fields_of(against_angle)["warnings"].dump(), HasSubstr("the phases depart from eq. (42)'s lag and delay"));
  // A delay of zero within its scatter is no warning.
  const Lag none{1.0, 300.0, 0.0};
  EXPECT_TRUE(bandwidth_and_delay(response(none, frequencies)).warnings.empty());
}

TEST(BandwidthAndDelay, HandComputedThreePoints) {
  // Gains with G² = 1/(1 + ω²T²) for T² = 1e-6 s² exactly at ω = 100, 200, 400 rad/s:
  // G² = 1/1.01, 1/1.04, 1/1.16. Phase 0 everywhere: Td = Σω(−atan(ωT))/Σω².
  std::vector<FrequencyResponsePoint> points;
  double num = 0;
  double den = 0;
  for (double w : {100.0, 200.0, 400.0}) {
    points.push_back({w / (2 * kPi), 1.0 / std::sqrt(1 + w * w * 1e-6), 0.0});
    num += w * -std::atan(w * 1e-3);
    den += w * w;
  }
  BandwidthOptions options;
  options.minimum_frequencies = 3;
  const auto result = bandwidth_and_delay(points, options);
  EXPECT_NEAR_RELATIVE(result.time_constant.value, 1e-3, 1e-9);
  EXPECT_NEAR_RELATIVE(result.bandwidth.value, 1.0 / (2 * kPi * 1e-3), 1e-9);
  EXPECT_NEAR_RELATIVE(result.delay.value, num / den, 1e-9);
  EXPECT_FALSE(result.warnings.empty());  // fewer than 10 and below 2·Bw
}

TEST(BandwidthAndDelay, PhaseLagsPastHalfATurnAreUnwrapped) {
  // Delay 1 ms: the lag passes −180° near 400 Hz. Phases given wrapped to (−180°, 180°].
  const Lag lag{1.0, 400.0, 1e-3};
  auto points = response(lag, log_spaced(10.0, 1000.0, 15));
  for (auto& p : points) p.phase_rad = std::remainder(p.phase_rad, 2 * kPi);
  const auto result = bandwidth_and_delay(points);
  EXPECT_NEAR_RELATIVE(result.delay.value, 1e-3, 1e-9);
  EXPECT_NEAR_RELATIVE(result.bandwidth.value, 400.0, 1e-9);
}

// Bw 500 Hz, Td 1.5 ms over 10 frequencies from 10 to 1000 Hz (5.13.3 a): the lag grows by 230 deg
// between the last two. A gyro's lag grows with frequency, so the step is taken as lag whatever
// turn the phases are given in (±180, 0 to -360, 0 to 360, unwrapped, either polarity); taken the
// short way it was -130 deg and Td 0.86 ms, and a first phase of 354 deg read as a negative
// polarity. The warning says the step was taken as lag.
TEST(BandwidthAndDelay, PhasesInAnyTurnTakeTheLagAsGrowing) {
  for (const double bandwidth : {500.0, 100.0}) {
    const Lag lag{1.0, bandwidth, 1.5e-3};
    const auto truth = response(lag, log_spaced(bandwidth == 500.0 ? 10.0 : 5.0, bandwidth == 500.0 ? 1000.0 : 600.0,
                                                bandwidth == 500.0 ? 10 : 15));
    for (const double shift : {0.0, -2 * kPi, 2 * kPi}) {
      for (const bool negative : {false, true}) {
        for (const bool wrapped : {false, true}) {
          auto points = truth;
          for (auto& p : points) {
            p.phase_rad += (negative ? kPi : 0.0);
            if (wrapped) p.phase_rad = std::remainder(p.phase_rad, 2 * kPi);
            p.phase_rad += shift;
          }
          const auto result = bandwidth_and_delay(points);
          EXPECT_NEAR_RELATIVE(result.delay.value, 1.5e-3, 1e-9)
              << bandwidth << " Hz, shift " << shift << (negative ? ", negative" : "") << (wrapped ? ", wrapped" : "");
          EXPECT_EQ(result.polarity, negative ? -1 : 1) << bandwidth << " " << shift;
        }
      }
    }
  }
  const auto sparse = bandwidth_and_delay(response(Lag{1.0, 500.0, 1.5e-3}, log_spaced(10.0, 1000.0, 10)));
  EXPECT_THAT(nlohmann::json(sparse.warnings).dump(),
              HasSubstr("the lag grows by up to 230 deg between neighbouring frequencies, taken as a lag"));
}

TEST(BandwidthAndDelay, NegativePolarityIsRemovedBeforeTheDelayFit) {
  // A gyro of negative scale factor (the misalignment paper's K = -2.9222 V/(deg/s)): every phase
  // is the lag's plus 180 deg, given wrapped to (-180, 180]. The delay stays 0.2 ms.
  const Lag lag{1.0, 300.0, 2e-4};
  auto points = response(lag, log_spaced(10.0, 1000.0, 12));
  for (auto& p : points) p.phase_rad = std::remainder(p.phase_rad + kPi, 2 * kPi);
  const auto result = bandwidth_and_delay(points);
  EXPECT_EQ(result.polarity, -1);
  EXPECT_NEAR_RELATIVE(result.delay.value, 2e-4, 1e-9);
  EXPECT_NEAR_RELATIVE(result.bandwidth.value, 300.0, 1e-9);
  EXPECT_NEAR(result.bode.front().phase_deg, lag.phase(10.0) / constants::kDegree, 1e-9);
  EXPECT_TRUE(result.warnings.empty());
  EXPECT_EQ(fields_of(result).at("polarity"), -1);
  EXPECT_THAT(procedure_text(*find_procedure_spec("bandwidth"), fields_of(result)),
              ContainsRegex("polarity +negative"));
  // The same lag with positive polarity reports +1.
  EXPECT_EQ(bandwidth_and_delay(response(lag, log_spaced(10.0, 1000.0, 12))).polarity, 1);
}

TEST(BandwidthAndDelay, NoisyGainsGiveUncertainties) {
  const Lag lag;
  auto points = response(lag, log_spaced(10.0, 1000.0, 12));
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i].gain *= 1 + (i % 2 == 0 ? 1e-3 : -1e-3);
    points[i].phase_rad += (i % 3 == 0 ? 1e-3 : -5e-4);
  }
  const auto result = bandwidth_and_delay(points);
  EXPECT_NEAR(result.bandwidth.value, 300.0, 3.0);
  EXPECT_GT(*result.bandwidth.uncertainty, 0.0);
  EXPECT_GT(*result.delay.uncertainty, 0.0);
  EXPECT_GT(*result.dc_gain.uncertainty, 0.0);
}

// Monte Carlo coverage of the 1-sigma uncertainties (1000 trials of 12 frequencies, 5 to 250 Hz, of
// a 100 Hz lag with a 2 ms delay): noise of a fixed size on the output (its relative size on Gi and
// its phase error grow as 1/Gi) and noise of a fixed relative size. With 10 degrees of freedom the
// truth lies within 1 sigma in P(|t_10| < 1) = 0.66 of trials (binomial sd 0.015); one residual
// variance for all frequencies gave 0.48 (bandwidth) and 0.45 (delay) with the fixed noise.
TEST(BandwidthAndDelay, UncertaintiesCoverTheTruthWhenTheNoiseGrowsWithFrequency) {
  const Lag lag{1.0, 100.0, 2e-3};
  const std::vector<double> frequencies = log_spaced(5.0, 250.0, 12);
  for (const bool fixed_size : {true, false}) {
    sim::Random random(fixed_size ? 7 : 8);
    int bandwidth_covered = 0;
    int delay_covered = 0;
    constexpr int kTrials = 1000;
    for (int trial = 0; trial < kTrials; ++trial) {
      std::vector<FrequencyResponsePoint> points = response(lag, frequencies);
      std::vector<double> noise;
      for (const FrequencyResponsePoint& p : points) noise.push_back(0.005 * random.normal() * (fixed_size ? 1.0 : p.gain));
      const double lowest = points.front().gain + noise.front();  // Gi = Fi / FL (eq. 35)
      for (std::size_t i = 0; i < points.size(); ++i) {
        const double gain = points[i].gain;
        points[i].gain = (gain + noise[i]) / lowest;
        points[i].phase_rad += 0.005 * random.normal() / (fixed_size ? gain : 1.0);
      }
      const BandwidthResult result = bandwidth_and_delay(points);
      bandwidth_covered += std::abs(result.bandwidth.value - 100.0) <= *result.bandwidth.uncertainty ? 1 : 0;
      delay_covered += std::abs(result.delay.value - 2e-3) <= *result.delay.uncertainty ? 1 : 0;
    }
    for (const int covered : {bandwidth_covered, delay_covered}) {
      EXPECT_GT(covered, 600) << (fixed_size ? "fixed-size noise" : "relative noise");
      EXPECT_LT(covered, 760) << (fixed_size ? "fixed-size noise" : "relative noise");
    }
  }
}

TEST(BandwidthAndDelay, BadInputIsAnError) {
  const Lag lag;
  const auto good = response(lag, log_spaced(10.0, 1000.0, 12));
  try {
    bandwidth_and_delay(std::span(good.data(), 9));
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("9 frequencies"));
  }
  auto unordered = good;
  std::swap(unordered[3], unordered[4]);
  try {
    bandwidth_and_delay(unordered);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("point 5"));  // 1-based: the 5th is below the 4th
    EXPECT_THAT(e.message(), HasSubstr("must increase"));
  }
  auto repeated = good;
  repeated[5].frequency_hz = repeated[4].frequency_hz;
  EXPECT_THROW(bandwidth_and_delay(repeated), Error);
  auto negative = good;
  negative[0].frequency_hz = -1.0;
  EXPECT_THROW(bandwidth_and_delay(negative), Error);
  auto zero_gain = good;
  zero_gain[2].gain = 0.0;
  EXPECT_THROW(bandwidth_and_delay(zero_gain), Error);
  // Gains rising with frequency: T² < 0, no bandwidth.
  auto rising = good;
  for (std::size_t i = 0; i < rising.size(); ++i) rising[i].gain = 1.0 + 0.01 * static_cast<double>(i);
  try {
    bandwidth_and_delay(rising);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("no bandwidth can be determined"));
  }
  BandwidthOptions options;
  options.minimum_frequencies = 2;
  EXPECT_THROW(bandwidth_and_delay(good, options), Error);
}

// A raw angular-vibration record: θ = A·sin(ωt + Φθ) in deg, output = S·K_rel(ω)·Aω·sin(ωt + Φθ +
// π/2 + ∠G) + offset, with S the absolute gain (output per deg/s).
AngularVibrationRecord vibration_record(const Lag& lag, double f, double angle_amplitude_deg, double angle_phase,
                                        double absolute_gain) {
  AngularVibrationRecord record;
  record.frequency_hz = f;
  const double w = 2 * kPi * f;
  const double sample_rate = 20000.0;
  for (std::size_t i = 0; i < 4000; ++i) {
    const double t = static_cast<double>(i) / sample_rate;
    record.time_s.push_back(t);
    record.angle.push_back(angle_amplitude_deg * std::sin(w * t + angle_phase) + 0.01);
    record.output.push_back(absolute_gain * lag.gain(f) * angle_amplitude_deg * w *
                                std::sin(w * t + angle_phase + kPi / 2 + lag.phase(f)) +
                            3.0);
  }
  return record;
}

TEST(BandwidthAndDelay, RawRecordsGiveTheLagBack) {
  const Lag lag{1.0, 250.0, 3e-4};
  std::vector<AngularVibrationRecord> records;
  const auto frequencies = log_spaced(10.0, 800.0, 11);
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    // The amplitude shrinks with frequency (the table's rate limit) and the phase varies.
    records.push_back(vibration_record(lag, frequencies[i], 0.5 * 10.0 / frequencies[i], 0.3 * static_cast<double>(i),
                                       5000.0));
  }
  BandwidthOptions options;
  options.output_unit = "pulse/s";
  const auto result = bandwidth_and_delay(std::span<const AngularVibrationRecord>(records), options);
  // Gi = (Fi/Ri)/(FL/RL) is G(fi)/G(f1): the fitted K is 1/G(f1), bandwidth and delay unchanged.
  EXPECT_NEAR_RELATIVE(result.bandwidth.value, 250.0, 1e-8);
  EXPECT_NEAR_RELATIVE(result.delay.value, 3e-4, 1e-8);
  EXPECT_NEAR_RELATIVE(result.dc_gain.value, 1.0 / lag.gain(10.0), 1e-8);
  ASSERT_EQ(result.vibration_fits.size(), 11u);
  EXPECT_NEAR_RELATIVE(result.vibration_fits[0].angle.amplitude, 0.5, 1e-10);
  const auto json = fields_of(result);
  EXPECT_NEAR_RELATIVE(json.at("gain_at_lowest_frequency").at("value").get<double>(), 5000.0 * lag.gain(10.0), 1e-9);
  EXPECT_EQ(json.at("gain_at_lowest_frequency").at("unit"), "pulse/s/(deg/s)");
}

TEST(BandwidthAndDelay, RawRecordsOfANegativeScaleFactorGiveTheDelayBack) {
  // Output = K·rate through the lag with K = -2.9222 V/(deg/s): the output is in antiphase.
  const Lag lag{1.0, 300.0, 2e-4};
  std::vector<AngularVibrationRecord> records;
  for (double f : log_spaced(10.0, 600.0, 10)) records.push_back(vibration_record(lag, f, 0.05, 0.2, -2.9222));
  BandwidthOptions options;
  options.output_unit = "V";
  const auto result = bandwidth_and_delay(std::span<const AngularVibrationRecord>(records), options);
  EXPECT_EQ(result.polarity, -1);
  EXPECT_NEAR_RELATIVE(result.delay.value, 2e-4, 1e-8);
  EXPECT_NEAR_RELATIVE(result.bandwidth.value, 300.0, 1e-8);
  const auto json = fields_of(result);
  EXPECT_NEAR_RELATIVE(json.at("gain_at_lowest_frequency").at("value").get<double>(), -2.9222 * lag.gain(10.0), 1e-9);
}

TEST(BandwidthAndDelay, RawRecordWithoutVibrationIsAnError) {
  const Lag lag;
  std::vector<AngularVibrationRecord> records;
  for (double f : log_spaced(10.0, 800.0, 10)) records.push_back(vibration_record(lag, f, 0.1, 0.0, 1.0));
  std::fill(records[2].angle.begin(), records[2].angle.end(), 0.0);
  records[2].source = "vib_3.csv";
  try {
    bandwidth_and_delay(std::span<const AngularVibrationRecord>(records));
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("vib_3.csv"));
  }
  records[2] = vibration_record(lag, records[2].frequency_hz, 0.1, 0.0, 1.0);
  records[4].output.pop_back();
  EXPECT_THROW(bandwidth_and_delay(std::span<const AngularVibrationRecord>(records)), Error);
}

}  // namespace
}  // namespace inertest
