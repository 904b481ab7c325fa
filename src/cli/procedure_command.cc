// The generic command of a declared procedure (issue 22): `inertest <kind-in-kebab-case>` with one
// flag per parameter, --NAME-file/--NAME-output per input, a positional FILE... or --run NUMBER:FILE
// per runs input, --column/--format for the records, and --json; the procedure's spec
// (core/procedure_spec.h) says which.
#include "procedure_command.h"

#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/io/procedure_inputs.h"
#include "inertest/numerics/statistics.h"
#include "record_options.h"

namespace inertest::cli {
namespace {

struct InputArguments {
  std::string file;
  std::optional<double> value;
};

struct Arguments {
  std::map<std::string, std::optional<double>> numbers;     // by parameter name
  std::map<std::string, std::optional<std::string>> texts;  // by parameter name
  std::map<std::string, std::vector<double>> lists;         // by parameter name
  std::map<std::string, std::vector<std::string>> text_lists;  // by parameter name (the option repeated)
  std::map<std::string, bool> flags;                        // by parameter name (boolean or ParameterSpec::cli_flag)
  std::map<std::string, InputArguments> inputs;             // by input name
  std::map<std::string, std::string> files;                 // by input name
  std::map<std::string, std::vector<std::string>> runs;     // by input name: FILE or NUMBER:FILE each
  std::map<std::string, std::string> listings;              // by input name: the CSV listing of its runs
  OutputRecordSource source;
  std::optional<double> sample_rate_hz;  // timed records without a time column
  std::string time_column;
  bool json = false;
};

std::string help_text(const ProcedureSpec& spec) {
  std::string text = fmt::format("{} ({}): {}\nJSON:", spec.title, spec.clause, spec.doc);
  for (const FieldSpec& field : spec.fields) text += " " + field.name;
  return text;
}

std::string parameter_help(const ProcedureSpec& spec, const ParameterSpec& parameter) {
  std::string text = parameter.doc;
  if (!parameter.unit.empty()) text += ", " + parameter.unit;
  // Where a plan's key (and Python's keyword) is not the option's name in snake_case, the help names it
  // (--rate is sample_rate_hz, --rest-band rest_band_deg_h).
  std::string snake = parameter.command_line_option().substr(2);
  std::replace(snake.begin(), snake.end(), '-', '_');
  if (parameter.instrument_only) {
    text +=
        fmt::format(" [plan: [{}] {}]", parameter.site_default ? "site" : "instrument", parameter.instrument_default);
  } else if (parameter.plan_name() != snake) {
    text += " [plan: " + parameter.plan_name() + "]";
  }
  if (!parameter.needed_when.empty()) return text + " (needed for " + parameter.needed_when + ")";
  const auto found = spec.defaults.find(parameter.name);
  // An empty list or text is no default to tell (the parameter's documentation says what is taken).
  if (found != spec.defaults.end() && !found->second.empty() && found->second != "") {
    text += " (default: " + (found->second.is_string() ? found->second.get<std::string>() : found->second.dump()) + ")";
  }
  return text;
}

// The value of one input from its one source: the mean of the record file (with its standard
// error), or the value given.
InputValue input_value(const ProcedureSpec& spec, const InputSpec& input, const InputArguments& given,
                   const OutputRecordSource& base) {
  if (!given.file.empty() && given.value) {
    throw Error(fmt::format("{}: give a {} file or a {} output, not both", spec.kind, input.name, input.name));
  }
  if (given.value) return {*given.value, std::nullopt};
  if (given.file.empty()) {
    throw Error(fmt::format("{}: missing {} (--{}-file or --{}-output)", spec.kind, input.doc, kebab_case(input.name),
                            kebab_case(input.name)));
  }
  OutputRecordSource source = base;
  source.path = given.file;
  const MeanWithError mean = with_file_context(given.file, [&] { return mean_with_error(read_output_record(source)); });
  return {mean.mean, mean.standard_error};
}

// Whether a file or runs input is on the command line (a value input always is).
bool is_given(const InputSpec& input, const Arguments& arguments) {
  if (input.kind == InputKind::file) return !arguments.files.at(input.name).empty();
  if (input.kind == InputKind::runs) {
    return !arguments.runs.at(input.name).empty() || !arguments.listings.at(input.name).empty();
  }
  return true;
}

// The runs of a runs input: files numbered 1, 2, ..., NUMBER:FILE each, or the rows of its listing;
// at least the minimum.
std::vector<RunInput> runs_given(const ProcedureSpec& spec, const InputSpec& input, const Arguments& arguments) {
  std::vector<RunInput> runs;
  if (const std::string& listing = arguments.listings.at(input.name); !listing.empty()) {
    for (ListedFile& row : read_file_listing(listing, input.listing_column())) {
      runs.push_back({row.key, row.path, row.path, row.where});
    }
  }
  for (const std::string& text : arguments.runs.at(input.name)) {
    if (input.number_key.empty()) {
      runs.push_back({static_cast<double>(runs.size() + 1), text, text});
    } else {
      auto [number, file] = parse_number_and_file(text, input.cli_name, input.number_example);
      runs.push_back({number, file, file});
    }
  }
  if (runs.size() < input.minimum_runs) {
    throw Error(fmt::format("{}: needs at least {} runs ({}), got {}", spec.kind, input.minimum_runs, input.minimum_why,
                            runs.size()));
  }
  return runs;
}

// "--number" for a whole-number parameter given 2.5 or -1.
void check_whole(const ParameterSpec& parameter, double value) {
  if (parameter.whole && !(value >= 0.0 && value == std::floor(value))) {
    throw Error(fmt::format("{} must be a whole number, got {}", parameter.command_line_option(), value));
  }
}

// A list option takes its values from one word (a comma list, TMIN:TMAX), or from exactly `count`
// words (--export FORMAT FILE), each time it is given: never the positional FILE after it.
CLI::Option* list_option(CLI::Option* option, std::size_t count, char separator) {
  option->allow_extra_args(false)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  return count > 0 ? option->expected(static_cast<int>(count)) : option->expected(1)->delimiter(separator);
}

// One option of a parameter: a flag for a boolean, a list for numbers, a value otherwise.
CLI::Option* add_parameter_option(CLI::App& command, Arguments& arguments, const ProcedureSpec& spec,
                                  const ParameterSpec& parameter) {
  const std::string flag = parameter.command_line_option();
  switch (parameter.type) {
    case ParameterType::boolean: return command.add_flag(flag, arguments.flags[parameter.name], parameter.doc);
    case ParameterType::numbers:
      return list_option(command.add_option(flag, arguments.lists[parameter.name], parameter_help(spec, parameter)), 0,
                         parameter.cli_separator)
          ->type_name(parameter.cli_separator == ',' ? "X,Y,..." : fmt::format("X{}Y", parameter.cli_separator));
    case ParameterType::number:
      return command.add_option(flag, arguments.numbers[parameter.name], parameter_help(spec, parameter))
          ->type_name(parameter.whole ? "UINT" : "FLOAT");
    case ParameterType::texts:
      return list_option(command.add_option(flag, arguments.text_lists[parameter.name], parameter_help(spec, parameter)),
                         parameter.cli_values, ',');
    case ParameterType::text: break;
  }
  return command.add_option(flag, arguments.texts[parameter.name], parameter_help(spec, parameter));
}

}  // namespace

CommandAction add_procedure_command(CLI::App& root, const ProcedureSpec& spec) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command =
      root.add_subcommand(spec.command_path.empty() ? kebab_case(spec.kind) : spec.command_path.back(), help_text(spec));
  bool reads_records = false;
  bool reads_timed_records = false;
  for (const InputSpec& input : spec.inputs) {
    reads_records = reads_records || input.records;
    reads_timed_records = reads_timed_records || input.timed;
    CLI::Option* option = nullptr;
    if (input.kind == InputKind::file) {
      option = command->add_option(input.cli_name, arguments->files[input.name], input.doc)->check(CLI::ExistingFile);
    } else if (input.kind == InputKind::runs) {
      std::vector<std::string>& given = arguments->runs[input.name];
      std::string& listing = arguments->listings[input.name];
      if (!input.listing.empty()) {
        option = command->add_option(input.listing, listing, fmt::format("{}: a CSV with the header '{},file'",
                                                                         input.doc, input.listing_column()))
                     ->check(CLI::ExistingFile);
      } else if (input.number_key.empty()) {
        option = command->add_option(input.cli_name, given, input.doc)->check(CLI::ExistingFile);
      } else {
        option = command->add_option(input.cli_name, given, fmt::format("{}, once per run: NUMBER:FILE (e.g. {}), NUMBER the {}",
                                                                        input.doc, input.number_example, input.number_key));
      }
    }
    if (option) {
      if (input.alternatives.empty()) option->required();
      continue;
    }
    reads_records = true;
    InputArguments& given = arguments->inputs[input.name];
    const std::string flag = "--" + kebab_case(input.name);
    command->add_option(flag + "-file", given.file, "record of " + input.doc);
    command->add_option(flag + "-output", given.value, "mean of " + input.doc);
  }
  for (const ParameterSpec& parameter : spec.parameters) {
    if (!parameter.cli_flag.empty()) {
      command->add_flag("--" + parameter.cli_flag, arguments->flags[parameter.name],
                        // What the flag does first: "--no-compensation  compensate ..." read as its opposite.
                        fmt::format("sets {} = {}; {}: {}", parameter.name,
                                    parameter.cli_flag_value.is_string() ? parameter.cli_flag_value.get<std::string>()
                                                                         : parameter.cli_flag_value.dump(),
                                    parameter.name, parameter.doc));
      continue;
    }
    CLI::Option* option = add_parameter_option(*command, *arguments, spec, parameter);
    if (!parameter.choices.empty()) option->check(CLI::IsMember(parameter.choices));
    if (parameter.required) option->required();
  }
  if (reads_records) add_record_options(*command, arguments->source);
  if (reads_timed_records) {
    command->add_option("--rate", arguments->sample_rate_hz,
                        "sample rate, Hz (records without a time column) [plan: sample_rate_hz, else [instrument]'s "
                        "for a binary record]");
    command->add_option("--time-column", arguments->time_column, "time column by name or 1-based index");
  }
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments, &spec] {
    ProcedureCall call;
    for (const auto& [name, value] : spec.defaults) call.parameters[name] = value;
    for (const auto& [name, value] : arguments->numbers) {
      if (!value) continue;
      check_whole(*spec.find_parameter(name), *value);
      call.parameters[name] = *value;
    }
    for (const auto& [name, given] : arguments->flags) {
      const ParameterSpec& parameter = *spec.find_parameter(name);
      if (given) {
        call.parameters[name] = parameter.cli_flag.empty() ? nlohmann::json(true) : parameter.cli_flag_value;
      }
    }
    for (const auto& [name, values] : arguments->lists) {
      if (!values.empty()) call.parameters[name] = values;
    }
    for (const auto& [name, values] : arguments->text_lists) {
      if (!values.empty()) call.parameters[name] = values;
    }
    for (const auto& [name, value] : arguments->texts) {
      if (value) call.parameters[name] = *value;
    }
    check_alternatives(spec, spec.kind + ": ", [&](const InputSpec& input) { return is_given(input, *arguments); },
                       [](const InputSpec& input) { return input.listing.empty() ? input.cli_name : input.listing; });
    for (const InputSpec& input : spec.inputs) {
      if (!is_given(input, *arguments)) continue;
      if (input.kind == InputKind::runs) call.runs[input.name] = runs_given(spec, input, *arguments);
      if (input.kind == InputKind::file) call.files[input.name] = arguments->files.at(input.name);
    }
    set_record_readers(call, arguments->source, minimum_samples_of(spec.inputs), arguments->sample_rate_hz,
                       arguments->time_column);
    // An error about a parameter's value names it as given here: --input-unit, not input_unit.
    const auto naming_options = [&spec](auto&& work) {
      try {
        return work();
      } catch (const ParameterError& e) {
        throw Error(e.message_naming(spec.find_parameter(e.parameter)->command_line_option()));
      }
    };
    naming_options([&] {
      read_pulse_counts_as_rates(
          call, spec, [&](const InputSpec& input) { return is_given(input, *arguments); }, arguments->sample_rate_hz);
      spec.check(call);
    });
    // A file the procedure would write over one of its inputs: said before a record of 10^9 samples
    // is analysed, not after (ProcedureCall::output_path refuses it again when it writes).
    for (const ParameterSpec& parameter : spec.parameters) {
      if (!parameter.output_file || !call.parameters.contains(parameter.name)) continue;
      const nlohmann::json& value = call.parameters.at(parameter.name);
      const nlohmann::json& path = value.is_array() ? (value.empty() ? value : value.back()) : value;
      if (path.is_string() && !path.get<std::string>().empty()) call.output_path(path.get<std::string>());
    }
    for (const InputSpec& input : spec.inputs) {
      if (input.kind == InputKind::value_or_record) {
        call.inputs[input.name] = input_value(spec, input, arguments->inputs.at(input.name), arguments->source);
      }
    }
    // A procedure's complaint about the data of its one file names that file, and so does a figure
    // its data overflowed (procedure_json).
    call.progress = terminal_progress();
    nlohmann::json json;
    const auto run = [&] {
      return naming_options([&] {
        ProcedureOutput output = spec.run(call);
        json = procedure_json(spec, output.fields);
        return output;
      });
    };
    const ProcedureOutput output = with_call_file_context(call, run);
    print_result(json, procedure_text(spec, output), arguments->json);
    return 0;
  };
}

}  // namespace inertest::cli
