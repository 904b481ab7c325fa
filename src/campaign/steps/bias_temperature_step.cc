// Plan kind "bias_temperature": GJB 2426A-2004 5.12.4, eq. (22).
//   room_temperature_degC = 20     # optional; default: the first run is the room-temperature run
//   format, column, scale_factor, input   # as for "bias"
//   [[procedure.run]]
//   temperature_degC = 20
//   file = "bias_20C.txt"
#include <fmt/format.h>

#include "campaign/steps/record_keys.h"
#include "inertest/procedures/bias.h"
#include "inertest/procedures/bias_temperature_sensitivity.h"

namespace inertest::campaign {
namespace {

struct Run {
  double temperature_degC;
  std::string file;
};

StepAction prepare(PlanTable& step, const PlanContext& context) {
  BiasTemperatureOptions temperature_options;
  temperature_options.room_temperature_degC = step.optional_number("room_temperature_degC");
  const OutputRecordSource source = read_record_keys(step, "");
  BiasOptions options;
  options.input_in_deg_h = read_input_in_deg_h(step);
  if (!options.input_in_deg_h) options.scale_factor = read_scale_factor(step, context);
  std::vector<Run> runs;
  for (auto& run : step.tables("run")) {
    runs.push_back({run.number("temperature_degC"), run.file("file")});
    run.require_all_used();
  }
  if (runs.size() < 2) step.fail("needs at least 2 [[procedure.run]] tables: room temperature and one other");
  return [runs, source, options, temperature_options](const StepRunContext&) {
    std::vector<TemperatureRunBias> biases;
    for (const auto& run : runs) {
      OutputRecordSource record = source;
      record.path = run.file;
      biases.push_back({run.temperature_degC, bias_deg_h(read_output_record(record), options)});
    }
    return bias_temperature_sensitivity(biases, temperature_options).to_json();
  };
}

const bool registered = register_step("bias_temperature", prepare);

}  // namespace
}  // namespace inertest::campaign
