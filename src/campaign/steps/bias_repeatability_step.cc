// Plan kind "bias_repeatability": GJB 2426A-2004 5.12.3, eq. (21), over Q runs.
//   files = ["run1.txt", "run2.txt", ...]  # one output record per run (Q >= 6 asked for)
//   format, column, scale_factor, input    # as for "bias"
#include "campaign/steps/record_keys.h"
#include "inertest/procedures/bias.h"
#include "inertest/procedures/bias_repeatability.h"

namespace inertest::campaign {
namespace {

StepAction prepare(PlanTable& step, const PlanContext& context) {
  const std::vector<std::string> files = step.files("files");
  if (files.size() < 2) step.fail_at("files", "needs at least 2 runs (GJB 2426A 5.12.3 asks for 6 or more)");
  const OutputRecordSource source = read_record_keys(step, "");
  BiasOptions options;
  options.input_in_deg_h = read_input_in_deg_h(step);
  if (!options.input_in_deg_h) options.scale_factor = read_scale_factor(step, context);
  return [files, source, options](const StepRunContext&) {
    std::vector<double> biases;
    for (const auto& file : files) {
      OutputRecordSource run = source;
      run.path = file;
      biases.push_back(bias_deg_h(read_output_record(run), options));
    }
    return bias_repeatability(biases).to_json();
  };
}

const bool registered = register_step("bias_repeatability", prepare);

}  // namespace
}  // namespace inertest::campaign
