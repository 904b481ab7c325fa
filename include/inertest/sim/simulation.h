// `inertest simulate`: runs a simulation plan (TOML) through the virtual lab and writes, into an
// output directory, the records a real test station would export for every test the plan names,
// the test plan that processes them (plan.toml, for `inertest run` / run_campaign), and truth.json
// with the true parameters and, for every figure a plan step reports, the true value and the
// statistical tolerance of its estimate.
//
// The simulator never calls a procedure: every true value comes from the instrument model itself.
//
// Simulation plan:
//   seed = 20240601                        # same seed, byte-identical files
//   [plan] title = "...", date = "YYYY-MM-DD"  # optional; the date goes into the processing plan
//   [site] name, latitude_deg, gravity_m_s2 (default: WGS 84 normal gravity)
//   [gyro] the GyroParameters keys (gyro_model.h), [gyro.drift] DI ... DOS
//   [accelerometer] id, output_unit, sample_rate_hz, scale_factor, bias_mg, misalignment_arcsec,
//                   noise_ug_rt_hz, output_resolution (accelerometer_model.h)
//   [rate_table] tilt_arcsec = [east, north], wobble_arcsec, face_arcsec = [x, y], rate_error_ppm,
//                fixture_arcsec (the misalignment fixture's vertical face, the misalignment paper's Δθy1)
//   [dividing_head] tilt_arcsec (Δθy0), fixture_arcsec (Δθy1) of the accelerometer test
//   [centrifuge] radius_m, platform_rate_error_rad_s, perpendicularity_arcsec = [x2t, y2t],
//                wobble_arcsec (platform axis), sleeve_arcsec = [x1t, y1t]
//   [[test]] kind = "...", name = "..." (optional), then the kind's keys (in the header comment of
//   src/sim/generate_*.cc), and optionally [test.limits]: the specification limits of the test's
//   step, figure = { min, max, unit } as in a processing plan's [procedure.limits]. Kinds: scale_factor, scale_factor_repeatability,
//   scale_factor_temperature, maximum_input_rate, bias, bias_repeatability, bias_temperature,
//   turn_on_time, polarity, threshold, resolution, bandwidth, input_axis_misalignment,
//   gyro_misalignment, accelerometer_misalignment, allan, centrifuge, imu_noise, imu_tumble,
//   accelerometer_tumble.
//
// truth.json "truth": one entry per figure a plan step reports, {"procedure", "quantity", "figure"
// (result key or JSON pointer), "true", "systematic" (a known effect of the rigs or the method,
// predicted from the model), "expected" (= true + systematic), "unit", "tolerance", "basis"}, and
// "tolerance_sigmas" where the tolerance is that many times the uncertainty the procedure reports.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "inertest/core/progress.h"

namespace inertest::sim {

struct SimulationOptions {
  ProgressCallback progress;
  // Overrides of the plan (`inertest simulate --seed --instrument --date`): the seed of the noise
  // (the gyro's parameters stay the plan's: another run of the same gyro; a batch of gyros is a plan
  // each, as `inertest demo --fleet` writes them), the gyro's id (held to run's rules,
  // core/instrument_id.h) and the test date (YYYY-MM-DD) written into the processing plan.
  std::optional<std::uint64_t> seed;
  std::string instrument_id;
  std::string date;
};

struct SimulationSummary {
  nlohmann::json truth;                    // what truth.json holds
  std::string plan_path;                   // the processing plan written (DIR/plan.toml)
  std::vector<std::string> written_files;  // every file written, in order
};

// Throws Error naming the plan file, line and column for any problem in the plan; writes nothing
// then. Files appear whole or not at all.
SimulationSummary simulate(const std::string& plan_path, const std::string& out_dir,
                           const SimulationOptions& options = {});

// The same on plan text already in memory; `source` names it in messages.
SimulationSummary simulate_text(std::string_view plan_text, const std::string& source, const std::string& out_dir,
                                const SimulationOptions& options = {});

}  // namespace inertest::sim
