// Plan kind "maximum_input_rate": GJB 2426A-2004 5.9.
//   file = "points.csv"              # test points, header rate,output, beyond the expected maximum
//   nonlinearity_limit_ppm = 100.0   # the nonlinearity requirement
//   rate_unit = "deg/s"              # optional
#include "campaign/step_registry.h"
#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/maximum_input_rate.h"

namespace inertest::campaign {
namespace {

StepAction prepare(PlanTable& step, const PlanContext& context) {
  const std::string file = step.file("file");
  MaximumInputRateOptions options;
  options.nonlinearity_limit_ppm = step.number("nonlinearity_limit_ppm");
  options.scale_factor.rate_unit = step.string_or("rate_unit", options.scale_factor.rate_unit);
  options.scale_factor.output_unit = context.instrument.output_unit;
  try {
    options.validate();
  } catch (const Error& e) {
    step.fail(e.message());
  }
  return [file, options](const StepRunContext&) {
    return maximum_input_rate(read_scale_factor_points(file), options).to_json();
  };
}

const bool registered = register_step("maximum_input_rate", prepare);

}  // namespace
}  // namespace inertest::campaign
