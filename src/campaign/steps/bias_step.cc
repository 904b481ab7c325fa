// Plan kind "bias": GJB 2426A-2004 5.12.1, 5.12.2, 5.12.5.4.1 from one record at rest.
//   file = "rest.txt"           # instrument output, one column (or `column`), or binary (`format`)
//   format = "f64"              # optional: binary record
//   column = "gyro_x"           # optional: text column by name or 1-based index
//   sample_rate_hz = 100        # optional, default [instrument] sample_rate_hz
//   scale_factor = 5000         # optional, output units per deg/s, default [instrument] nominal
//   smoothing_s = [1, 10, 100]  # optional
//   input = "output"            # optional: "output" or "deg/h" (the record holds rate already)
//   remove_earth_rate = false   # optional: subtract Earth rate along the IRA (site latitude and
//   ira_elevation_deg = 0       #   heading, IRA elevation); the standard's bias keeps it
#include "campaign/steps/record_keys.h"
#include "inertest/procedures/bias.h"

namespace inertest::campaign {
namespace {

StepAction prepare(PlanTable& step, const PlanContext& context) {
  const OutputRecordSource source = read_record_keys(step, step.file("file"));
  BiasOptions options;
  options.input_in_deg_h = read_input_in_deg_h(step);
  options.sample_rate_hz = read_sample_rate(step, context);
  if (!options.input_in_deg_h) options.scale_factor = read_scale_factor(step, context);
  options.output_unit = context.instrument.output_unit;
  options.smoothing_s = step.optional_numbers("smoothing_s").value_or(options.smoothing_s);
  options.remove_earth_rate = read_earth_rate_removal(step, context);
  check_in_plan(step, [&] { options.validate(); });
  return [source, options](const StepRunContext&) { return bias(read_output_record(source, 2), options).to_json(); };
}

const bool registered = register_step("bias", prepare);

}  // namespace
}  // namespace inertest::campaign
