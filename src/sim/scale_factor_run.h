// One scale-factor test run (GJB 2426A-2004 5.8.1.3) in the virtual lab, shared by the scale-factor,
// temperature, repeatability and maximum-input-rate generators: static run, each rate +Ω, each −Ω,
// static run, IA up along the rate-table axis; the mean output of every point, and the truth from
// the noise-free instrument at the gyro's temperature while each point was recorded. Private to src/sim.
#pragma once

#include <string>
#include <vector>

#include "sim/lab.h"

namespace inertest::sim {

struct ScaleFactorTruth {
  double scale_factor = 0.0;  // K of eqs. (2)-(6) on the noise-free outputs, output unit per deg/s
  double nonlinearity = 0.0;  // Kn, relative (eqs. 7-9)
  double asymmetry = 0.0;     // Ka, relative (eqs. 10-11)
  double largest_output = 0.0;      // the largest |F − F0| of the run
};

struct ScaleFactorRun {
  std::vector<double> rates;    // deg/s, in test order (0 first and last)
  std::vector<double> outputs;  // measured means
  // The instrument's own figures: the noise-free outputs at exactly the commanded rate about IA,
  // the vertical Earth rate, g along IA, at the gyro's temperature during each point.
  ScaleFactorTruth truth;
  // What the noise-free run on the real rig gives (table rate error, tilt, wobble, face errors).
  ScaleFactorTruth expected;
  double sigma_point = 0.0;     // 1-sigma noise of one point's mean, output unit
  // 1-sigma of K and of the asymmetry (relative) from the full covariance of the points' noise
  // (interval_mean_covariance: the flicker and random walk correlate the points of a run).
  double sigma_scale_factor = 0.0;
  double sigma_asymmetry = 0.0;
  std::string points_csv;       // rate,output
};

// The rates of a run: 0, +each magnitude, −each magnitude, 0.
std::vector<double> scale_factor_rates(const std::vector<double>& magnitudes);

// Eqs. (2)-(11) on (rate, output) pairs, written out here so the truth does not depend on the
// library's fit; zero rates are the static runs (their mean is the rest output).
ScaleFactorTruth scale_factor_truth(const std::vector<double>& rates, const std::vector<double>& outputs);

// Records one run on the rate table with `model`, which must be fresh (its noise starts with the run),
// 1 s of settling before each point. raw_prefix non-empty: each point's record is also written as <raw_prefix>NN.csv.
ScaleFactorRun record_scale_factor_run(Lab& lab, GyroModel& model, const std::vector<double>& magnitudes,
                                       double seconds, double static_seconds, const TemperatureProfile& temperature,
                                       const std::string& title, const std::string& raw_prefix = "");

}  // namespace inertest::sim
