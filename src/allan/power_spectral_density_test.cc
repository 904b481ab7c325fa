// The Welch PSD against scipy and Parseval, the noise terms read off it from simulated records whose
// truth follows from how they were made (with a Monte Carlo coverage test), periodic components, the
// comparison with the Allan fit, and bad options.
#include "inertest/allan/power_spectral_density.h"

#include <gmock/gmock.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <thread>
#include <vector>

#include "inertest/allan/allan.h"
#include "inertest/core/error.h"
#include "inertest/sim/noise.h"
#include "inertest/sim/random.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

constexpr double kPi = std::numbers::pi;

// x_n = sin(0.3 n) + 0.5 cos(1.7 n + 0.2) + 0.01 n + ((7919 n) mod 101) / 101, n = 0..99.
std::vector<double> fixed_record() {
  std::vector<double> x(100);
  for (std::size_t n = 0; n < x.size(); ++n) {
    const auto t = static_cast<double>(n);
    x[n] = std::sin(0.3 * t) + 0.5 * std::cos(1.7 * t + 0.2) + 0.01 * t + static_cast<double>((n * 7919) % 101) / 101.0;
  }
  return x;
}

struct ScipyCase {
  SpectralWindow window;
  std::size_t segment_length;
  double overlap;
  std::vector<double> density;
};

// Reference values made once with /usr/bin/python3, scipy 1.10.1:
//   f, p = scipy.signal.welch(x, fs=10.0, window=W, nperseg=L, noverlap=V, detrend='constant',
//                             scaling='density')
// for x = fixed_record() and (W, L, V) = ('hann', 16, 8), ('blackmanharris', 32, 8),
// ('hamming', 20, 10), ('boxcar', 25, 0); printed with repr().
std::vector<ScipyCase> scipy_cases() {
  return {
      {SpectralWindow::kHann, 16, 0.5,
       {0.09396935286848312, 0.36149326749343197, 0.06313488947684032, 0.02838615484128534, 0.12075127628011549,
        0.07289257512896484, 0.046958091312714195, 0.0410580544753127, 0.0016347985242802115}},
      {SpectralWindow::kBlackmanHarris, 32, 0.25,
       {0.28670902980313756, 0.9308512079131033, 0.7806948895326683, 0.1650631303757515, 0.010241653190754194,
        0.013769049765145208, 0.01989439187486898, 0.021791660150050875, 0.14062739473299343, 0.17014394775077676,
        0.038449538535465295, 0.006071633134001085, 0.03934023617683778, 0.08338427999302374, 0.04420730331454501,
        0.006736857372623768, 0.0011403797856150348}},
      {SpectralWindow::kHamming, 20, 0.5,
       {0.1120723017473291, 0.7077528753457463, 0.10824927675854851, 0.008621700084830897, 0.03349404334338171,
        0.14382260938005217, 0.10470487853560703, 0.017935863629106378, 0.08057593034732499, 0.019771351204263172,
        0.00040996988106778784}},
      {SpectralWindow::kRectangular, 25, 0.0,
       {8.578862344278504e-33, 1.1637045164149455, 0.07403413750167524, 0.014620793663041785, 0.016852116202881233,
        0.0664588558644488, 0.05997845442657529, 0.20687402777415914, 0.009859094205357084, 0.01019730743980314,
        0.1215067250124661, 0.009466023472463364, 0.0016062982278924976}},
  };
}

TEST(WelchPsd, AgreesWithScipyWelchToTwelveDigits) {
  const std::vector<double> x = fixed_record();
  for (const ScipyCase& c : scipy_cases()) {
    WelchOptions options;
    options.sample_rate_hz = 10.0;
    options.window = c.window;
    options.segment_length = c.segment_length;
    options.overlap = c.overlap;
    const PowerSpectralDensity psd = welch_power_spectral_density(x, "V", options);
    ASSERT_EQ(psd.density.size(), c.density.size()) << spectral_window_name(c.window);
    for (std::size_t k = 0; k < c.density.size(); ++k) {
      EXPECT_NEAR_RELATIVE(psd.frequency_hz[k], 10.0 * static_cast<double>(k) / static_cast<double>(c.segment_length), 1e-15);
      if (c.density[k] < 1e-20) {
        EXPECT_LT(psd.density[k], 1e-20) << "the rectangular window's 0 Hz bin, zero after the mean's removal";
      } else {
        EXPECT_NEAR_RELATIVE(psd.density[k], c.density[k], 1e-12) << spectral_window_name(c.window) << " bin " << k;
      }
    }
  }
}

// Parseval: sum_k S1(f_k) fs / L = mean over segments of sum_n ((x_n - mean) w_n)^2 / sum_n w_n^2 (the
// windowed, mean-removed mean square), computed here by hand; with the rectangular window and one
// segment, the record's variance (n in the denominator).
TEST(WelchPsd, IntegralOfTheDensityIsTheWindowNormalisedVariance) {
  sim::Random random(7);
  std::vector<double> x(1000);
  for (double& v : x) v = 3.0 + 2.0 * random.normal();
  WelchOptions options;
  options.sample_rate_hz = 50.0;
  options.window = SpectralWindow::kRectangular;
  options.segment_length = x.size();
  const auto integral = [&](const PowerSpectralDensity& psd) {
    double sum = 0.0;
    for (double s : psd.density) sum += s * psd.resolution_hz;
    return sum;
  };
  double mean = 0.0;
  for (double v : x) mean += v / static_cast<double>(x.size());
  double variance = 0.0;
  for (double v : x) variance += (v - mean) * (v - mean) / static_cast<double>(x.size());
  EXPECT_NEAR_RELATIVE(integral(welch_power_spectral_density(x, "V", options)), variance, 1e-12);

  // Hann, 200-sample segments overlapping by half: 9 segments starting every 100 samples.
  options.window = SpectralWindow::kHann;
  options.segment_length = 200;
  const PowerSpectralDensity psd = welch_power_spectral_density(x, "V", options);
  ASSERT_EQ(psd.segment_count, 9U);
  double windowed = 0.0;
  double energy = 0.0;
  for (std::size_t n = 0; n < 200; ++n) {
    const double w = 0.5 - 0.5 * std::cos(2.0 * kPi * static_cast<double>(n) / 200.0);
    energy += w * w;
  }
  for (std::size_t s = 0; s < 9; ++s) {
    double segment_mean = 0.0;
    for (std::size_t n = 0; n < 200; ++n) segment_mean += x[100 * s + n] / 200.0;
    for (std::size_t n = 0; n < 200; ++n) {
      const double w = 0.5 - 0.5 * std::cos(2.0 * kPi * static_cast<double>(n) / 200.0);
      windowed += std::pow((x[100 * s + n] - segment_mean) * w, 2) / (9.0 * energy);
    }
  }
  EXPECT_NEAR_RELATIVE(integral(psd), windowed, 1e-12);
  // ENBW of the Hann window: 1.5 bins.
  EXPECT_NEAR_RELATIVE(psd.equivalent_noise_bandwidth_hz, 1.5 * psd.resolution_hz, 1e-12);
}

// A pure sinusoid of peak amplitude 3 V between two bins: the density integrates to A^2 / 2 = 4.5 V^2
// and one periodic component is found at its frequency with its amplitude.
TEST(WelchPsd, PureSinusoidIntegratesToHalfItsSquaredAmplitudeAndIsFound) {
  const double fs = 100.0;
  const double f0 = 12.34;
  std::vector<double> x(1 << 14);
  for (std::size_t n = 0; n < x.size(); ++n) x[n] = 3.0 * std::sin(2.0 * kPi * f0 * static_cast<double>(n) / fs + 0.3);
  for (SpectralWindow window : {SpectralWindow::kHann, SpectralWindow::kBlackmanHarris}) {
    WelchOptions options;
    options.sample_rate_hz = fs;
    options.window = window;
    const PowerSpectralDensity psd = welch_power_spectral_density(x, "V", options);
    EXPECT_EQ(psd.segment_length, 1024U);
    EXPECT_EQ(psd.segment_count, 31U);
    double integral = 0.0;
    for (double s : psd.density) integral += s * psd.resolution_hz;
    EXPECT_NEAR_RELATIVE(integral, 4.5, 1e-3);
    ASSERT_EQ(psd.peaks.size(), 1U) << spectral_window_name(window);
    EXPECT_NEAR(psd.peaks[0].frequency.value, f0, 0.1 * psd.resolution_hz);
    EXPECT_EQ(psd.peaks[0].amplitude.unit, "V");
    EXPECT_NEAR_RELATIVE(psd.peaks[0].amplitude.value, 3.0, 2e-3);
    EXPECT_GT(psd.peaks[0].peak_to_floor_ratio, 1e6);
  }
}

// The simulator's noise at dt / oversampling, averaged to dt (as noise_terms_test.cc makes its
// records, there with an oversampling of 4).
std::vector<double> simulated_rate(const sim::NoiseParameters& parameters, double dt, std::size_t samples,
                                   std::uint64_t seed, int oversampling = 4) {
  sim::NoiseGenerator noise(parameters, dt / oversampling, sim::Random(seed));
  std::vector<double> rate(samples);
  for (double& v : rate) {
    v = 0.0;
    for (int k = 0; k < oversampling; ++k) v += noise.next() / oversampling;
  }
  return rate;
}

bool covers(const Figure& figure, double truth, double sigmas = 1.0) {
  return std::abs(figure.value - truth) <= sigmas * figure.uncertainty.value_or(0.0);
}

// White samples of sigma = 2 m/s^2 at 100 Hz: the one-sided level 2 sigma^2 / fs = 0.08 (m/s^2)^2/Hz,
// the ASD sqrt(2) N, and N = sigma / sqrt(fs) = 0.2 (m/s^2)*sqrt(s) within 2 of its uncertainties; B
// and K are not identified.
TEST(WelchPsd, WhiteNoiseReadsTwoSigmaSquaredOverFsAndN) {
  sim::Random random(11);
  std::vector<double> x(1 << 16);
  for (double& v : x) v = 5.0 + 2.0 * random.normal();
  WelchOptions options;
  options.sample_rate_hz = 100.0;
  const PowerSpectralDensity psd = welch_power_spectral_density(x, "m/s^2", options);
  double level = 0.0;
  double asd = 0.0;
  const std::vector<double> amplitude = psd.amplitude_spectral_density();
  for (std::size_t k = 1; k + 1 < psd.density.size(); ++k) {
    level += psd.density[k] / static_cast<double>(psd.density.size() - 2);
    asd += amplitude[k] / static_cast<double>(psd.density.size() - 2);
  }
  EXPECT_NEAR_RELATIVE(level, 0.08, 0.01);
  EXPECT_NEAR_RELATIVE(asd, std::sqrt(2.0) * 0.2, 0.02);  // the mean of sqrt is a little below
  std::vector<double> unbiased = x;
  for (double& v : unbiased) v -= 5.0;
  const PowerSpectralDensity without_bias = welch_power_spectral_density(unbiased, "m/s^2", options);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_NEAR_RELATIVE(psd.density[k], without_bias.density[k], 1e-9) << "the bias leaked into bin " << k;
  }
  const SpectralNoiseTerms& noise = psd.noise;
  ASSERT_TRUE(noise.identified[1]);
  // An accelerometer's velocity random walk, reported in m/s/sqrt(h): 0.2 (m/s^2)*sqrt(s) = 12 m/s/sqrt(h).
  EXPECT_EQ(noise.angle_random_walk.unit, "m/s/sqrt(h)");
  EXPECT_TRUE(covers(noise.angle_random_walk, 0.2 * 60.0, 2.0))
      << noise.angle_random_walk.value << " +- " << *noise.angle_random_walk.uncertainty;
  EXPECT_LT(*noise.angle_random_walk.uncertainty, 0.01 * 0.2 * 60.0);
  // K and B are absent: either held at zero (with an upper bound) or within 3 sigma of zero.
  for (std::size_t k : {2, 3}) {
    const Figure& figure = k == 2 ? noise.bias_instability : noise.rate_random_walk;
    if (noise.identified[k]) {
      EXPECT_TRUE(covers(figure, 0.0, 3.0)) << k;
    } else {
      ASSERT_TRUE(noise.upper_bounds[k].has_value());
      EXPECT_EQ(noise.upper_bounds[k]->unit, k == 2 ? "ug" : "m/s/h/sqrt(h)");
    }
  }
  EXPECT_EQ(noise.verdict, "consistent");
  EXPECT_TRUE(psd.peaks.empty());
}

struct Simulated {
  sim::NoiseParameters parameters;
  double dt = 0.1;
  std::size_t samples = 1 << 15;
};

// Figures in deg/h input: N in deg/sqrt(h) = (deg/h*sqrt(s)) / 60, B in deg/h, K in deg/h/sqrt(h) =
// (deg/h/sqrt(s)) * 60.
std::array<double, 3> truth_of(const sim::NoiseParameters& p) {
  return {p.angle_random_walk / 60.0, p.bias_instability, p.rate_random_walk * 60.0};
}

PowerSpectralDensity psd_of(const Simulated& s, std::uint64_t seed) {
  WelchOptions options;
  options.sample_rate_hz = 1.0 / s.dt;
  return welch_power_spectral_density(simulated_rate(s.parameters, s.dt, s.samples, seed), "deg/h", options);
}

// White noise, flicker and rate random walk each dominating about a decade of a 32768-sample record
// at 10 Hz (deg/h; N = 1 deg/h*sqrt(s), B = 1.94 deg/h, K = 1.19 deg/h/sqrt(s): crossovers
// B^2 / (2 pi N^2) = 0.6 Hz and K^2 / (2 pi B^2) = 0.06 Hz).
Simulated three_terms() {
  Simulated s;
  s.parameters.angle_random_walk = 1.0;
  s.parameters.bias_instability = 1.94;
  s.parameters.rate_random_walk = 1.19;
  s.parameters.flicker_shortest_s = s.dt / 4;
  s.parameters.flicker_longest_s = 1e5;
  return s;
}

// White noise and rate random walk each dominating about half the band fitted of a 32768-sample
// record at 10 Hz (N = 1 deg/h*sqrt(s), K = 0.6 deg/h/sqrt(s): crossover K / (2 pi N) = 0.095 Hz).
Simulated white_and_random_walk() {
  Simulated s;
  s.parameters.angle_random_walk = 1.0;
  s.parameters.rate_random_walk = 0.6;
  return s;
}

struct Coverage {
  std::array<int, 3> covered{};
  int seeds = 0;
  double rate(std::size_t k) const { return static_cast<double>(covered[k]) / seeds; }
};

// Over seeds 1..seeds: how often the 1-sigma interval of each of N, B, K covers the truth (a figure
// not identified counts as not covering).
Coverage coverage_over(const Simulated& s, int seeds) {
  const auto truth = truth_of(s.parameters);
  Coverage coverage;
  coverage.seeds = seeds;
  for (int seed = 1; seed <= seeds; ++seed) {
    const SpectralNoiseTerms n = psd_of(s, static_cast<std::uint64_t>(seed)).noise;
    const std::array<const Figure*, 3> figures = {&n.angle_random_walk, &n.bias_instability, &n.rate_random_walk};
    for (std::size_t k = 0; k < 3; ++k) {
      if (n.identified[k + 1] && covers(*figures[k], truth[k])) ++coverage.covered[k];
    }
  }
  return coverage;
}

// Monte Carlo over 100 seeds of white noise and rate random walk: the 1-sigma intervals of N and K
// cover the truth in 55-80 % of the seeds (68 % expected; the binomial spread over 100 seeds is
// 4.7 %). Measured: N 72 %, K 74 %.
TEST(WelchPsd, OneSigmaIntervalsOfNAndKCoverTheTruthInAboutTwoThirdsOfTheSeeds) {
  const Coverage coverage = coverage_over(white_and_random_walk(), 100);
  for (std::size_t k : {0, 2}) {
    RecordProperty(std::array{"coverage_N", "coverage_B", "coverage_K"}[k], std::to_string(coverage.rate(k)));
    EXPECT_GE(coverage.rate(k), 0.55) << "term " << k;
    EXPECT_LE(coverage.rate(k), 0.80) << "term " << k;
  }
}

// The same with flicker (three_terms): B and K cover the truth in 55-80 % of 100 seeds. N is checked
// within 10 % only: the simulator's flicker is a sum of Gauss-Markov processes whose correlation
// times start at its step, here dt / 4, so that its spectrum falls short of B^2 / (2 pi f) by about
// 4 f dt / 4 (half of it at the Nyquist frequency); the model then overstates the flicker at high
// frequency and N reads low (the Done-when test below simulates at dt / 16 instead, which costs 4
// times as much). Measured: B 72 %, K 67 %.
TEST(WelchPsd, OneSigmaIntervalsOfBAndKCoverTheTruthWithFlicker) {
  const Simulated s = three_terms();
  const auto truth = truth_of(s.parameters);
  Coverage coverage;
  coverage.seeds = 100;
  for (int seed = 1; seed <= coverage.seeds; ++seed) {
    const SpectralNoiseTerms n = psd_of(s, static_cast<std::uint64_t>(seed)).noise;
    ASSERT_TRUE(n.identified[1]);
    EXPECT_NEAR_RELATIVE(n.angle_random_walk.value, truth[0], 0.10);
    if (n.identified[2] && covers(n.bias_instability, truth[1])) ++coverage.covered[1];
    if (n.identified[3] && covers(n.rate_random_walk, truth[2])) ++coverage.covered[2];
  }
  for (std::size_t k : {1, 2}) {
    RecordProperty(std::array{"coverage_N", "coverage_B", "coverage_K"}[k], std::to_string(coverage.rate(k)));
    EXPECT_GE(coverage.rate(k), 0.55) << "term " << k;
    EXPECT_LE(coverage.rate(k), 0.80) << "term " << k;
  }
}

// As the Allan fit's (NoiseTerms.ATermIsSignificantWhereTheRecordHasIt), over 100 seeds each of
// white noise alone, with a rate random walk, and with flicker too: B and K absent from the record
// are identified (left free) in 28-40 of 100 but significant in at most 1; the terms present are
// significant in 98-100. (R, held at zero unless 2 sigma above it, is significant whenever kept:
// 7 and 4 of 100 here, and its figure is flagged and not compared, see RateRampIsFlaggedAndNotCompared.)
TEST(WelchPsd, ATermIsSignificantWhereTheRecordHasIt) {
  Simulated white;
  white.parameters.angle_random_walk = 1.0;
  for (const Simulated& c : {white, white_and_random_walk(), three_terms()}) {
    const auto truth = truth_of(c.parameters);  // N, B, K
    std::array<int, 3> significant{};
    constexpr int kSeeds = 100;
    for (int seed = 1; seed <= kSeeds; ++seed) {
      const SpectralNoiseTerms n = psd_of(c, static_cast<std::uint64_t>(seed)).noise;
      for (std::size_t k = 0; k < 3; ++k) {
        significant[k] += n.significant[k + 1];
        ASSERT_EQ(n.significant[k + 1], !n.upper_bounds[k + 1].has_value()) << k;
      }
    }
    for (std::size_t k = 0; k < 3; ++k) {
      if (truth[k] == 0.0) {
        EXPECT_LE(significant[k], 8) << "an absent term " << k << " read as significant";
      } else {
        EXPECT_GE(significant[k], 95) << "a present term " << k << " not significant";
      }
    }
  }
}

// The noise fit scales with the record: samples s times larger give terms s times larger, whatever
// s (1e100 and 1e-100 overflowed or underflowed the covariance of the bands and crashed the QR).
TEST(WelchPsd, NoiseFitScalesWithTheRecordAtAnyMagnitude) {
  sim::Random random(5);
  std::vector<double> x(1 << 14);
  for (double& v : x) v = random.normal();
  WelchOptions options;
  options.sample_rate_hz = 100.0;
  const SpectralNoiseTerms unit = welch_power_spectral_density(x, "deg/h", options).noise;
  ASSERT_TRUE(unit.identified[1]);
  for (double s : {1e-100, 1e45, 1e100}) {
    std::vector<double> scaled = x;
    for (double& v : scaled) v *= s;
    const SpectralNoiseTerms terms = welch_power_spectral_density(scaled, "deg/h", options).noise;
    EXPECT_EQ(terms.identified, unit.identified) << s;
    EXPECT_NEAR_RELATIVE(terms.angle_random_walk.value, s * unit.angle_random_walk.value, 1e-9) << s;
    EXPECT_NEAR_RELATIVE(*terms.angle_random_walk.uncertainty, s * *unit.angle_random_walk.uncertainty, 1e-9) << s;
  }
}

// The segments' means are taken about the first sample: the record at an offset of 1e8 has the
// density of the same record less 1e8 (exact, Sterbenz). Stored near the offset, the means were
// rounded to 1.5e-8 and the DC left in leaked into the lowest band (8e-5 of it for noise of 1e-3).
TEST(WelchPsd, TheDensityDoesNotDependOnTheOffset) {
  sim::Random random(6);
  std::vector<double> at_offset(1 << 16);
  std::vector<double> shifted(at_offset.size());
  for (std::size_t i = 0; i < at_offset.size(); ++i) {
    at_offset[i] = 1e8 + 1e-3 * random.normal();
    shifted[i] = at_offset[i] - 1e8;
  }
  WelchOptions options;
  options.sample_rate_hz = 100.0;
  const PowerSpectralDensity big = welch_power_spectral_density(at_offset, "deg/h", options);
  const PowerSpectralDensity small = welch_power_spectral_density(shifted, "deg/h", options);
  ASSERT_EQ(big.density.size(), small.density.size());
  for (std::size_t k = 1; k < big.density.size(); ++k) {  // 0 Hz: the segments' means are removed
    EXPECT_NEAR_RELATIVE(big.density[k], small.density[k], 1e-12) << k;
  }
}

// The sinusoid of sinusoid_on_noise() is found within kCheckSigmas of its frequency and amplitude
// uncertainties, and its bins are left out of the noise fit, so that N and K still cover the truth
// within kCheckSigmas of theirs. Each check at 3.5 sigma fails by chance with probability 4.7e-4
// (normal); with four checks and the peak search's false-alarm probability of 1e-3, a seed fails by
// chance in about 0.3 % of seeds. Measured over seeds 1-1000: 998 pass (one shows a second, false
// component, one has N at 3.7 sigma); at the 5 % amplitude tolerance this test had before (0.85 of
// the amplitude's 1-sigma scatter), and N and K at 2 sigma, 541.
constexpr double kCheckSigmas = 3.5;

// A sinusoid of 0.5 deg/h at 1.234 Hz (the mean over each sample interval: amplitude 0.5 sinc(f0 dt))
// on white noise and rate random walk, 32768 samples at 10 Hz: 8 times the floor, its amplitude read
// to about 6 % (1 sigma).
struct SinusoidOnNoise {
  std::vector<double> rate;
  double frequency_hz = 1.234;
  double amplitude = 0.0;
};

SinusoidOnNoise sinusoid_on_noise(std::uint64_t seed) {
  const Simulated s = white_and_random_walk();
  SinusoidOnNoise record;
  record.rate = simulated_rate(s.parameters, s.dt, s.samples, seed);
  const double f0 = record.frequency_hz;
  record.amplitude = 0.5 * std::sin(kPi * f0 * s.dt) / (kPi * f0 * s.dt);
  for (std::size_t n = 0; n < record.rate.size(); ++n) {
    record.rate[n] += record.amplitude * std::sin(2.0 * kPi * f0 * (static_cast<double>(n) + 0.5) * s.dt);
  }
  return record;
}

TEST(WelchPsd, SinusoidOnNoiseIsFoundAndLeftOutOfTheNoiseFit) {
  const Simulated s = white_and_random_walk();
  const SinusoidOnNoise record = sinusoid_on_noise(77);
  WelchOptions options;
  options.sample_rate_hz = 1.0 / s.dt;
  const PowerSpectralDensity psd = welch_power_spectral_density(record.rate, "deg/h", options);
  ASSERT_EQ(psd.peaks.size(), 1U);
  const PeriodicComponent& peak = psd.peaks[0];
  EXPECT_TRUE(covers(peak.frequency, record.frequency_hz, kCheckSigmas))
      << peak.frequency.value << " +- " << *peak.frequency.uncertainty;
  EXPECT_LT(*peak.frequency.uncertainty, 0.2 * psd.resolution_hz);
  EXPECT_EQ(peak.frequency.unit, "Hz");
  EXPECT_TRUE(covers(peak.amplitude, record.amplitude, kCheckSigmas))
      << peak.amplitude.value << " +- " << *peak.amplitude.uncertainty;
  EXPECT_EQ(peak.amplitude.unit, "deg/h");
  EXPECT_LT(peak.frequency_low_hz, record.frequency_hz);
  EXPECT_GT(peak.frequency_high_hz, record.frequency_hz);
  const auto truth = truth_of(s.parameters);
  EXPECT_TRUE(covers(psd.noise.angle_random_walk, truth[0], kCheckSigmas)) << psd.noise.angle_random_walk.value;
  EXPECT_TRUE(covers(psd.noise.rate_random_walk, truth[2], kCheckSigmas)) << psd.noise.rate_random_walk.value;
}

// The amplitude's 1-sigma interval covers the truth in 55-80 % of 100 seeds of sinusoid_on_noise()
// (68 % expected, binomial spread 4.7 %) and its 2-sigma interval in at least 88 % (95 % expected).
// The variance counts the correlation of the bins of one window and the sinusoid-noise cross term
// over the whole window (cross_term_factor in power_spectral_density.cc); counted bin by bin as if
// independent, it was 0.52 of the scatter: 54 % and 84 % over 1000 seeds. Measured (1000 seeds):
// 67 % and 95.5 %, the amplitude's scatter 1.01 times its uncertainty, its mean 0.2 % low.
TEST(WelchPsd, PeriodicComponentAmplitudeUncertaintyCoversTheTruth) {
  int within_one = 0;
  int within_two = 0;
  constexpr int kSeeds = 100;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const SinusoidOnNoise record = sinusoid_on_noise(static_cast<std::uint64_t>(seed));
    WelchOptions options;
    options.sample_rate_hz = 10.0;
    const PowerSpectralDensity psd = welch_power_spectral_density(record.rate, "deg/h", options);
    ASSERT_FALSE(psd.peaks.empty()) << seed;
    if (covers(psd.peaks[0].amplitude, record.amplitude, 1.0)) ++within_one;
    if (covers(psd.peaks[0].amplitude, record.amplitude, 2.0)) ++within_two;
  }
  RecordProperty("coverage_1_sigma", std::to_string(within_one));
  RecordProperty("coverage_2_sigma", std::to_string(within_two));
  EXPECT_GE(within_one, 55);
  EXPECT_LE(within_one, 80);
  EXPECT_GE(within_two, 88);
}

// Pure noise (white and rate random walk) over 50 seeds: at the default false-alarm probability of
// 1e-3 for the whole spectrum no component is reported; at 0.3, at most 21 seeds of 50 show one (15
// expected, + 2 binomial sigma). Measured: 0 and 14 (at 0.1: 3).
TEST(WelchPsd, PureNoiseShowsNoMoreFalseAlarmsThanTheThresholdPromises) {
  const Simulated s = white_and_random_walk();
  for (double probability : {1e-3, 0.3}) {
    int seeds_with_alarm = 0;
    for (int seed = 1001; seed <= 1050; ++seed) {
      WelchOptions options;
      options.sample_rate_hz = 1.0 / s.dt;
      options.false_alarm_probability = probability;
      const PowerSpectralDensity psd = welch_power_spectral_density(
          simulated_rate(s.parameters, s.dt, s.samples, static_cast<std::uint64_t>(seed)), "deg/h", options);
      if (!psd.peaks.empty()) ++seeds_with_alarm;
    }
    EXPECT_LE(seeds_with_alarm, probability < 0.01 ? 0 : 21) << probability;
  }
}

// Quantization (white angle noise, differenced: the simulator's Q) on white noise, 32768 samples at
// 10 Hz: Q = 0.35 arcsec ((deg/h)*s) reads 8 Q^2 sin^2(pi f tau0) / tau0, 5 times the white level 2 N^2
// at the Nyquist frequency; Q and N come back within 2 of their uncertainties over 5 seeds (measured:
// Q 0.347-0.355 +- 0.0027 arcsec, N 0.987-1.012 +- 0.011 deg/h*sqrt(s)).
TEST(WelchPsd, QuantizationNoiseGivesQ) {
  Simulated s;
  s.parameters.angle_random_walk = 1.0;
  s.parameters.quantization = 0.35;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const SpectralNoiseTerms terms = psd_of(s, seed).noise;
    ASSERT_TRUE(terms.identified[0]) << seed;
    EXPECT_EQ(terms.quantization.unit, "arcsec");
    EXPECT_TRUE(covers(terms.quantization, 0.35, 2.0)) << seed << ": " << terms.quantization.value << " +- "
                                                        << *terms.quantization.uncertainty;
    EXPECT_TRUE(covers(terms.angle_random_walk, 1.0 / 60.0, 2.0)) << seed << ": " << terms.angle_random_walk.value;
  }
}

// A rate ramp of 0.1 deg/h/s (360 deg/h/h) on white noise: R is read but understated, and a warning
// says so; the comparison with the Allan fit leaves R out.
TEST(WelchPsd, RateRampIsFlaggedAndNotCompared) {
  sim::Random random(3);
  std::vector<double> x(1 << 15);
  for (std::size_t n = 0; n < x.size(); ++n) x[n] = std::sqrt(10.0) * random.normal() + 0.1 * static_cast<double>(n) * 0.1;
  WelchOptions options;
  options.sample_rate_hz = 10.0;
  const PowerSpectralDensity psd = welch_power_spectral_density(x, "deg/h", options);
  ASSERT_TRUE(psd.noise.identified[4]);
  EXPECT_LT(psd.noise.rate_ramp.value, 360.0);
  EXPECT_THAT(psd.warnings, ::testing::Contains(::testing::HasSubstr("understates a deterministic ramp")));
  EXPECT_TRUE(covers(psd.noise.angle_random_walk, 1.0 / 60.0, 2.0));
  NoiseTerms allan;
  allan.identified = {false, false, false, false, true};
  allan.rate_ramp = Figure{360.0, "deg/h/h", 1.0};
  EXPECT_THAT(compare_noise_terms(allan, psd.noise), ::testing::IsEmpty());
}

// The JSON carries the band means (not every bin), in the units the header states.
TEST(WelchPsd, JsonCarriesTheBandsTheNoiseTermsAndThePeaks) {
  const Simulated s = white_and_random_walk();
  std::vector<double> x = simulated_rate(s.parameters, s.dt, s.samples, 5);
  for (std::size_t n = 0; n < x.size(); ++n) x[n] += std::sin(2.0 * kPi * 2.5 * static_cast<double>(n) * s.dt);
  WelchOptions options;
  options.sample_rate_hz = 1.0 / s.dt;
  options.window = parse_spectral_window("blackman-harris");
  const PowerSpectralDensity psd = welch_power_spectral_density(x, "deg/h", options);
  const nlohmann::json json = psd.to_json();
  EXPECT_EQ(json["window"], "blackman-harris");
  EXPECT_EQ(json["segment_length"], 2048);
  EXPECT_EQ(json["segment_count"], 31);
  EXPECT_EQ(json["overlap"], 0.5);
  EXPECT_DOUBLE_EQ(json["resolution_hz"].get<double>(), 10.0 / 2048);
  EXPECT_EQ(json["bands_per_decade"], kBandsPerDecade);
  const auto bands = json["band_frequency_hz"].size();
  EXPECT_GT(bands, 40U);
  EXPECT_LT(bands, 80U);
  EXPECT_EQ(json["band_edf"].size(), bands);
  EXPECT_EQ(json["density"]["unit"], "(deg/h)^2/Hz");
  EXPECT_EQ(json["density"]["values"].size(), bands);
  EXPECT_EQ(json["amplitude_spectral_density"]["unit"], "(deg/h)/sqrt(Hz)");
  EXPECT_DOUBLE_EQ(json["amplitude_spectral_density"]["values"][3].get<double>(),
                   std::sqrt(json["density"]["values"][3].get<double>()));
  EXPECT_EQ(json["noise_terms"]["angle_random_walk"]["unit"], "deg/sqrt(h)");
  EXPECT_EQ(json["noise_terms"]["rate_random_walk"]["unit"], "deg/h/sqrt(h)");
  EXPECT_EQ(json["noise_terms"]["fit"]["verdict"], "consistent");
  ASSERT_EQ(json["peaks"].size(), 1U);
  EXPECT_EQ(json["peaks"][0]["frequency"]["unit"], "Hz");
  EXPECT_NEAR(json["peaks"][0]["frequency"]["value"].get<double>(), 2.5, psd.resolution_hz);
  EXPECT_EQ(json["peaks"][0]["amplitude"]["unit"], "deg/h");
  EXPECT_EQ(json["peak_search"]["false_alarm_probability"], 1e-3);
  EXPECT_TRUE(json["warnings"].empty());
}

NoiseTerms allan_terms(double n, double n_sigma, double k, double k_sigma) {
  NoiseTerms terms;
  terms.identified = {false, true, false, true, false};
  terms.angle_random_walk = Figure{n, "deg/sqrt(h)", n_sigma};
  terms.rate_random_walk = Figure{k, "deg/h/sqrt(h)", k_sigma};
  return terms;
}

// One warning per term both identify that differs by more than 3 combined sigma, none otherwise; a
// term only one fit identifies is not compared. The PSD's figure is converted to the Allan unit.
TEST(WelchPsd, ComparisonWarnsOnlyBeyondThreeCombinedSigma) {
  SpectralNoiseTerms psd;
  psd.identified = {false, true, true, true, false};
  psd.angle_random_walk = Figure{0.5 * 60.0, "(deg/h)*sqrt(s)", 0.03 * 60.0};  // 0.5 +- 0.03 deg/sqrt(h)
  psd.bias_instability = Figure{3.0, "deg/h", 0.1};
  psd.rate_random_walk = Figure{4.0, "deg/h/sqrt(h)", 0.3};
  EXPECT_TRUE(compare_noise_terms(allan_terms(0.55, 0.04, 4.5, 0.5), psd).empty());  // 1.0 and 0.86 sigma
  const std::vector<std::string> warnings = compare_noise_terms(allan_terms(0.7, 0.04, 4.5, 0.5), psd);
  ASSERT_EQ(warnings.size(), 1U);  // N: 0.2 / 0.05 = 4 sigma
  EXPECT_THAT(warnings[0], ::testing::HasSubstr("angle random walk N"));
  EXPECT_THAT(warnings[0], ::testing::HasSubstr("4.0 combined sigma"));
  EXPECT_THAT(warnings[0], ::testing::HasSubstr("0.5 +- 0.03 deg/sqrt(h)"));
  EXPECT_EQ(compare_noise_terms(allan_terms(0.7, 0.04, 6.0, 0.5), psd).size(), 2U);  // and K: 2 / 0.58 = 3.4
  psd.identified[1] = false;
  EXPECT_EQ(compare_noise_terms(allan_terms(0.7, 0.04, 4.5, 0.5), psd).size(), 0U);
}

TEST(WelchPsd, BadOptionsAndSamplesSayWhatIsWrong) {
  const std::vector<double> x(64, 1.0);
  const auto message = [&](const WelchOptions& options, std::span<const double> samples) {
    try {
      welch_power_spectral_density(samples, "V", options);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  WelchOptions options;
  options.sample_rate_hz = 10.0;
  options.segment_length = 65;
  EXPECT_THAT(message(options, x), ::testing::HasSubstr("segment length 65 is longer than the record (64 samples)"));
  options.segment_length = 0;
  for (double overlap : {1.0, -0.1, std::nan("")}) {
    options.overlap = overlap;
    EXPECT_THAT(message(options, x), ::testing::HasSubstr("overlap must lie in [0, 1)"));
  }
  options.overlap = 0.5;
  for (double rate : {0.0, -10.0, std::numeric_limits<double>::infinity()}) {
    options.sample_rate_hz = rate;
    EXPECT_THAT(message(options, x), ::testing::HasSubstr("sample rate must be positive and finite"));
  }
  options.sample_rate_hz = 10.0;
  options.false_alarm_probability = 1.0;
  EXPECT_THAT(message(options, x), ::testing::HasSubstr("false-alarm probability"));
  options.false_alarm_probability = 1e-3;
  std::vector<double> with_nan = x;
  with_nan[17] = std::nan("");
  EXPECT_THAT(message(options, with_nan), ::testing::HasSubstr("sample 18 is not finite"));
  EXPECT_THAT(message(options, std::span(x).first(10)), ::testing::HasSubstr("at least 16 samples (got 10)"));
  EXPECT_THROW(parse_spectral_window("hanning"), Error);
  try {
    parse_spectral_window("kaiser");
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("unknown spectral window 'kaiser'"));
  }
  for (const char* name : {"rectangular", "hann", "hamming", "blackman-harris"}) {
    EXPECT_EQ(spectral_window_name(parse_spectral_window(name)), name);
  }
  // A constant record: a PSD of zeros, no component, and no fit.
  const PowerSpectralDensity constant = welch_power_spectral_density(x, "V", options);
  EXPECT_TRUE(constant.peaks.empty());
  EXPECT_EQ(constant.noise.verdict, "not fitted");
}

// FFTW's planner is called under a mutex: PSDs computed on several threads at once equal the one
// computed alone.
TEST(WelchPsd, ThreadsComputeTheSameDensity) {
  const Simulated s = white_and_random_walk();
  const std::vector<double> x = simulated_rate(s.parameters, s.dt, 1 << 13, 3);
  WelchOptions options;
  options.sample_rate_hz = 10.0;
  const PowerSpectralDensity alone = welch_power_spectral_density(x, "deg/h", options);
  std::vector<PowerSpectralDensity> results(4);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < results.size(); ++t) {
    threads.emplace_back([&, t] {
      WelchOptions own = options;
      own.segment_length = 256 << (t % 2);  // plans of two sizes at once
      results[t] = welch_power_spectral_density(x, "deg/h", own);
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (std::size_t t = 0; t < results.size(); ++t) {
    WelchOptions own = options;
    own.segment_length = 256 << (t % 2);
    EXPECT_EQ(results[t].density, welch_power_spectral_density(x, "deg/h", own).density) << t;
  }
  EXPECT_EQ(alone.segment_length, 512U);
}

// The Done-when of issue 19 (PSD part): a record with known N, B, K and a sinusoid gives each
// coefficient back within its 1-sigma uncertainty, and the sinusoid is found. 65536 samples at 10 Hz
// (deg/h): N = 1 deg/h*sqrt(s), B = 1.12 deg/h, K = 0.397 deg/h/sqrt(s) (crossovers 0.2 and 0.02 Hz),
// 0.5 deg/h at 1.234 Hz. The flicker's Gauss-Markov processes start at dt / 16 (simulated at dt / 16),
// so that its spectrum is 1/f up to the Nyquist frequency within 12 % (see the coverage test above).
// Measured (seed 3): N, B, K at +0.66, -0.82, +0.67 of their uncertainties.
TEST(WelchPsd, RecordWithKnownNoiseAndASinusoidGivesEachTermBack) {
  sim::NoiseParameters p;
  p.angle_random_walk = 1.0;
  p.bias_instability = 1.12;
  p.rate_random_walk = 0.397;
  const double dt = 0.1;
  p.flicker_shortest_s = dt / 16;
  p.flicker_longest_s = 1e5;
  std::vector<double> x = simulated_rate(p, dt, 1 << 16, 3, 16);
  const double f0 = 1.234;
  const double amplitude = 0.5;
  for (std::size_t n = 0; n < x.size(); ++n) x[n] += amplitude * std::sin(2.0 * kPi * f0 * static_cast<double>(n) * dt);
  WelchOptions options;
  options.sample_rate_hz = 1.0 / dt;
  const PowerSpectralDensity psd = welch_power_spectral_density(x, "deg/h", options);
  const SpectralNoiseTerms& terms = psd.noise;
  const auto truth = truth_of(p);
  ASSERT_TRUE(terms.identified[1] && terms.identified[2] && terms.identified[3]);
  EXPECT_TRUE(covers(terms.angle_random_walk, truth[0])) << terms.angle_random_walk.value;
  EXPECT_TRUE(covers(terms.bias_instability, truth[1])) << terms.bias_instability.value;
  EXPECT_TRUE(covers(terms.rate_random_walk, truth[2])) << terms.rate_random_walk.value;
  EXPECT_EQ(terms.verdict, "consistent");
  ASSERT_EQ(psd.peaks.size(), 1U);
  EXPECT_NEAR(psd.peaks[0].frequency.value, f0, psd.resolution_hz);
  // The sample is the value at n dt, not the interval's mean: the amplitude is 0.5 itself.
  EXPECT_NEAR_RELATIVE(psd.peaks[0].amplitude.value, amplitude, 0.05);
  // The Allan fit of the same record agrees within 3 combined sigma: no warning.
  AllanOptions allan_options;
  allan_options.sample_rate_hz = 1.0 / dt;
  allan_options.estimators = EstimatorSet::parse("oadev");
  allan_options.worker_count = 1;
  const AllanResult allan = allan_variance(x, allan_options);
  ASSERT_TRUE(allan.noise.has_value());
  EXPECT_THAT(compare_noise_terms(*allan.noise, terms), ::testing::IsEmpty());
  // Its units are those of the PSD's figures.
  EXPECT_EQ(allan.noise->bias_instability.unit, terms.bias_instability.unit);
}

}  // namespace
}  // namespace inertest
