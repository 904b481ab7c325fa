// The generic plan step of a declared procedure (issue 22): the TOML keys are the spec's parameter
// names, NAME_file or NAME_output per input (exactly one), and format/column for the records.
#include "campaign/procedure_step.h"

#include <fmt/format.h>

#include "campaign/steps/record_keys.h"
#include "inertest/numerics/statistics.h"

namespace inertest::campaign {
namespace {

// "\"a\"", "\"a\" or \"b\"", "\"a\", \"b\" or \"c\"".
std::string choice_list(const std::vector<std::string>& choices) {
  std::string text;
  for (std::size_t i = 0; i < choices.size(); ++i) {
    if (i > 0) text += i + 1 == choices.size() ? " or " : ", ";
    text += "\"" + choices[i] + "\"";
  }
  return text;
}

nlohmann::json instrument_value(const PlanContext& context, const std::string& key) {
  if (key == "output_unit") return context.instrument.output_unit;
  throw Error("procedure spec: unknown instrument key '" + key + "'");
}

}  // namespace

StepAction prepare_procedure_step(const ProcedureSpec& spec, PlanTable& step, const PlanContext& context) {
  ProcedureCall call;
  for (const auto& [name, value] : spec.defaults) call.parameters[name] = value;
  for (const ParameterSpec& parameter : spec.parameters) {
    if (!parameter.instrument_default.empty()) {
      call.parameters[parameter.name] = instrument_value(context, parameter.instrument_default);
      continue;
    }
    if (parameter.type == ParameterType::number) {
      if (const auto value = step.optional_number(parameter.name)) call.parameters[parameter.name] = *value;
      continue;
    }
    const auto value = step.optional_string(parameter.name);
    if (!value) continue;
    if (!parameter.choices.empty() &&
        std::find(parameter.choices.begin(), parameter.choices.end(), *value) == parameter.choices.end()) {
      step.fail_at(parameter.name, "must be " + choice_list(parameter.choices));
    }
    call.parameters[parameter.name] = *value;
  }
  // Each input from exactly one source; records read when the step runs.
  std::map<std::string, std::string> files;
  for (const InputSpec& input : spec.inputs) {
    const auto file = step.optional_file(input.name + "_file");
    const auto value = step.optional_number(input.name + "_output");
    if (file.has_value() == value.has_value()) {
      step.fail(fmt::format("needs exactly one of '{}_file' and '{}_output'", input.name, input.name));
    }
    if (value) call.inputs[input.name] = *value;
    if (file) files[input.name] = *file;
  }
  const OutputRecordSource source = spec.inputs.empty() ? OutputRecordSource{} : read_record_keys(step, "");
  return [&spec, call, files, source](const StepRunContext&) {
    ProcedureCall run_call = call;
    for (const auto& [name, file] : files) {
      OutputRecordSource record = source;
      record.path = file;
      run_call.inputs[name] = mean(read_output_record(record));
    }
    return procedure_json(spec, spec.run(run_call));
  };
}

}  // namespace inertest::campaign
