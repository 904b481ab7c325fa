// Plan kind "scale_factor_repeatability": GJB 2426A-2004 5.8.4, eq. (12).
//   files = ["run1.csv", ..., "run6.csv"]  # one table of test points (rate,output) per run
//   minimum_runs = 6                       # optional; 5.8.4.3 asks for Q >= 6
//   rate_unit = "deg/s"                    # optional
#include "campaign/step_registry.h"
#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/scale_factor_repeatability.h"

namespace inertest::campaign {
namespace {

StepAction prepare(PlanTable& step, const PlanContext& context) {
  const std::vector<std::string> files = step.files("files");
  ScaleFactorRepeatabilityOptions options;
  const double minimum_runs = step.number_or("minimum_runs", static_cast<double>(options.minimum_runs));
  if (minimum_runs < 2 || minimum_runs != static_cast<double>(static_cast<std::size_t>(minimum_runs))) {
    step.fail_at("minimum_runs", "must be a whole number >= 2");
  }
  options.minimum_runs = static_cast<std::size_t>(minimum_runs);
  options.scale_factor.rate_unit = step.string_or("rate_unit", options.scale_factor.rate_unit);
  options.scale_factor.output_unit = context.instrument.output_unit;
  try {
    options.validate();
  } catch (const Error& e) {
    step.fail(e.message());
  }
  if (files.size() < options.minimum_runs) {
    step.fail_at("files", "names " + std::to_string(files.size()) + " run(s); GJB 2426A 5.8.4.3 asks for Q >= " +
                              std::to_string(options.minimum_runs));
  }
  return [files, options](const StepRunContext&) {
    std::vector<std::vector<ScaleFactorPoint>> runs;
    for (const auto& file : files) runs.push_back(read_scale_factor_points(file));
    return scale_factor_repeatability(runs, options).to_json();
  };
}

const bool registered = register_step("scale_factor_repeatability", prepare);

}  // namespace
}  // namespace inertest::campaign
