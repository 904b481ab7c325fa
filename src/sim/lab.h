// What the simulation's test generators share: the instrument, the site and rigs, the seed, where
// to write, and how to record truth and plan steps. Private to src/sim.
#pragma once

#include <cmath>
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "campaign/plan_table.h"
#include "inertest/core/progress.h"
#include "inertest/sim/accelerometer_model.h"
#include "inertest/sim/centrifuge.h"
#include "inertest/sim/gyro_model.h"
#include "inertest/sim/rigs.h"

namespace inertest::sim {

// One true figure for the truth check: the plan step `procedure` reports it as `figure` (a key
// of its result or a JSON pointer); `tolerance` is the bound the estimate must meet (several
// standard deviations of the estimator for this record, plus any known rig systematic).
struct TruthEntry {
  std::string procedure;
  std::string quantity;
  std::string figure;  // empty: no plan step reports it yet
  double value = 0.0;
  std::string unit;
  double tolerance = 0.0;
  std::string basis;  // how the tolerance was derived
  // A known systematic effect of the rigs or of the method, predicted from the model: the estimate
  // is expected at value + systematic, within the tolerance.
  double systematic = 0.0;
  // > 0: the tolerance is this many times the 1-sigma uncertainty the procedure reports with the
  // figure (used where that uncertainty is the estimator's own, e.g. the Allan fit's edf-based one);
  // `tolerance` is then 0.
  double tolerance_sigmas = 0.0;
};

struct Lab {
  std::string out_dir;
  std::string plan_path;  // the simulation plan: no file of the lab may replace it
  std::uint64_t seed = 0;
  Site site;
  std::string site_name;
  GyroParameters gyro;
  RateTable rate_table;
  double fixture_tilt_rad = 0.0;  // Δθy1: the rate-table fixture's vertical face leaning (misalignment paper)
  // The dividing head of the accelerometer test: its horizontal axis tilted up by Δθy0, the
  // fixture face by Δθy1 (misalignment paper).
  double dividing_head_tilt_rad = 0.0;
  double dividing_head_fixture_rad = 0.0;
  AccelerometerParameters accelerometer;
  Centrifuge centrifuge;  // geometry and errors; rate and β are set per run
  ProgressCallback progress;
  // First pass over the plan: generators read and check their keys, then return before simulating.
  bool dry_run = false;

  std::vector<std::string> written_files;
  std::vector<TruthEntry> truth;
  nlohmann::json tests = nlohmann::json::array();
  std::string plan_steps;  // [[procedure]] tables in TOML

  // Writes out_dir/relative (directories created) and remembers it; require_not_the_plan first.
  void write(const std::string& relative, const std::string& content);
  // Throws Error when out_dir/relative is the simulation plan (by any path to it): `simulate
  // lab/plan.toml --out lab` replaced the plan with the processing plan it made.
  void require_not_the_plan(const std::string& relative) const;
  // The samples of a record of `seconds` at `rate_hz`, rounded; more than the simulator makes in one
  // record (10^9, 8 GB of counts), or no number, is an Error at the plan (seconds = 1e12 was an
  // internal error, std::bad_alloc).
  std::size_t samples(double seconds, double rate_hz) const;
  Random random(const std::string& stream) const { return Random(seed).stream(stream); }
};

// One test of the simulation plan: reads its keys from `test`, simulates, writes its records,
// adds its truth, and its plan step when the library processes that kind.
using TestGenerator = void (*)(campaign::PlanTable& test, const std::string& name, Lab& lab);

// A time series as a test station exports it: header time,output; time in s at the centre of
// each counting interval, output in the instrument's unit (pulse count × sample rate).
std::string time_series_csv(const std::vector<std::int64_t>& pulses, double sample_rate_hz, double start_s,
                            const std::string& comment);

// Allan deviation of the model's noise for averaging time τ (IEEE 952 C.2-C.8 summed), deg/s,
// plus the pulse counter's quantization of a τ-mean: the 1-sigma noise of a τ-second mean
// relative to another, used for the tolerances.
double noise_of_mean_deg_s(const GyroParameters& gyro, double tau_s);

// The same samples as a raw little-endian f64 record (one channel: the output in the instrument's
// unit), as the long static records are written.
std::string f64_record(const std::vector<std::int64_t>& pulses, double sample_rate_hz);

// Mean output (instrument unit) of pulse counts at the sample rate.
double mean_output(const std::vector<std::int64_t>& pulses, double sample_rate_hz);

// 1-sigma of the mean of a record of length T (s) about the noise-free output, deg/s: the exact
// variance of the mean of each simulated noise process (the flicker as its Gauss-Markov sum, the
// rate random walk started at zero, the pulse counter's two ends), for a record at sample_rate_hz.
double noise_of_record_mean_deg_s(const GyroParameters& gyro, double seconds);

// Expected sample standard deviation (deg/s) of the means of n consecutive windows of tau seconds
// (GJB 2426A eq. 20): E[s²] = n/(n−1)·(V(τ) − V(nτ)) for the stationary processes (V the variance of
// a mean) plus n·K²·τ/6 for the rate random walk (Barnes' bias function B1(n, μ = 1) = n/2).
double expected_window_sd_deg_s(const GyroParameters& gyro, double tau_s, double windows);

// Covariance, (deg/s)², of the noise's means over the given intervals [start, end] (seconds since
// power-on, in any order) of one GyroModel whose noise started at t0 (the rate random walk at zero
// there, the flicker stationary): white terms on the diagonal; each flicker Gauss-Markov process
// (variance s², correlation time T) with s²·T²·(1 − e^(−L1/T))·(1 − e^(−L2/T))·e^(−gap/T)/(L1·L2)
// between disjoint intervals; the random walk with K²·(mean of min(s, u) − t0).
std::vector<std::vector<double>> interval_mean_covariance(const GyroParameters& gyro,
                                                          const std::vector<std::array<double, 2>>& intervals,
                                                          double t0);

// 1-sigma (deg/s) of the sample standard deviation s of n consecutive τ-window means (eq. 20): for
// the stationary noise Var(s²) ≈ (2/n)·Σ_k (1 − |k|/n)·(γ(k) − γ̄)² with γ the autocovariance of the
// window means (the flicker's Gauss-Markov processes and the pulse counter's shared remainder, −1/12
// pulse² between neighbours, correlate them) and γ̄ its mean over all pairs (what the record's mean
// removes), plus the random walk's part of s² taken as uncertain by its
// whole size; sd(s) = sd(s²)/(2s). For white noise this is s/√(2n), the large-n s/√(2(n − 1)).
double window_sd_sigma_deg_s(const GyroParameters& gyro, double tau_s, double windows);

// Upper bound, exceeded with probability about that of a z-sigma normal deviate, of the sample
// standard deviation of `count` independent normal errors of standard deviation sigma: the
// chi-squared quantile by the Wilson-Hilferty approximation. A sample standard deviation of
// true values plus such errors differs from that of the true values by at most this (triangle
// inequality), which bounds repeatability estimates.
double sample_sd_bound(double sigma, double count, double z = 4.0);

// Inverse of a small square matrix (Gauss-Jordan, partial pivoting); throws Error when singular.
std::vector<std::vector<double>> invert(std::vector<std::vector<double>> a);

// The tolerance of a figure that is exact but for floating-point rounding through unit
// conversions (a sign, a choice among the tested inputs): 1e-9 relative.
inline double rounding_tolerance(double value) { return 1e-9 * std::abs(value); }

// Formats a number for TOML/CSV so that it reads back exactly.
std::string exact(double value);

}  // namespace inertest::sim
