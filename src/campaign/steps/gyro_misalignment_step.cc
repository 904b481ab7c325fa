// Plan kind "gyro_misalignment": misalignment separation on a rate table (the misalignment paper, core/citations.h).
//   file = "positions.csv"     # header alpha_deg,beta_deg,rate_dps,output (one row per position and direction)
//   scale_factor = -2.9222     # optional: kI in output units per deg/s; default [instrument] nominal_scale_factor
#include "campaign/step_registry.h"
#include "inertest/misalignment/gyro_misalignment.h"
#include "inertest/misalignment/misalignment_files.h"

namespace inertest::campaign {
namespace {

StepAction prepare(PlanTable& step, const PlanContext& context) {
  const std::string file = step.file("file");
  GyroMisalignmentOptions options;
  options.scale_factor = scale_factor_or_nominal(step, context, "deg/s");
  options.output_unit = context.instrument.output_unit;
  options.source = file;
  try {
    options.validate();
  } catch (const Error& e) {
    step.fail(e.message());
  }
  return [file, options](const StepRunContext&) {
    return gyro_misalignment(read_gyro_misalignment_positions(file), options).to_json();
  };
}

const bool registered = register_step("gyro_misalignment", prepare);

}  // namespace
}  // namespace inertest::campaign
