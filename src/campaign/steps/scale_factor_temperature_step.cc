// Plan kind "scale_factor_temperature": GJB 2426A-2004 5.8.5, eq. (13).
//   reference_temperature_degC = 20.0   # optional: the room-temperature run (default: the first)
//   rate_unit = "deg/s"                 # optional
//   [[procedure.run]]                   # one per temperature
//   temperature_degC = 20.0
//   file = "sf_20C.csv"                 # test points, header rate,output
#include <algorithm>

#include "campaign/step_registry.h"
#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/scale_factor_temperature_sensitivity.h"

namespace inertest::campaign {
namespace {

struct Run {
  double temperature_degC;
  std::string file;
};

StepAction prepare(PlanTable& step, const PlanContext& context) {
  ScaleFactorTemperatureOptions options;
  options.reference_temperature_degC = step.optional_number("reference_temperature_degC");
  options.scale_factor.rate_unit = step.string_or("rate_unit", options.scale_factor.rate_unit);
  options.scale_factor.output_unit = context.instrument.output_unit;
  std::vector<Run> runs;
  for (auto& run : step.tables("run")) {
    runs.push_back({run.number("temperature_degC"), run.file("file")});
    run.require_all_used();
  }
  if (runs.size() < 2) {
    step.fail("needs at least two [[procedure.run]] tables (room temperature and a test temperature)");
  }
  if (options.reference_temperature_degC &&
      std::none_of(runs.begin(), runs.end(),
                   [&](const Run& r) { return r.temperature_degC == *options.reference_temperature_degC; })) {
    step.fail_at("reference_temperature_degC", "matches no run's temperature_degC");
  }
  try {
    options.validate();
  } catch (const Error& e) {
    step.fail(e.message());
  }
  return [runs, options](const StepRunContext&) {
    std::vector<TemperatureRun> data;
    for (const auto& run : runs) data.push_back({run.temperature_degC, read_scale_factor_points(run.file)});
    return scale_factor_temperature_sensitivity(data, options).to_json();
  };
}

const bool registered = register_step("scale_factor_temperature", prepare);

}  // namespace
}  // namespace inertest::campaign
