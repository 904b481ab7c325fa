// The analysis of a whole IMU (issue 19) on a simulated six-axis record whose N, B, K per axis
// follow from how it was made: every coefficient back within its uncertainty, the accelerometer's
// names and units, the per-channel units, and the filter parameters against the truth converted by
// hand.
#include "inertest/allan/allan_channels.h"

#include <array>
#include <cmath>
#include <gmock/gmock.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tuple>

#include "inertest/allan/filter_parameters.h"
#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/sim/imu_noise.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

constexpr double kRate = 10.0;          // Hz
constexpr std::size_t kSamples = 200000;  // 20000 s: the K slope shows from ~1000 s
constexpr double kPi = constants::kPi;

// Truth per axis in the units the analysis reports. Gyro (deg/s samples): N deg/sqrt(h), B deg/h,
// K deg/h/sqrt(h). Accelerometer (m/s^2 samples): N m/s/sqrt(h), B ug, K m/s/h/sqrt(h).
struct AxisTruth {
  const char* name;
  const char* unit;
  double n, b, k;
};
constexpr AxisTruth kTruth[] = {{"gx", "deg/s", 0.30, 5.0, 10.0},  {"gy", "deg/s", 0.25, 4.0, 8.0},
                                {"gz", "deg/s", 0.35, 6.0, 12.0},  {"ax", "m/s^2", 0.06, 50.0, 4.0},
                                {"ay", "m/s^2", 0.05, 40.0, 3.0},  {"az", "m/s^2", 0.07, 60.0, 5.0}};
bool is_gyro(const AxisTruth& t) { return std::string(t.unit) == "deg/s"; }

std::vector<sim::ImuAxisNoise> axes() {
  std::vector<sim::ImuAxisNoise> result;
  for (const AxisTruth& t : kTruth) {
    sim::ImuAxisNoise axis;
    axis.name = t.name;
    axis.unit = t.unit;
    // The generator takes U*sqrt(s), U, U/sqrt(s) in the samples' unit U.
    const std::string n_unit = is_gyro(t) ? "deg/sqrt(h)" : "m/s/sqrt(h)";
    const std::string b_unit = is_gyro(t) ? "deg/h" : "ug";
    const std::string k_unit = is_gyro(t) ? "deg/h/sqrt(h)" : "m/s/h/sqrt(h)";
    axis.noise.angle_random_walk = convert(t.n, n_unit, "(" + axis.unit + ")*sqrt(s)");
    axis.noise.bias_instability = convert(t.b, b_unit, axis.unit);
    axis.noise.rate_random_walk = convert(t.k, k_unit, "(" + axis.unit + ")/sqrt(s)");
    // The flicker's Gauss-Markov processes are asked to start at dt/16, but NoiseGenerator starts
    // them at the sample interval dt (faster ones would alias) and does not oversample: the flicker's
    // PSD falls short of B^2 / (2 pi f) near the Nyquist frequency, where the PSD fit reads N (the
    // accelerometers' N reads ~1 sigma low; see ThePsdGivesTheSameCoefficientsAndFindsTheSinusoid).
    axis.noise.flicker_shortest_s = 1.0 / (16.0 * kRate);
    axis.noise.flicker_longest_s = 1e5;
    result.push_back(axis);
  }
  // A sinusoid on gz: 0.01 deg/s at 1.25 Hz (well inside the bins searched, clear of the noise).
  result[2].sine_amplitude = 0.01;
  result[2].sine_frequency_hz = 1.25;
  return result;
}

AllanChannels analyse(std::uint64_t seed) {
    const auto columns = sim::simulate_imu_noise(axes(), kRate, kSamples, seed);
    std::vector<std::span<const double>> spans(columns.begin(), columns.end());
    std::vector<std::string> names;
    for (const AxisTruth& t : kTruth) names.push_back(t.name);
    AllanOptions common;
    common.sample_rate_hz = kRate;
    common.estimators = EstimatorSet::parse("oadev");
    common.psd = WelchOptions{};
    return allan_variance_of_channels(spans, names,
                                      channel_options(common, names, names, "deg/s,ax=m/s^2,ay=m/s^2,az=m/s^2"));
}

const AllanChannels& analysed() {
  static const AllanChannels channels = analyse(19);
  return channels;
}

// The Allan fit of every axis gives N, B, K back. Every condition is one the record meets by
// construction except with a stated small chance; over seeds 2000-2149 of the record the former
// conditions (every figure identified, |z| < 3, no known bias) held in 116 of 150.
// - A figure the fit identifies lies within kSigma = 4 of its uncertainty of the truth, less its
//   known bias (Bonferroni: 18 x P(|z| > 4) = 0.1 % chance of a false failure).
// - A figure it does not identify (K, on 1-7 % of axes) is a bound: the truth lies below it.
// - Known biases, in units of the figure's uncertainty (measured over the 150 seeds): N reads about
//   0.6 sigma low on every axis (the record has no quantization, Q is free with the bound Q >= 0,
//   noise_terms.h: the bound takes some short-tau variance from N), and 0.6 more on the
//   accelerometers (the simulator's flicker falls short of B^2 / (2 pi f) near the Nyquist
//   frequency: see axes()).
// - The rms of the z-scores less their biases is that of unit normals: in [0.4, 1.7] (as below).
// With these, 149 of the 150 seeds pass: one K truth above its bound (the bound's 2 sigma). (Seed
// 2036 failed until the automatic fit range could drop the longest taus: noise_terms.h.)
constexpr double kSigma = 4.0;

// N, B, K of an Allan fit (NoiseTerms) or a PSD fit (SpectralNoiseTerms), and of the truth.
template <typename Terms>
std::array<const Figure*, 3> nbk_figures(const Terms& noise) {
  return {&noise.angle_random_walk, &noise.bias_instability, &noise.rate_random_walk};
}
std::array<double, 3> nbk_truths(const AxisTruth& t) { return {t.n, t.b, t.k}; }

double known_allan_bias(const AxisTruth& t, int term) {
  if (term != 0) return 0.0;
  return is_gyro(t) ? -0.6 : -1.2;
}

TEST(AllanChannels, EveryCoefficientOfEveryAxisComesBackWithinItsUncertainty) {
  const AllanChannels& channels = analysed();
  ASSERT_EQ(channels.channels.size(), 6u);
  double sum_z2 = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    const AxisTruth& t = kTruth[i];
    const AllanResult& result = channels.channels[i].result;
    EXPECT_EQ(channels.channels[i].name, t.name);
    ASSERT_TRUE(result.noise.has_value()) << t.name;
    const NoiseTerms& noise = *result.noise;
    for (int term = 0; term < 3; ++term) {
      const std::size_t index = static_cast<std::size_t>(term) + 1;  // N, B, K of Q, N, B, K, R
      const Figure& figure = *nbk_figures(noise)[static_cast<std::size_t>(term)];
      const double truth = nbk_truths(t)[static_cast<std::size_t>(term)];
      if (!noise.identified[index]) {
        ASSERT_TRUE(noise.upper_bounds[index].has_value()) << t.name << " " << figure.unit;
        EXPECT_LE(truth, noise.upper_bounds[index]->value) << t.name << " " << figure.unit << " (a bound)";
        continue;
      }
      ASSERT_TRUE(figure.uncertainty.has_value()) << t.name << " " << figure.unit;
      const double z = (figure.value - truth) / *figure.uncertainty - known_allan_bias(t, term);
      EXPECT_LT(std::abs(z), kSigma) << t.name << ": " << figure.value << " ± " << *figure.uncertainty << " "
                                     << figure.unit << ", truth " << truth;
      sum_z2 += z * z;
      ++count;
    }
  }
  // The uncertainties are honest as a set, neither inflated nor too small.
  const double rms_z = std::sqrt(sum_z2 / count);
  EXPECT_GT(rms_z, 0.4);
  EXPECT_LT(rms_z, 1.7);
}

// The PSD beside the Allan variance (IEEE Std 952-1997 Annex C): the same N, B, K from the spectrum
// of every axis, the sinusoid on gz found at its frequency and amplitude, no peak on the others, and
// no disagreement between the two fits. Every condition is one the record meets by construction
// except with a stated small chance. Monte Carlo over 200 further seeds of the record (1000-1199):
// all met in 198 (one false peak on gx, the 5 x 1e-3 false-alarm chance below; one ax B 4.9 sigma
// low, the flicker's estimate having a heavier tail than a normal); with the former conditions
// about 15 % of seeds passed.
//
// Checks against the truth, 18 figures (N, B, K on six axes):
// - A figure the PSD identifies lies within kSigma = 4 of its uncertainty of the truth, plus the
//   known bias below: a Bonferroni bound, 18 x P(|z| > 4) = 0.1 % chance of a false failure.
// - A figure it does not identify (K, in ~30 % of axes: with the automatic segment length the
//   lowest band is 3.7e-3 Hz, and K dominates only below ~1.8e-4 Hz) is a bound: the truth must lie
//   below the reported upper bound (the demo's truth check), unconstrained estimate + 2 sigma.
// - Known biases, in units of the figure's uncertainty (measured over the 200 seeds):
//   the accelerometers' N reads ~0.2 % (~1 sigma) low: the simulator starts the flicker's
//   Gauss-Markov processes at the sample interval dt (NoiseGenerator clamps the shortest time to
//   dt) and does not oversample, so the missing faster processes leave the flicker's PSD short of
//   B^2 / (2 pi f) by a nearly white amount near the Nyquist frequency, which the fit takes from N^2
//   (on the accelerometers B^2 / (2 pi f_N) is 0.8 % of N^2; on the gyros 0.25 %, bias negligible);
//   K, when identified, reads ~1 sigma high: it is identified only when it stands clear of zero, so
//   the figures that pass are the high ones.
// - The rms of the z-scores of the identified figures, each less its known bias, is that of unit
//   normals: in [0.4, 1.7] (13 to 18 figures: chi-squared tails below 1e-3 each side; over 200
//   seeds it was 0.49 to 1.62, median 0.98).
// The Allan fit and the PSD fit (figures identified by both) differ by at most kSigma combined
// sigma plus the PSD's known K bias (the library's own warning fires at 3 combined sigma, which a
// record of 24 pairs trips by chance in ~7 % of seeds: it is not the test's condition).

// The known bias, in sigma, of a PSD figure (term 0 N, 1 B, 2 K) of axis t when identified.
double known_psd_bias(const AxisTruth& t, int term) {
  if (term == 2) return 1.0;
  if (term == 0 && !is_gyro(t)) return -1.0;
  return 0.0;
}

// The conditions above that the analysed record fails, each a message (none: all hold).
std::vector<std::string> psd_failures(const AllanChannels& channels) {
  std::vector<std::string> failures;
  double sum_z2 = 0.0;
  int count = 0;
  if (channels.channels.size() != 6) return {"not six channels"};
  for (std::size_t i = 0; i < 6; ++i) {
    const AxisTruth& t = kTruth[i];
    const AllanResult& result = channels.channels[i].result;
    if (!result.psd.has_value()) {
      failures.push_back(fmt::format("{}: no PSD", t.name));
      continue;
    }
    const SpectralNoiseTerms& noise = result.psd->noise;
    for (int term = 0; term < 3; ++term) {
      const std::size_t index = static_cast<std::size_t>(term) + 1;  // N, B, K of Q, N, B, K, R
      const Figure& figure = *nbk_figures(noise)[static_cast<std::size_t>(term)];
      const double truth = nbk_truths(t)[static_cast<std::size_t>(term)];
      if (!noise.identified[index]) {
        if (!noise.upper_bounds[index].has_value() || !(truth <= noise.upper_bounds[index]->value)) {
          failures.push_back(fmt::format("{} (PSD): {} not identified, truth {} above the bound {}", t.name,
                                         figure.unit, truth,
                                         noise.upper_bounds[index] ? noise.upper_bounds[index]->value : -1.0));
        }
        continue;
      }
      if (!figure.uncertainty.has_value() || !(*figure.uncertainty > 0.0)) {
        failures.push_back(fmt::format("{} (PSD): {} identified without an uncertainty", t.name, figure.unit));
        continue;
      }
      const double bias = known_psd_bias(t, term);
      const double z = (figure.value - truth) / *figure.uncertainty;
      if (!(std::abs(z) <= kSigma + std::abs(bias))) {
        failures.push_back(fmt::format("{} (PSD): {} +- {} {}, truth {} (z {:.2f})", t.name, figure.value,
                                       *figure.uncertainty, figure.unit, truth, z));
      }
      sum_z2 += (z - bias) * (z - bias);
      ++count;
      // Against the Allan fit's figure of the same term.
      if (!result.noise.has_value() || !result.noise->identified[index]) continue;
      const Figure& a = *nbk_figures(*result.noise)[static_cast<std::size_t>(term)];
      const Figure b = figure.in(a.unit);
      const double sigma = std::hypot(a.uncertainty.value_or(0.0), b.uncertainty.value_or(0.0));
      if (!(std::abs(a.value - b.value) <= (kSigma + std::abs(bias)) * sigma)) {
        failures.push_back(fmt::format("{}: Allan {} +- {} and PSD {} +- {} {} differ by {:.2f} combined sigma",
                                       t.name, a.value, a.uncertainty.value_or(0.0), b.value,
                                       b.uncertainty.value_or(0.0), a.unit, std::abs(a.value - b.value) / sigma));
      }
    }
    const auto& peaks = result.psd->peaks;
    if (std::string(t.name) == "gz") {
      if (peaks.size() != 1) {
        failures.push_back(fmt::format("gz: {} peaks, not 1", peaks.size()));
        continue;
      }
      const PeriodicComponent& peak = peaks.front();
      if (!(std::abs(peak.frequency.value - 1.25) <= result.psd->resolution_hz)) {
        failures.push_back(fmt::format("gz: peak at {} Hz", peak.frequency.value));
      }
      // kSigma of the amplitude's uncertainty, plus a floor of 5 % of it.
      if (!(std::abs(peak.amplitude.value - 0.01) <= kSigma * peak.amplitude.uncertainty.value_or(0.0) + 0.0005)) {
        failures.push_back(fmt::format("gz: amplitude {} +- {}", peak.amplitude.value,
                                       peak.amplitude.uncertainty.value_or(0.0)));
      }
      if (peak.amplitude.unit != "deg/s") failures.push_back("gz: amplitude unit " + peak.amplitude.unit);
    } else if (!peaks.empty()) {  // by chance in 5 x 1e-3 of records (WelchOptions' false-alarm probability)
      failures.push_back(fmt::format("{}: {} peaks where there is none", t.name, peaks.size()));
    }
  }
  const double rms_z = count > 0 ? std::sqrt(sum_z2 / count) : 0.0;
  if (!(rms_z >= 0.4 && rms_z <= 1.7)) failures.push_back(fmt::format("rms z {:.3f} over {} figures", rms_z, count));
  return failures;
}

TEST(AllanChannels, ThePsdGivesTheSameCoefficientsAndFindsTheSinusoid) {
  const std::vector<std::string> failures = psd_failures(analysed());
  for (const std::string& failure : failures) ADD_FAILURE() << failure;
  EXPECT_TRUE(failures.empty());
}

TEST(AllanChannels, AnAccelerometerChannelHasItsOwnNoiseTermsAndUnits) {
  const nlohmann::json json = analysed().to_json();
  const nlohmann::json& ax = json.at("channels").at("ax").at("noise");
  EXPECT_EQ(ax.at("velocity_random_walk").at("unit"), "m/s/sqrt(h)");
  EXPECT_EQ(ax.at("bias_instability").at("unit"), "ug");
  EXPECT_EQ(ax.at("acceleration_random_walk").at("unit"), "m/s/h/sqrt(h)");
  EXPECT_FALSE(ax.contains("angle_random_walk"));
  EXPECT_FALSE(ax.contains("random_walk_coefficient"));  // GJB eq. (31) is a gyro's
  const nlohmann::json& gx = json.at("channels").at("gx").at("noise");
  EXPECT_EQ(gx.at("angle_random_walk").at("unit"), "deg/sqrt(h)");
  EXPECT_EQ(gx.at("rate_random_walk").at("unit"), "deg/h/sqrt(h)");
  EXPECT_EQ(json.at("channels").at("gx").at("input_unit"), "deg/s");
  EXPECT_EQ(json.at("channels").at("az").at("input_unit"), "m/s^2");
}

// Kalibr's densities are N and K in SI (imu.yaml: *_noise_density, *_random_walk), the largest of
// the axes. The truth converted by hand: N deg/sqrt(h) * (pi/180) / 60 = rad/sqrt(s) = rad/s/sqrt(Hz);
// K deg/h/sqrt(h) * (pi/180) / 3600 / 60 = rad/s^2/sqrt(Hz); m/s/sqrt(h) / 60 = m/s^2/sqrt(Hz);
// m/s/h/sqrt(h) / 3600 / 60 = m/s^3/sqrt(Hz).
TEST(FilterParameters, KalibrDensitiesEqualTheTruthConvertedByHand) {
  const auto sensors = filter_noise_parameters(analysed());
  const std::string yaml = format_filter_parameters(sensors, FilterFormat::kKalibr, "test");
  const auto value_of = [&](const std::string& key) {
    const auto at = yaml.find("\n" + key + ": ");
    EXPECT_NE(at, std::string::npos) << key;
    return std::stod(yaml.substr(at + key.size() + 3));
  };
  // The axis of the largest truth is gz (gyro) and az (accelerometer) for both N and K.
  const double gyro_n = 0.35 * (kPi / 180.0) / 60.0;
  const double gyro_k = 12.0 * (kPi / 180.0) / 3600.0 / 60.0;
  const double accel_n = 0.07 / 60.0;
  const double accel_k = 5.0 / 3600.0 / 60.0;
  for (const auto& [key, truth, sensor, field] :
       {std::tuple{"gyroscope_noise_density", gyro_n, 2, &SensorNoiseParameters::white_noise_density},
        std::tuple{"gyroscope_random_walk", gyro_k, 2, &SensorNoiseParameters::random_walk_density},
        std::tuple{"accelerometer_noise_density", accel_n, 5, &SensorNoiseParameters::white_noise_density},
        std::tuple{"accelerometer_random_walk", accel_k, 5, &SensorNoiseParameters::random_walk_density}}) {
    const NoiseDensity& density = sensors[static_cast<std::size_t>(sensor)].*field;
    ASSERT_TRUE(density.identified) << key;
    const double written = value_of(key);
    EXPECT_NEAR(written, truth, 3.0 * density.uncertainty) << key;
    // The file holds the largest axis's estimate, to the 6 digits written.
    double largest = 0.0;
    for (const auto& s : sensors) {
      if (s.kind == sensors[static_cast<std::size_t>(sensor)].kind) largest = std::max(largest, (s.*field).value);
    }
    EXPECT_NEAR(written, largest, 1e-5 * largest) << key;
  }
  EXPECT_NE(yaml.find("update_rate: 10"), std::string::npos);
}

// The discrete-time values follow from the densities at the record's rate, and the Gauss-Markov
// equivalent's Allan maximum is the flicker floor 0.664 B.
TEST(FilterParameters, DiscreteValuesAndTheGaussMarkovEquivalentFollowFromTheDensities) {
  const auto sensors = filter_noise_parameters(analysed());
  for (const SensorNoiseParameters& s : sensors) {
    const double dt = 1.0 / s.sample_rate_hz;
    EXPECT_NEAR_RELATIVE(s.discrete_white_sigma, s.white_noise_density.value / std::sqrt(dt), 1e-12);
    EXPECT_NEAR_RELATIVE(s.discrete_random_walk_sigma, s.random_walk_density.value * std::sqrt(dt), 1e-12);
    const double t = s.gauss_markov_correlation_time_s;
    EXPECT_NEAR_RELATIVE(s.discrete_gauss_markov_phi, std::exp(-dt / t), 1e-12);
    // sigma_A^2(tau) of the process (El-Sheimy et al. 2008, eq. 23), at its peak tau = 1.8926 T.
    const double x = 1.8926179;
    const double peak = s.gauss_markov_sigma *
                        std::sqrt((2.0 * x - 3.0 + 4.0 * std::exp(-x) - std::exp(-2.0 * x)) / (x * x));
    EXPECT_NEAR_RELATIVE(peak, kBiasInstabilityFactor * s.bias_instability.value, 1e-6);
  }
}

TEST(FilterParameters, EveryFormatNamesItsKeysAndSaysHowEachNumberWasObtained) {
  const auto sensors = filter_noise_parameters(analysed());
  const std::string matlab = format_filter_parameters(sensors, FilterFormat::kMatlab, "test");
  for (const char* key : {"gyroparams(", "accelparams(", "'NoiseDensity'", "'RandomWalk'", "'BiasInstability'"}) {
    EXPECT_NE(matlab.find(key), std::string::npos) << key;
  }
  const std::string sim = format_filter_parameters(sensors, FilterFormat::kGnssInsSim, "test");
  for (const char* key : {"'gyro_arw'", "'gyro_b_stability'", "'gyro_b_corr'", "'accel_vrw'", "'accel_b_stability'",
                          "'accel_b_corr'"}) {
    EXPECT_NE(sim.find(key), std::string::npos) << key;
  }
  // gnss-ins-sim's gyro_arw is deg/sqrt(h): gx's N back in its reported unit.
  EXPECT_NE(sim.find(fmt::format("{:.6g}", analysed().channels[0].result.noise->angle_random_walk.value)),
            std::string::npos);
  const nlohmann::json json = nlohmann::json::parse(format_filter_parameters(sensors, FilterFormat::kJson, "test"));
  EXPECT_EQ(json.at("sensors").at("ax").at("white_noise_density").at("unit"), "m/s^2/sqrt(Hz)");
  EXPECT_EQ(json.at("sensors").at("gx").at("random_walk_density").at("unit"), "rad/s^2/sqrt(Hz)");
  for (const std::string& text : {matlab, sim}) EXPECT_NE(text.find("GJB 2426A-2004 eq. 30"), std::string::npos);
  EXPECT_THROW(parse_filter_format("yaml"), Error);
}

// Each target loads only what its reader takes: Kalibr both sensors, MATLAB one axis or three,
// gnss-ins-sim three of each; anything else is refused before a line is written.
TEST(FilterParameters, ChannelSetsATargetCannotLoadAreRefused) {
  const auto sensors = filter_noise_parameters(analysed());
  const std::vector<SensorNoiseParameters> gyros(sensors.begin(), sensors.begin() + 3);
  const std::vector<SensorNoiseParameters> two_gyros_one_accelerometer = {sensors[0], sensors[1], sensors[5]};
  const auto refusal = [](const std::vector<SensorNoiseParameters>& chosen, FilterFormat format) {
    try {
      format_filter_parameters(chosen, format, "test");
    } catch (const Error& e) {
      return e.message();
    }
    return std::string("accepted");
  };
  EXPECT_THAT(refusal(gyros, FilterFormat::kKalibr),
              ::testing::HasSubstr("Kalibr's imu.yaml needs a gyroscope and an accelerometer: the channels give 3 "
                                   "gyro and 0 accelerometer axes"));
  EXPECT_THAT(refusal(two_gyros_one_accelerometer, FilterFormat::kMatlab),
              ::testing::HasSubstr("MATLAB's gyroparams and accelparams take one axis or three"));
  EXPECT_THAT(refusal(gyros, FilterFormat::kGnssInsSim),
              ::testing::HasSubstr("gnss-ins-sim's IMU error model takes three gyro and three accelerometer axes"));
  EXPECT_EQ(refusal(gyros, FilterFormat::kMatlab), "accepted");
  EXPECT_EQ(refusal(two_gyros_one_accelerometer, FilterFormat::kKalibr), "accepted");
  EXPECT_EQ(refusal({sensors[0]}, FilterFormat::kJson), "accepted");
}

// gnss-ins-sim has no random-walk term: its file lists each K it leaves out. MATLAB's and
// gnss-ins-sim's files carry the record's rate and the discrete values the JSON has.
TEST(FilterParameters, WhatAFormatCannotHoldIsInItsComments) {
  const auto sensors = filter_noise_parameters(analysed());
  const std::string sim = format_filter_parameters(sensors, FilterFormat::kGnssInsSim, "test");
  EXPECT_THAT(sim, ::testing::HasSubstr("K is left out (gx " + fmt::format("{:.6g}", sensors[0].random_walk_density.value)));
  EXPECT_THAT(sim, ::testing::HasSubstr("rad/s^2/sqrt(Hz); ax "));
  EXPECT_THAT(sim, ::testing::HasSubstr("\nfs = 10  # Hz"));
  const std::string matlab = format_filter_parameters(sensors, FilterFormat::kMatlab, "test");
  EXPECT_THAT(matlab, ::testing::HasSubstr("\nsample_rate_hz = 10;"));
  for (const std::string& text : {sim, matlab}) {
    for (const SensorNoiseParameters& s : {sensors[0], sensors[3]}) {
      EXPECT_THAT(text, ::testing::HasSubstr(fmt::format("white sigma [{:.6g}", s.discrete_white_sigma)));
      EXPECT_THAT(text, ::testing::HasSubstr(fmt::format("Gauss-Markov phi [{:.6g}", s.discrete_gauss_markov_phi)));
    }
  }
}

// An estimate within 2 sigma of zero (NoiseTerms::significant) is written as the estimate, and each
// file's comment gives its 2-sigma bound beside it; the JSON marks it as the fit does. In this
// 6-hour record at 10 Hz, K is measured on every axis but within 2 sigma of zero on each (each
// bound was above the simulator's K: gx 1.9e-6 against 8.1e-7 rad/s^2/sqrt(Hz), az 2.8e-5 against
// 2.3e-5 m/s^3/sqrt(Hz)).
// A fit whose sigma^2 still falls at the longest tau (K held at zero: flicker over white) shows no
// correlation time: the one written (that tau / 1.8926) is said to be the record's, in the JSON and
// in every file's comments (six channels of one flicker noise gave 185 to 3463 s, unsaid).
TEST(FilterParameters, ACorrelationTimeTheRecordCannotShowIsSaidToBeUnknown) {
  AllanChannels channels = analysed();
  // gx's K^2/3 (A_1) and ramp (A_2) held at zero.
  channels.channels[0].result.noise->coefficients[3] = 0.0;
  channels.channels[0].result.noise->coefficients[4] = 0.0;
  const std::vector<SensorNoiseParameters> sensors = filter_noise_parameters(channels);
  EXPECT_FALSE(sensors[0].gauss_markov_identified);
  EXPECT_NEAR_RELATIVE(sensors[0].gauss_markov_correlation_time_s, channels.channels[0].result.tau_s.back() / 1.8926179,
                       1e-6);
  const nlohmann::json json = filter_parameters_json(sensors).at("sensors");
  EXPECT_EQ(json.at("gx").at("gauss_markov").at("correlation_time").at("identified"), false);
  // The others turn up within the record (their K): their correlation times are theirs.
  for (std::size_t i = 1; i < sensors.size(); ++i) {
    EXPECT_TRUE(sensors[i].gauss_markov_identified) << sensors[i].channel;
    EXPECT_LT(sensors[i].gauss_markov_correlation_time_s, 0.999 * channels.channels[i].result.tau_s.back() / 1.8926179);
  }
  // A rate random walk alone (gy's N and B held at zero) is least at the shortest tau.
  AllanChannels walk = analysed();
  walk.channels[1].result.noise->coefficients[0] = 0.0;
  walk.channels[1].result.noise->coefficients[1] = 0.0;
  walk.channels[1].result.noise->coefficients[2] = 0.0;
  EXPECT_FALSE(filter_noise_parameters(walk)[1].gauss_markov_identified);
  for (const FilterFormat format : {FilterFormat::kKalibr, FilterFormat::kMatlab, FilterFormat::kGnssInsSim}) {
    const std::string text = format_filter_parameters(sensors, format, "test");
    EXPECT_THAT(text, ::testing::HasSubstr("Gauss-Markov correlation time not identified (the fitted curve is least at "
                                           "an end of its taus: the value is that tau/1.8926, a figure of the record, "
                                           "and so are phi and the driving sigma): gx;"));
  }
}

TEST(FilterParameters, AnEstimateWithinTwoSigmaOfZeroHasItsBoundInTheComments) {
  const std::vector<SensorNoiseParameters> sensors = filter_noise_parameters(analysed());
  const nlohmann::json json = filter_parameters_json(sensors).at("sensors");
  std::size_t insignificant = 0;
  for (const SensorNoiseParameters& s : sensors) {
    const NoiseDensity& k = s.random_walk_density;
    const nlohmann::json& written = json.at(s.channel).at("random_walk_density");
    EXPECT_DOUBLE_EQ(written.at("value").get<double>(), k.value) << s.channel;
    if (!k.identified || k.significant) {
      EXPECT_FALSE(written.contains("significant")) << s.channel;
      continue;
    }
    ++insignificant;
    EXPECT_GT(k.upper_bound, k.value) << s.channel;
    EXPECT_EQ(written.at("significant"), false) << s.channel;
    EXPECT_DOUBLE_EQ(written.at("upper_bound").get<double>(), k.upper_bound) << s.channel;
    for (const FilterFormat format : {FilterFormat::kKalibr, FilterFormat::kMatlab, FilterFormat::kGnssInsSim}) {
      const std::string text = format_filter_parameters(sensors, format, "test");
      EXPECT_THAT(text, ::testing::HasSubstr("estimates within 2 sigma of zero, their 2-sigma upper bounds in brackets:"));
      EXPECT_THAT(text, ::testing::HasSubstr(" " + s.channel + ": random walk (< " + fmt::format("{:.6g}", k.upper_bound) +
                                             (s.kind == SensorKind::kGyro ? " rad/s^2/sqrt(Hz));" : " m/s^3/sqrt(Hz));")));
    }
  }
  EXPECT_GT(insignificant, 0u);
}

TEST(AllanChannels, PerChannelUnitsAreCheckedAgainstTheChannels) {
  AllanOptions common;
  common.sample_rate_hz = 10.0;
  const std::vector<std::string> names = {"gx", "ax"};
  const auto options = channel_options(common, names, {"2", "5"}, "deg/s, ax = m/s^2");
  EXPECT_EQ(options[0].input_unit, "deg/s");
  EXPECT_EQ(options[1].input_unit, "m/s^2");
  EXPECT_EQ(channel_options(common, names, {"2", "5"}, "5=g")[1].input_unit, "g");  // by the selector as given
  EXPECT_EQ(channel_options(common, names, {"2", "5"}, "")[0].input_unit, "deg/h");
  EXPECT_THROW(channel_options(common, names, names, "gz=deg/s"), Error);
  EXPECT_THROW(channel_options(common, names, names, "gx=deg/s,gx=rad/s"), Error);
  EXPECT_THROW(channel_options(common, names, names, "deg/s,rad/s"), Error);
  EXPECT_THROW(channel_options(common, names, names, "gx=furlong"), Error);
}

}  // namespace
}  // namespace inertest
