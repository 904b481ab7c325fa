// Plan kind "accelerometer_misalignment": multi-position gravity test (the misalignment paper, core/citations.h).
//   file = "positions.csv"     # header beta_deg,output and optionally run
//   scale_factor = 1.299       # optional: kI in output units per g; default [instrument] nominal_scale_factor
#include "campaign/step_registry.h"
#include "inertest/misalignment/accelerometer_misalignment.h"
#include "inertest/misalignment/misalignment_files.h"

namespace inertest::campaign {
namespace {

StepAction prepare(PlanTable& step, const PlanContext& context) {
  const std::string file = step.file("file");
  AccelerometerMisalignmentOptions options;
  options.scale_factor = scale_factor_or_nominal(step, context, "g");
  options.output_unit = context.instrument.output_unit;
  options.source = file;
  try {
    options.validate();
  } catch (const Error& e) {
    step.fail(e.message());
  }
  return [file, options](const StepRunContext&) {
    return accelerometer_misalignment(read_accelerometer_misalignment_positions(file), options).to_json();
  };
}

const bool registered = register_step("accelerometer_misalignment", prepare);

}  // namespace
}  // namespace inertest::campaign
