// Plan kinds "turn_on_time" (GJB 2426A-2004 5.5) and "warm_up_time" (5.6, computed as 5.5.4).
//   scale_factor = 5000         # optional, output units per deg/s, default [instrument] nominal
//   zero_output = 0.0           # the calibrated zero F0, output units (default 0)
//   rate_band = 1e-3            # at rate: allowed rate error relative to the input rate
//   rest_band_deg_h = 0.5       # at rest: allowed indicated rate, deg/h
//   smoothing_s = 1             # optional averaging window from power-on, s
//   sample_rate_hz = 100        # optional: records are the output column alone; without it the
//   time_column = "t"           #   records have a time column (s since power-on, default first)
//   column, format              # the output column (default the second, or the only one)
//   remove_earth_rate = true    # optional: remove Earth rate along the IRA (site latitude, heading,
//   ira_elevation_deg = 0       #   IRA elevation)
//   [[procedure.run]]
//   file = "power_on_1.txt"
//   input_rate_deg_s = 100      # optional, 0 (at rest) by default
#include "campaign/steps/record_keys.h"
#include "inertest/procedures/turn_on_time.h"

namespace inertest::campaign {
namespace {

struct Run {
  std::string file;
  double input_rate_deg_s;
};

StepPreparer make_preparer(bool warm_up) {
  return [warm_up](PlanTable& step, const PlanContext& context) -> StepAction {
    TurnOnTimeOptions options;
    options.warm_up = warm_up;
    options.scale_factor = read_scale_factor(step, context);
    options.zero_output = step.number_or("zero_output", 0.0);
    options.rate_band = step.number_or("rate_band", 0.0);
    options.rest_band_deg_h = step.number_or("rest_band_deg_h", 0.0);
    options.smoothing_s = step.number_or("smoothing_s", 0.0);
    options.earth_rate = read_earth_rate_removal(step, context);
    const std::optional<double> sample_rate = step.optional_number("sample_rate_hz");
    if (sample_rate && !(*sample_rate > 0.0)) step.fail_at("sample_rate_hz", "must be positive");
    const std::string time_column = step.string_or("time_column", "");
    if (sample_rate && !time_column.empty()) step.fail_at("time_column", "is not used with sample_rate_hz");
    const OutputRecordSource source = read_record_keys(step, "");
    check_in_plan(step, [&] { options.validate(); });
    std::vector<Run> runs;
    for (auto& run : step.tables("run")) {
      runs.push_back({run.file("file"), run.number_or("input_rate_deg_s", 0.0)});
      const bool at_rest = runs.back().input_rate_deg_s == 0.0;
      if (at_rest && options.rest_band_deg_h <= 0.0) run.fail("a run at rest needs 'rest_band_deg_h' on the procedure");
      if (!at_rest && options.rate_band <= 0.0) run.fail("a run at rate needs 'rate_band' on the procedure");
      run.require_all_used();
    }
    if (runs.empty()) step.fail("needs at least one [[procedure.run]] table (file, input_rate_deg_s)");
    return [runs, source, sample_rate, time_column, options](const StepRunContext&) {
      std::vector<PowerOnRun> records;
      for (const auto& run : runs) {
        OutputRecordSource record_source = source;
        record_source.path = run.file;
        TimedRecord record = read_timed_record(record_source, sample_rate, time_column, 2);
        records.push_back({run.file, run.input_rate_deg_s, std::move(record.time_s), std::move(record.output)});
      }
      return turn_on_time(records, options).to_json();
    };
  };
}

const bool registered_turn_on = register_step("turn_on_time", make_preparer(false));
const bool registered_warm_up = register_step("warm_up_time", make_preparer(true));

}  // namespace
}  // namespace inertest::campaign
