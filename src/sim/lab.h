// What the simulation's test generators share: the instrument, the site and rigs, the seed, where
// to write, and how to record truth and plan steps. Private to src/sim.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "campaign/plan_table.h"
#include "inertest/core/progress.h"
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
};

struct Lab {
  std::string out_dir;
  std::uint64_t seed = 0;
  Site site;
  std::string site_name;
  GyroParameters gyro;
  RateTable rate_table;
  Centrifuge centrifuge;  // geometry and errors; rate and β are set per run
  ProgressCallback progress;
  // First pass over the plan: generators read and check their keys, then return before simulating.
  bool dry_run = false;

  std::vector<std::string> written_files;
  std::vector<TruthEntry> truth;
  nlohmann::json tests = nlohmann::json::array();
  std::string plan_steps;  // [[procedure]] tables in TOML

  // Writes out_dir/relative (directories created) and remembers it.
  void write(const std::string& relative, const std::string& content);
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

// Formats a number for TOML/CSV so that it reads back exactly.
std::string exact(double value);

}  // namespace inertest::sim
