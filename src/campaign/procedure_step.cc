// The generic plan step of a declared procedure (issue 22): the TOML keys are the spec's parameter
// names, NAME_file or NAME_output per input (exactly one), an array of files or [[procedure.run]]
// tables per runs input, and format/column for the records.
#include "campaign/procedure_step.h"

#include <cmath>

#include <fmt/format.h>

#include <set>

#include "campaign/steps/record_keys.h"
#include "inertest/numerics/statistics.h"

namespace inertest::campaign {
namespace {

// "\"a\"", "\"a\" or \"b\"", "\"a\", \"b\" or \"c\"" (text); "1, 2 or 3" (numbers, quote "").
std::string choice_list(const std::vector<std::string>& choices, const std::string& quote) {
  std::string text;
  for (std::size_t i = 0; i < choices.size(); ++i) {
    if (i > 0) text += i + 1 == choices.size() ? " or " : ", ";
    text += quote + choices[i] + quote;
  }
  return text;
}

// The [instrument] or [site] value a parameter defaults to; null when the plan does not give it.
nlohmann::json instrument_value(const PlanContext& context, const ParameterSpec& parameter) {
  const std::string& key = parameter.instrument_default;
  const auto optional = [](const std::optional<double>& value) { return value ? nlohmann::json(*value) : nlohmann::json(); };
  if (parameter.site_default && key == "latitude_deg") return optional(context.site.latitude_deg);
  if (parameter.site_default && key == "heading_deg") return context.site.heading_deg;
  if (parameter.site_default && key == "gravity_m_s2") return context.site.gravity_m_s2;
  if (key == "output_unit") return context.instrument.output_unit;
  if (key == "nominal_scale_factor") return optional(context.instrument.nominal_scale_factor);
  if (key == "sample_rate_hz") return optional(context.instrument.sample_rate_hz);
  throw Error("procedure spec: unknown instrument key '" + key + "'");
}

// The runs of a runs input: the array of files `plan_key` (numbered 1, 2, ...) or one
// [[procedure.run]] table per run (file and the number key); at least the minimum.
std::vector<RunInput> read_runs(const InputSpec& input, PlanTable& step) {
  std::vector<RunInput> runs;
  if (input.number_key.empty()) {
    // At the key: a run of the array has no table of its own (its data errors name its file).
    for (PlanTable::NamedFile& file : step.named_files(input.plan_key)) {
      runs.push_back({static_cast<double>(runs.size() + 1), std::move(file.path), std::move(file.as_written),
                      step.location_of_key(input.plan_key)});
    }
    if (runs.size() < input.minimum_runs) {
      step.fail_at(input.plan_key, fmt::format("needs at least {} runs ({})", input.minimum_runs, input.minimum_why));
    }
    return runs;
  }
  for (PlanTable& run : step.tables(input.plan_key)) {
    const double number = input.number_default ? run.number_or(input.number_key, *input.number_default)
                                               : run.number(input.number_key);
    PlanTable::NamedFile file = run.named_file("file");
    runs.push_back({number, std::move(file.path), std::move(file.as_written), run.location_of_key(input.number_key)});
    run.require_all_used();
  }
  if (runs.size() < input.minimum_runs) {
    step.fail(fmt::format("needs at least {} [[procedure.{}]] {} with file and {} ({})",
                          input.minimum_runs == 1 ? "one" : std::to_string(input.minimum_runs), input.plan_key,
                          input.minimum_runs == 1 ? "table" : "tables", input.number_key, input.minimum_why));
  }
  return runs;
}

}  // namespace

PreparedAction prepare_procedure_step(const ProcedureSpec& spec, PlanTable& step, const PlanContext& context) {
  ProcedureCall call;
  for (const auto& [name, value] : spec.defaults) call.parameters[name] = value;
  std::set<std::string> given;  // by the step itself
  for (const ParameterSpec& parameter : spec.parameters) {
    if (parameter.instrument_only) continue;
    const std::string& key = parameter.plan_name();
    if (parameter.type == ParameterType::number) {
      if (const auto value = step.optional_number(key)) {
        if (parameter.whole && !(*value >= 0.0 && *value == std::floor(*value))) step.fail_at(key, "must be a whole number");
        if (!parameter.choices.empty() && std::find(parameter.choices.begin(), parameter.choices.end(),
                                                    fmt::format("{}", *value)) == parameter.choices.end()) {
          step.fail_at(key, "must be " + choice_list(parameter.choices, ""));
        }
        call.parameters[parameter.name] = *value;
      }
    } else if (parameter.type == ParameterType::numbers) {
      if (const auto values = step.optional_numbers(key)) call.parameters[parameter.name] = *values;
    } else if (parameter.type == ParameterType::texts) {
      if (step.contains(key)) call.parameters[parameter.name] = step.strings(key);
    } else if (parameter.type == ParameterType::boolean) {
      if (step.contains(key)) call.parameters[parameter.name] = step.boolean_or(key, false);
    } else if (const auto value = step.optional_string(key)) {
      if (!parameter.choices.empty() &&
          std::find(parameter.choices.begin(), parameter.choices.end(), *value) == parameter.choices.end()) {
        step.fail_at(key, "must be " + choice_list(parameter.choices, "\""));
      }
      call.parameters[parameter.name] = *value;
    }
    if (step.contains(key)) given.insert(parameter.name);
    // An export outside the output directory would escape the staging of run_campaign: a failed
    // campaign left an earlier step's "../leak.json" (or an absolute path) behind.
    if (parameter.output_file && call.parameters.contains(parameter.name) && step.contains(key)) {
      const nlohmann::json& value = call.parameters.at(parameter.name);
      const std::string path = value.is_array() ? (value.empty() ? "" : value.back().get<std::string>())
                                                : value.get<std::string>();
      if (!path.empty() && !is_inside_output_directory(path)) {
        step.fail_at(key, "names '" + path + "', outside the output directory: in a plan an export is a relative path "
                          "beside results.json, written only when every procedure has run");
      }
      if (const auto clash = path.empty() ? std::nullopt : context.outputs.claim(path, step.location_of_key(key))) {
        step.fail_at(key, "names '" + path + "', " + *clash);
      }
    }
  }
  // Each input from exactly one source; records read when the step runs.
  std::map<std::string, std::string> files;
  bool reads_records = false;
  bool reads_timed_records = false;
  // A file or runs input in a group of alternatives is its key (or table array) when given.
  const auto is_given = [&step](const InputSpec& input) {
    return input.alternatives.empty() || input.kind == InputKind::value_or_record || step.contains(input.plan_key);
  };
  check_in_plan(step, [&] {
    check_alternatives(spec, "", is_given, [](const InputSpec& input) {
      return input.number_key.empty() ? "'" + input.plan_key + "'" : "[[procedure." + input.plan_key + "]]";
    });
  });
  for (const InputSpec& input : spec.inputs) {
    if (!is_given(input)) continue;
    reads_records = reads_records || input.records;
    reads_timed_records = reads_timed_records || input.timed;
    if (input.kind == InputKind::file) {
      call.files[input.name] = step.file(input.plan_key);
      continue;
    }
    if (input.kind == InputKind::runs) {
      call.runs[input.name] = read_runs(input, step);
      continue;
    }
    reads_records = true;
    const auto file = step.optional_file(input.name + "_file");
    const auto value = step.optional_number(input.name + "_output");
    if (file.has_value() == value.has_value()) {
      step.fail(fmt::format("needs exactly one of '{}_file' and '{}_output'", input.name, input.name));
    }
    if (value) call.inputs[input.name] = {*value, std::nullopt};
    if (file) files[input.name] = *file;
  }
  // [instrument] defaults where the step gives none (and their condition holds), then what is missing;
  // after the inputs, so that a condition may look at the step's files.
  for (const ParameterSpec& parameter : spec.parameters) {
    bool declined = false;  // the plan gives the value, which does not apply to this step
    if (!parameter.instrument_default.empty() && !given.contains(parameter.name)) {
      const auto& condition = parameter.instrument_condition;
      if (!condition || call.parameters.value(condition->first, nlohmann::json()) == condition->second) {
        const nlohmann::json value = instrument_value(context, parameter);
        declined = !value.is_null() && parameter.instrument_applies &&
                   !parameter.instrument_applies(call, context.instrument.to_json());
        if (!value.is_null() && !declined) call.parameters[parameter.name] = value;
      }
    }
    if (parameter.required && !call.parameters.contains(parameter.name)) {
      std::string where;
      if (declined) {
        where = fmt::format(" (the plan's [instrument] {} is {}'s, which does not apply to this step: give it here)",
                            parameter.instrument_default,
                            context.instrument.type == "accelerometer" ? "an accelerometer" : "a " + context.instrument.type);
      } else if (!parameter.instrument_default.empty()) {
        where = fmt::format(" (give it here or as [{}] {}", parameter.site_default ? "site" : "instrument",
                            parameter.instrument_default);
        if (parameter.instrument_condition) {
          where += " with " + parameter.instrument_condition->first + " = \"" + parameter.instrument_condition->second + "\"";
        }
        where += ")";
      }
      step.fail(fmt::format("missing '{}'{}", parameter.plan_name(), where));
    }
  }
  OutputRecordSource source = reads_records ? read_record_keys(step, "") : OutputRecordSource{};
  source.instrument_sample_rate_hz = context.instrument.sample_rate_hz;
  std::optional<double> rate;
  std::string time_column;
  if (reads_timed_records) {
    rate = step.optional_number("sample_rate_hz");
    if (rate && !(*rate > 0.0)) step.fail_at("sample_rate_hz", "must be positive");
    time_column = step.string_or("time_column", "");
    if (rate && !time_column.empty()) step.fail_at("time_column", "is not used with sample_rate_hz");
  }
  set_record_readers(call, source, minimum_samples_of(spec.inputs), rate, time_column);
  try {
    read_pulse_counts_as_rates(call, spec, is_given, rate);
    spec.check(call);
  } catch (const ParameterError& e) {
    const ParameterSpec& parameter = *spec.find_parameter(e.parameter);
    // A parameter the step has no key for is given in [site] or [instrument]: the message says so.
    if (parameter.instrument_only) {
      step.fail(fmt::format("{} (give it as [{}] {})", e.message(), parameter.site_default ? "site" : "instrument",
                            parameter.instrument_default));
    }
    step.fail_at(parameter.plan_name(), e.message());
  } catch (const Error& e) {
    if (e.location()) throw;  // already at its place, e.g. a run's (RunInput::where)
    step.fail(e.message());
  }
  const auto run = [&spec, call, files](const StepRunContext& running) {
    ProcedureCall run_call = call;
    run_call.progress = running.progress;
    run_call.output_directory = running.output_directory;
    for (const auto& [name, file] : files) {
      const MeanWithError mean = mean_with_error(call.read_record(file));
      run_call.inputs[name] = {mean.mean, mean.standard_error};
    }
    // As the command: a complaint about the data of the step's one file names that file.
    return with_call_file_context(run_call, [&] { return procedure_json(spec, spec.run(run_call).fields); });
  };
  return {run, call.parameters};
}

}  // namespace inertest::campaign
