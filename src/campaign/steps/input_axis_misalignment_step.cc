// Plan kind "input_axis_misalignment": GJB 2426A-2004 5.15, eqs. (47)-(50).
//   file = "positions.csv"    # header position,output_positive,output_negative (2 or 4 positions)
//   rate = 100.0              # table rate magnitude, rate_unit
//   scale_factor = 5000.0     # K, output per rate unit; default: [instrument] nominal_scale_factor
//   rate_unit = "deg/s"       # optional (the nominal scale factor is per deg/s)
#include "campaign/step_registry.h"
#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/input_axis_misalignment.h"

namespace inertest::campaign {
namespace {

StepAction prepare(PlanTable& step, const PlanContext& context) {
  const std::string file = step.file("file");
  InputAxisMisalignmentOptions options;
  options.rate = step.number("rate");
  options.rate_unit = step.string_or("rate_unit", options.rate_unit);
  const auto scale_factor = step.optional_number("scale_factor");
  if (!scale_factor && !(context.instrument.nominal_scale_factor && options.rate_unit == "deg/s")) {
    step.fail("needs 'scale_factor' (output per rate unit), or [instrument] nominal_scale_factor with rate_unit deg/s");
  }
  options.scale_factor = scale_factor ? *scale_factor : *context.instrument.nominal_scale_factor;
  options.output_unit = context.instrument.output_unit;
  try {
    options.validate();
  } catch (const Error& e) {
    step.fail(e.message());
  }
  return [file, options](const StepRunContext&) {
    return input_axis_misalignment(read_misalignment_positions(file), options).to_json();
  };
}

const bool registered = register_step("input_axis_misalignment", prepare);

}  // namespace
}  // namespace inertest::campaign
