// The test generators of the virtual lab, each in a short case: every kind is simulated, its
// processing plan run through the demo's truth check, and every truth entry must be within its
// tolerance. Plus known answers of the statistical helpers the tolerances rest on.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <set>

#include "inertest/core/units.h"
#include "inertest/demo/demo.h"
#include "inertest/sim/accelerometer_model.h"
#include "inertest/sim/simulation.h"
#include "sim/lab.h"
#include "test_util/test_util.h"

namespace inertest::sim {
namespace {

using inertest::testing::ScratchDirectory;

// Every simulated kind, short.
const char* kEveryKind = R"(seed = 11
[site]
latitude_deg = 45.75
[gyro]
sample_rate_hz = 100
nonlinearity_ppm = [0, 8]
asymmetry_ppm = 6
scale_factor_temperature_ppm_per_c = 1.5
scale_factor_repeatability_ppm = 5
bias_deg_h = 0.02
bias_temperature_deg_h_per_c = 0.003
bias_repeatability_deg_h = 0.03
turn_on_bias_deg_h = 3
turn_on_time_constant_s = 150
angle_random_walk_deg_rt_h = 0.0005
bias_instability_deg_h = 0.005
rate_random_walk_deg_h_rt_h = 0.003
flicker_correlation_s = [0.1, 1e6]
bandwidth_hz = 300
delay_ms = 0.8
input_axis_misalignment_arcsec = [25, -15]
[gyro.drift]
DI = 0.01
DS = 0.004
[accelerometer]
scale_factor = 1.3
misalignment_arcsec = [20, -5]
noise_ug_rt_hz = 20
[rate_table]
rate_error_ppm = 0.5
tilt_arcsec = [2, -1]
wobble_arcsec = 1
face_arcsec = [5, 3]
fixture_arcsec = -50
[dividing_head]
tilt_arcsec = 6
[[test]]
kind = "scale_factor"
rates_deg_s = [1, 10, 100, 300]
seconds_per_rate = 5
static_seconds = 5
[[test]]
kind = "scale_factor_repeatability"
runs = 6
seconds_per_rate = 2
static_seconds = 2
[[test]]
kind = "scale_factor_temperature"
soak_s = 1800
seconds_per_rate = 2
static_seconds = 2
[[test]]
kind = "maximum_input_rate"
nonlinearity_limit_ppm = 5
seconds_per_rate = 2
static_seconds = 2
[[test]]
kind = "bias"
seconds = 600
smoothing_s = [1, 10]
[[test]]
kind = "bias_repeatability"
seconds = 60
[[test]]
kind = "bias_temperature"
seconds = 60
[[test]]
kind = "turn_on_time"
seconds = 900
[[test]]
kind = "warm_up_time"
seconds = 900
[[test]]
kind = "polarity"
[[test]]
kind = "threshold"
seconds = 5
[[test]]
kind = "resolution"
seconds = 5
[[test]]
kind = "bandwidth"
cycles = 5
minimum_seconds = 0.1
[[test]]
kind = "input_axis_misalignment"
revolutions = 1
[[test]]
kind = "gyro_misalignment"
revolutions = 1
[[test]]
kind = "accelerometer_misalignment"
seconds_per_position = 10
[[test]]
kind = "allan"
hours = 12
sample_rate_hz = 5
[[test]]
kind = "centrifuge"
revolutions = 5
[[test]]
kind = "imu_tumble"
orientations = 14
[[test]]
kind = "accelerometer_tumble"
)";

TEST(SimGenerators, EveryKindRecoversItsTruthInAShortCase) {
  ScratchDirectory dir;
  const std::string plan = dir.path() + "/every_kind.toml";
  std::ofstream(plan) << kEveryKind;
  DemoOptions options;
  options.simulation_plan = plan;
  const DemoSummary summary = run_demo(dir.path() + "/out", options);
  std::set<std::string> procedures;
  for (const auto& c : summary.results.at("truth_check")) {
    EXPECT_TRUE(c.at("within").get<bool>()) << c.dump();
    procedures.insert(c.at("procedure").get<std::string>());
  }
  for (const char* kind : {"scale_factor", "scale_factor_repeatability", "scale_factor_temperature",
                           "maximum_input_rate", "bias", "bias_repeatability", "bias_temperature", "turn_on_time",
                           "warm_up_time", "polarity", "threshold", "resolution", "bandwidth", "input_axis_misalignment",
                           "gyro_misalignment",
                           "accelerometer_misalignment", "allan", "centrifuge", "imu_tumble", "accelerometer_tumble"}) {
    EXPECT_TRUE(procedures.count(kind)) << kind << " has no truth check";
  }
  EXPECT_TRUE(summary.results.at("not_checked").empty()) << summary.results.at("not_checked").dump();
}

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(SimGenerators, EveryKindIsByteIdenticalForTheSameSeed) {
  ScratchDirectory a;
  ScratchDirectory b;
  const SimulationSummary first = simulate_text(kEveryKind, "every_kind", a.path());
  const SimulationSummary second = simulate_text(kEveryKind, "every_kind", b.path());
  ASSERT_EQ(first.written_files.size(), second.written_files.size());
  for (std::size_t i = 0; i < first.written_files.size(); ++i) {
    const auto relative = std::filesystem::relative(first.written_files[i], a.path());
    ASSERT_EQ(relative, std::filesystem::relative(second.written_files[i], b.path()));
    EXPECT_EQ(read(first.written_files[i]), read(second.written_files[i])) << relative;
  }
  EXPECT_EQ(first.truth.dump(), second.truth.dump());
}

TEST(SimStatistics, MeanAndWindowNoiseOfPureAngleRandomWalk) {
  GyroParameters gyro;
  gyro.scale_factor = 1e12;  // no counter quantisation to speak of
  gyro.angle_random_walk_deg_rt_h = 0.06;  // 0.001 deg/√s
  EXPECT_NEAR_RELATIVE(noise_of_record_mean_deg_s(gyro, 100.0), 0.001 / 10.0, 1e-9);
  // White noise: the expected sd of window means is N/√τ whatever the number of windows.
  EXPECT_NEAR_RELATIVE(expected_window_sd_deg_s(gyro, 4.0, 50.0), 0.001 / 2.0, 1e-9);
  // Rate random walk alone: n windows of a random walk, E[s²] = n·K²τ/6.
  GyroParameters walk;
  walk.scale_factor = 1e12;
  walk.rate_random_walk_deg_h_rt_h = 60.0;  // 60 deg/h/√h = 1/3600 deg/s/√s
  const double k = 1.0 / 3600.0;            // deg/s/√s
  EXPECT_NEAR_RELATIVE(expected_window_sd_deg_s(walk, 10.0, 20.0), std::sqrt(20.0 * k * k * 10.0 / 6.0), 1e-9);
  EXPECT_NEAR_RELATIVE(noise_of_record_mean_deg_s(walk, 30.0), std::sqrt(k * k * 30.0 / 3.0), 1e-9);
}

TEST(SimStatistics, WindowSdSigmaOfWhiteNoiseIsTheTextbookOne) {
  GyroParameters gyro;
  gyro.scale_factor = 1e12;
  gyro.angle_random_walk_deg_rt_h = 0.06;  // 0.001 deg/√s
  const double s = 0.001 / std::sqrt(4.0);
  // Var(s²) = 2σ⁴/(n − 1) for white noise: sd(s) = s/√(2(n − 1)); the autocovariance form, centred
  // on the grand mean (γ̄ = σ²/n), gives Var(s²) = (2/n)·σ⁴·(1 − 1/n), sd(s) = s·√(n − 1)/(√2·n): the
  // two agree to O(1/n).
  EXPECT_NEAR_RELATIVE(window_sd_sigma_deg_s(gyro, 4.0, 200.0), s / std::sqrt(2.0 * 199.0), 2.0 / 200.0);
  EXPECT_NEAR_RELATIVE(window_sd_sigma_deg_s(gyro, 4.0, 200.0), s * std::sqrt(199.0) / (std::sqrt(2.0) * 200.0), 1e-9);
}

TEST(SimStatistics, SampleSdBoundIsTheChiQuantile) {
  // χ²_5 at 1 − 3.17e-5 (one-sided 4 sigma) is 29.3 (tables); Wilson-Hilferty gives 29.1.
  EXPECT_NEAR(sample_sd_bound(1.0, 6.0, 4.0), std::sqrt(29.3 / 5.0), 0.02);
  EXPECT_NEAR(sample_sd_bound(2.0, 1001.0, 0.0), 2.0, 0.01);
}

TEST(SimStatistics, InvertSolvesAndRejectsSingular) {
  const auto inv = invert({{4, 1}, {2, 3}});
  EXPECT_NEAR(inv[0][0], 0.3, 1e-15);
  EXPECT_NEAR(inv[0][1], -0.1, 1e-15);
  EXPECT_NEAR(inv[1][0], -0.2, 1e-15);
  EXPECT_NEAR(inv[1][1], 0.4, 1e-15);
  EXPECT_THROW(invert({{1, 2}, {2, 4}}), Error);
}

TEST(SimAccelerometer, FourPositionClosedFormsGiveItsAngles) {
  AccelerometerParameters p;
  p.scale_factor = 1.3;
  p.bias_g = 5e-4;
  p.misalignment_arcsec = {20.0, -5.0};
  AccelerometerModel model(p, Random(1));
  // IA horizontal, turned β about itself: gravity (1 g up) in the IA/PA/OA frame is (0, sin β, cos β).
  auto v = [&](double beta_deg) {
    const double b = beta_deg * constants::kDegree;
    return model.noise_free_output({0.0, std::sin(b), std::cos(b)});
  };
  // Reference README §2: Δθy2 = (V(π) − V(0))/(2kI) = −sin b, Δθz2 = (V(π/2) − V(3π/2))/(2kI) = sin a·cos b.
  EXPECT_NEAR((v(180) - v(0)) / (2 * p.scale_factor) / constants::kArcsecond, 5.0, 1e-6);
  EXPECT_NEAR((v(90) - v(270)) / (2 * p.scale_factor) / constants::kArcsecond, 20.0, 1e-6);
  // Noise and quantisation: the mean of many samples converges on the noise-free output.
  p.noise_ug_rt_hz = 50;
  p.output_resolution = 1e-5;
  AccelerometerModel noisy(p, Random(2));
  const auto samples = noisy.record({1.0, 0.0, 0.0}, 20000);
  double mean = 0;
  for (const double s : samples) mean += s / samples.size();
  // σ of the mean: 50 µg/√Hz over 2000 s is 0.79 µg; 5 sigma in volts.
  EXPECT_NEAR(mean, 1.3 * (1.0 + 5e-4), 5 * 1.3 * 0.79e-6);
  EXPECT_THROW(AccelerometerModel(AccelerometerParameters{.scale_factor = 0.0}, Random(1)), Error);
}

}  // namespace
}  // namespace inertest::sim
