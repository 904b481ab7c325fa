// One description per procedure (issue 22): a procedure declares its parameters, inputs and result
// fields once, in its own source file (src/procedures/<kind>_spec.cc), and generic code makes the
// CLI command (`inertest <kind-in-kebab-case>`), the plan step (kind = "<kind>"), the JSON object
// and the text report from it.
//
// Names are one set: a parameter `nonlinearity_limit` is the plan key `nonlinearity_limit`, the
// flag `--nonlinearity-limit` and (later) the Python keyword `nonlinearity_limit`. An input
// `positive` read from exactly one source is `--positive-file`/`--positive-output` on the command
// line and `positive_file`/`positive_output` in a plan.
//
// Registration is guaranteed by the build, not by static initialisation: CMake lists every
// src/procedures/<kind>_spec.cc, each defines `ProcedureSpec inertest::<kind>_spec()`, and the
// generated procedure_spec_list.cc calls them all (procedure_specs() below).
#pragma once

#include <algorithm>
#include <any>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/figure.h"
#include "inertest/core/progress.h"

namespace inertest {

struct TimedRecord;  // io/output_record.h

// "nonlinearity_limit" -> "nonlinearity-limit".
std::string kebab_case(const std::string& name);

// Whether a path names a file inside a directory it is taken relative to: relative, not climbing out
// of it ("../leak.json", "a/../../b"), not the directory itself.
bool is_inside_output_directory(const std::string& path);

// number: a double or (whole) a std::size_t member; text: std::string; numbers: std::vector<double>
// (a comma-separated list on the command line, an array in a plan); boolean: bool (a flag without a
// value on the command line, true/false in a plan); texts: std::vector<std::string> (the option
// repeated on the command line, `--temperature-column coil --temperature-column case`; an array of
// strings in a plan; a list of str in Python).
enum class ParameterType { number, text, numbers, boolean, texts };

// An Error about the value of one parameter (`parameter`, its name), thrown by a check: a plan
// places it at the parameter's key.
class ParameterError : public Error {
 public:
  ParameterError(std::string parameter_name, const std::string& message)
      : Error(message), parameter(std::move(parameter_name)) {}
  // The message with the parameter as its caller names it (a flag "--table-rate", a Python keyword):
  // "--interval must be positive" for "interval_s must be positive", else "--table-rate: <message>".
  std::string message_naming(const std::string& given_as) const {
    const std::string& text = message();
    if (text.starts_with(parameter + " ")) return given_as + text.substr(parameter.size());
    return given_as + ": " + text;
  }
  std::string parameter;
};

// Runs a check of the parameter `name`'s value: an Error without a place from it becomes a
// ParameterError (a plan places it at the parameter's key).
template <typename Check>
void check_parameter(const std::string& name, const Check& check) {
  try {
    check();
  } catch (const ParameterError&) {
    throw;
  } catch (const Error& e) {
    if (e.location()) throw;
    throw ParameterError(name, e.message());
  }
}

// Runs work on one input file: an Error without a place gets the file as its place, so that a
// complaint about the data ("too short for two windows") names the file it came from. A
// ParameterError is about a parameter, not the file: it passes as it is.
template <typename Work>
auto with_file_context(const std::string& file, Work&& work) {
  try {
    return work();
  } catch (const ParameterError&) {
    throw;
  } catch (const Error& e) {
    if (e.location()) throw;
    throw Error(SourceLocation{file, 0, 0}, e.message());
  }
}

struct ProcedureCall;

// A parameter of the procedure's Options: ParameterSpec("rate_unit", "unit of the rates") and the
// setters below, e.g. .unit_is("deg/s").required_on_command_line().
struct ParameterSpec {
  ParameterSpec(std::string parameter_name, std::string documentation)
      : name(std::move(parameter_name)), doc(std::move(documentation)) {}
  ParameterSpec& unit_is(std::string value) { unit = std::move(value); return *this; }
  // A text parameter that takes one of `values`.
  ParameterSpec& one_of(std::vector<std::string> values) {
    type = ParameterType::text;
    choices = std::move(values);
    return *this;
  }
  ParameterSpec& required_on_command_line() { required = true; return *this; }
  // A file the procedure writes (an export; of a list of texts, the last): in a plan it must be a
  // relative path inside the output directory, checked before anything runs (the exports are
  // staged and moved beside results.json only when every step has run).
  ParameterSpec& writes_file() { output_file = true; return *this; }
  // A yes/no parameter stored through a binder (a bool member is one already).
  ParameterSpec& boolean() { type = ParameterType::boolean; return *this; }
  // A text parameter stored through a binder (a std::string member is one already).
  ParameterSpec& text() { type = ParameterType::text; return *this; }
  // Plans default to the [instrument] key; with only = true they have no key of their own for it.
  ParameterSpec& instrument_gives(std::string key, bool only = false) {
    instrument_default = std::move(key);
    instrument_only = only;
    return *this;
  }
  // As instrument_gives, from the plan's [site] ("latitude_deg", "heading_deg").
  ParameterSpec& site_gives(std::string key, bool only = false) {
    site_default = true;
    return instrument_gives(std::move(key), only);
  }
  // The [instrument] default applies only while the parameter `name` has `value` (e.g. the nominal
  // scale factor only for records of the output, input = "output", not for records in deg/h).
  ParameterSpec& instrument_gives_when(std::string parameter, std::string value) {
    instrument_condition = {std::move(parameter), std::move(value)};
    return *this;
  }
  // The [instrument] default applies only where `applies` holds, given the step's call so far (its
  // input files, the parameters it gives and the defaults of those declared before) and the plan's
  // [instrument] (Instrument::to_json: id, type, output_unit, nominal_scale_factor, sample_rate_hz).
  ParameterSpec& instrument_gives_if(
      std::function<bool(const ProcedureCall& call, const nlohmann::json& instrument)> applies) {
    instrument_applies = std::move(applies);
    return *this;
  }
  // The plan key (and Python keyword) when it is a contract that differs from the name (e.g.
  // "nonlinearity_limit_ppm").
  ParameterSpec& plan_key_is(std::string key) { plan_key = std::move(key); return *this; }
  // The command-line option when it is a contract that differs from --kebab-case(name) (e.g. "rate"
  // for sample_rate_hz: --rate).
  ParameterSpec& command_line_name_is(std::string option) { cli_option = std::move(option); return *this; }
  // A parameter whose default (0) stands for "not given", which `when` needs (e.g. "runs at rate"):
  // the help says "needed for runs at rate" where it would show the default.
  ParameterSpec& needed_for(std::string when) { needed_when = std::move(when); return *this; }
  // On the command line a flag without a value, `--flag`, that gives `value` (e.g. --input-deg-h for
  // input = "deg/h", --no-compensation for compensation = false: contracts); without it the
  // parameter has its default.
  ParameterSpec& command_line_flag(std::string flag, nlohmann::json value) {
    cli_flag = std::move(flag);
    cli_flag_value = std::move(value);
    return *this;
  }
  // A texts parameter whose option takes `count` values at once on the command line (`--export
  // FORMAT FILE`, a contract) instead of a comma list; an array of them in a plan.
  ParameterSpec& values_on_command_line(std::size_t count) { cli_values = count; return *this; }
  // A list of numbers stored through a binder (a std::vector<double> member is one already), its
  // values separated by `separator` on the command line (`--fit-range TMIN:TMAX`, a contract).
  ParameterSpec& numbers(char separator = ',') {
    type = ParameterType::numbers;
    cli_separator = separator;
    return *this;
  }
  const std::string& plan_name() const { return plan_key.empty() ? name : plan_key; }
  // "--rate", "--nonlinearity-limit".
  std::string command_line_option() const { return "--" + (cli_option.empty() ? kebab_case(name) : cli_option); }

  std::string name;  // snake_case: the plan key and the Python keyword (unless plan_key_is); the flag is --kebab-case
  ParameterType type = ParameterType::number;
  std::string unit;  // the unit of a number, "" when dimensionless or text
  std::string doc;
  std::vector<std::string> choices;  // the accepted values of a text parameter, empty when free
  bool required = false;             // no default: the command line must give it
  std::string needed_when;           // needed_for(): what needs it, "" for none
  // In a plan, the [instrument] key ("output_unit", "nominal_scale_factor", "sample_rate_hz") that gives the value
  // when the step does not; with `instrument_only` the step has no key for it at all.
  std::string instrument_default;
  bool instrument_only = false;
  bool site_default = false;  // instrument_default is a key of [site]
  std::optional<std::pair<std::string, std::string>> instrument_condition;  // parameter, value
  std::function<bool(const ProcedureCall&, const nlohmann::json&)> instrument_applies;  // empty: always
  std::string plan_key;  // "" : the plan key is `name`
  bool whole = false;    // a number that must be a whole number >= 0 (a count, e.g. minimum_runs)
  std::string cli_flag;  // "": the command line has --kebab-case(name) VALUE
  nlohmann::json cli_flag_value;
  std::string cli_option;  // "": the option is --kebab-case(name)
  std::size_t cli_values = 0;  // texts: the values one option takes, 0: a comma list or the option repeated
  char cli_separator = ',';     // numbers: between the values on the command line
  bool output_file = false;     // writes_file()
};

enum class InputKind {
  // A value from exactly one source: the mean of a record file (--NAME-file / NAME_file, read
  // with --column/--format) or the value itself (--NAME-output / NAME_output).
  value_or_record,
  // A file the procedure's reader reads (call.files): the positional argument `cli_name` (or the
  // option, when it starts with "--") on the command line, the key `plan_key` in a plan (a path
  // relative to the plan, checked to exist).
  file,
  // Several runs, each a file (call.runs): repeated runs numbered 1, 2, ... in the order given, or
  // runs each with a number of its own (a temperature, an input rate). See InputSpec::runs_in_files
  // and InputSpec::numbered_runs.
  runs,
};

// InputSpec("positive", "the output at the positive rate"), or a file with .read_from_file(...).
struct InputSpec {
  InputSpec(std::string input_name, std::string documentation)
      : name(std::move(input_name)), doc(std::move(documentation)) {}
  InputSpec& read_from_file(std::string positional_name, std::string key) {
    kind = InputKind::file;
    cli_name = std::move(positional_name);
    plan_key = std::move(key);
    return *this;
  }
  // Repeated runs, one file each, numbered 1, 2, ... in the order given: the positional arguments
  // `positional_name`... on the command line, the array of paths `key` in a plan.
  InputSpec& runs_in_files(std::string positional_name, std::string key) {
    kind = InputKind::runs;
    cli_name = std::move(positional_name);
    plan_key = std::move(key);
    return *this;
  }
  // Runs each with a number (`key`, e.g. "temperature_degC") and a file: `--run NUMBER:FILE` once per
  // run on the command line (`example` shows one, e.g. "25:run_25C.txt"), one [[procedure.run]]
  // table per run in a plan with the keys `file` and `key`.
  InputSpec& numbered_runs(std::string key, std::string example) {
    kind = InputKind::runs;
    cli_name = "--run";
    plan_key = "run";
    number_key = std::move(key);
    number_example = std::move(example);
    return *this;
  }
  // On the command line the numbered runs are one CSV listing, `name` (a positional argument such
  // as "RUNS" or an option such as "--records"), with the header `<number key>,file`, one row per
  // run, paths relative to the listing; instead of --run NUMBER:FILE. Plans keep [[procedure.run]].
  // `number_column`: the listing's header for the number when it is a contract that differs from
  // the number key (bandwidth: "freq_hz" for frequency_hz).
  InputSpec& listed_on_command_line(std::string listing_name, std::string number_column = "") {
    listing = std::move(listing_name);
    listing_number_column = std::move(number_column);
    return *this;
  }
  // The listing's header for the number: listing_number_column, or the number key.
  const std::string& listing_column() const { return listing_number_column.empty() ? number_key : listing_number_column; }
  // Inputs with the same `group` are alternatives: exactly one of them is given (e.g. a table of
  // test points, one long record, or a record per point). Their message names them in order.
  InputSpec& alternative_in(std::string group) { alternatives = std::move(group); return *this; }
  // A [[procedure.run]] table without the number key has this number (e.g. 0: a run at rest).
  InputSpec& number_defaults_to(double value) { number_default = value; return *this; }
  // The file (file) or each run's file (runs) is an instrument-output record (call.read_record): read
  // with --column/--format on the command line and the keys column/format in a plan.
  InputSpec& output_records() {
    records = true;
    raw_samples = true;
    return *this;
  }
  // The file (file) or each run's file (runs) may hold the instrument's raw samples, which the
  // procedure reads itself (a scale factor's long record, angular-vibration records; threshold's
  // file with method 3). With an output unit that counts pulses per sample interval, the call's
  // pulse_counts is then set and the procedure multiplies the outputs by their sample rate. A file
  // or runs input without raw samples is a table of mean outputs, taken per second
  // (io/output_record.h read_pulse_counts_as_rates).
  InputSpec& holds_raw_samples() { raw_samples = true; return *this; }
  // Output records with the time of each sample (call.read_timed_record): a time column (--time-column,
  // time_column; default the first) beside the output column, or the output column alone sampled at
  // --rate HZ (sample_rate_hz), sample i (from 0) at (i + 1)/HZ. Also output_records().
  InputSpec& timed_records() {
    timed = true;
    return output_records();
  }
  // A record (output_records, timed_records) of fewer samples is an error of its reader, naming the file.
  InputSpec& samples_at_least(std::size_t count) { minimum_samples = count; return *this; }
  // Fewer runs than `count` is an error given before any file is read; `why` says where the count
  // comes from (e.g. "GJB 2426A 5.12.3 asks for 6 or more").
  InputSpec& at_least(std::size_t count, std::string why) {
    minimum_runs = count;
    minimum_why = std::move(why);
    return *this;
  }

  std::string name;
  std::string doc;  // what the record, value or file is, e.g. "the output at the positive rate"
  InputKind kind = InputKind::value_or_record;
  std::string cli_name;  // file, runs: the positional argument ("STEPS", "FILE") or the option "--run"
  std::string plan_key;  // file, runs: the plan key ("file", "files") or the table array "run"
  // InputKind::runs with numbers: the number's plan key, an example of --run, and its default.
  std::string number_key;
  std::string number_example;
  std::optional<double> number_default;
  std::string listing;  // InputKind::runs with numbers: the command line's CSV listing, "" for --run
  std::string listing_number_column;  // the listing's number header, "" : number_key
  std::string alternatives;  // "" : always given; else the group of alternatives it belongs to
  bool records = false;  // file, runs: the files are output records, read by call.read_record
  bool timed = false;    // file, runs: the records are timed, read by call.read_timed_record
  bool raw_samples = false;  // file, runs: the instrument's raw samples (holds_raw_samples, output_records)
  std::size_t minimum_runs = 1;
  std::string minimum_why;
  std::size_t minimum_samples = 1;  // output and timed records
};

// The largest minimum_samples of a spec's inputs: what its readers ask of every record.
inline std::size_t minimum_samples_of(const std::vector<InputSpec>& inputs) {
  std::size_t count = 1;
  for (const InputSpec& input : inputs) count = std::max(count, input.minimum_samples);
  return count;
}

// What a result field is in a report.
enum class FieldRole {
  headline,  // a figure the procedure exists for (tables, limits)
  detail,    // a supporting figure or value
  table,     // rows (e.g. every test point): in the JSON and the report's tables, not in the text
  curve,     // points drawn as a plot in the report (FieldSpec::axes); in the text as their count
  hidden,    // in the JSON only
};

// What a field's JSON value is: the Python stubs' type of the member, and what a plan's limit may
// name (a figure or a number).
enum class FieldValue {
  figure,        // {"value", "unit"[, "uncertainty"]} (core/figure.h)
  number,
  whole_number,
  boolean,
  text,
  texts,         // an array of strings (warnings)
  rows,          // an array of objects (a table's rows, a curve's points)
  structured,    // anything else: an object, a number or null
};

// One key of the result's JSON object.
struct FieldSpec {
  std::string name;  // the JSON key (a contract: README, docs, closed issues)
  FieldRole role = FieldRole::detail;
  std::string label_en;
  std::string label_zh;  // GJB 2426A terms
  std::string equation;  // the source clause or equation, "" when the field is bookkeeping
  // FieldRole::curve: the members of each point that the report plots, the abscissa first, then the
  // ordinates (e.g. {"rate", "deviation"}); none when the kind's plot builder draws it (bias's
  // smoothed records).
  std::vector<std::string> axes = {};
  // The text report's words for some values, by the value's JSON text (e.g. {{"-1", "negative"}} for a
  // sign); other values read as they are.
  std::map<std::string, std::string> value_words = {};
  // Set by ProcedureDefinition::field from the member's type; by field_from, rows for a table or a
  // curve and structured otherwise unless declared.
  FieldValue value = FieldValue::structured;
  // The members of a structured field that are array figures ({"value": [x, y, z] or a 3x3, "unit",
  // "uncertainty"}), each with its rank (1 a vector, 2 a matrix; a triad's "bias", "misalignment"): a
  // plan's limit names one element ("/accelerometer/bias/value/0"), a limit on a whole one is an error.
  std::map<std::string, int> array_figures = {};
  // The unit the figure (or every figure of its rows) is reported in: fixed ("ppm", "degC"), or made
  // of the parameters' values ("{output_unit}/({rate_unit})", a parameter's name in braces); empty
  // when the parameters do not say it (a unit the record stores). A plan's limit in a unit that does
  // not convert to it is an error before anything runs (declared_unit).
  std::string unit = {};
  // A yes/no the procedure judges its own specification with (polarity's pass, given the expected
  // polarity): in a plan, a verdict of the step (FAIL when false), none when the result leaves it null.
  bool states_verdict = false;
  // A table with one row per element of this list parameter, in its order (bias stability, one row
  // per smoothing time: "smoothing_s"): a plan's limit on a row beyond them ("/bias_stability/5" of
  // three) is an error before anything runs. Empty: the rows follow the data.
  std::string one_row_per = {};

  FieldSpec&& rows_follow(std::string parameter) && {
    one_row_per = std::move(parameter);
    return std::move(*this);
  }
};

// One run of an InputKind::runs input: its number (the temperature, the input rate; its place
// 1, 2, ... when the runs have no numbers of their own), its file, its name: the file as the plan
// or the command line wrote it, which a result may show (a plan's file is read resolved against the
// plan's directory, but named as written, so that the same plan run from another directory gives
// the same results, and the archive one campaign), and where it was given (the plan's
// [[procedure.run]] table, at its number key when it has one, or the listing's row; empty when
// neither), for the procedure's errors about the run.
struct RunInput {
  double number = 0.0;
  std::string file;
  std::string name;
  SourceLocation where = {};
};

// Parameter values by name (defaults already applied), input values, input files and runs by name.
// files and runs are set before the check and hold only the inputs given (an alternative not given
// is absent).
// A value input: the value given, or the mean of a record with its standard error (the samples'
// standard deviation over sqrt(n): a lower bound when they are correlated; none for one sample).
struct InputValue {
  double value = 0.0;
  std::optional<double> standard_error;
};

struct ProcedureCall {
  nlohmann::json parameters = nlohmann::json::object();
  std::map<std::string, InputValue> inputs;
  std::map<std::string, std::string> files;
  std::map<std::string, std::vector<RunInput>> runs;
  // An instrument-output record as the command line (--column/--format) or the plan (column/format)
  // says it is stored; set when a runs input has output_records(). Errors name the file.
  std::function<std::vector<double>(const std::string& file)> read_record;
  // A timed record as the command line (--rate/--time-column) or the plan (sample_rate_hz/time_column)
  // says it is stored; set when an input has timed_records(). Errors name the file.
  std::function<TimedRecord(const std::string& file)> read_timed_record;
  // The rate of a record sampled at `given` Hz, checked against the rate the file stores (a record of
  // named channels, a text record's time column): a contradiction is an Error naming both; `given`
  // 0 (none given): the stored rate, or a ParameterError on sample_rate_hz when the file stores
  // none. Set with read_record.
  std::function<double(const std::string& file, double given)> record_sample_rate;
  // The unit of a record's samples, `given` checked against the unit the file stores (a record of
  // named channels): a contradiction is an Error naming both. Set with read_record.
  std::function<std::optional<std::string>(const std::string& file, const std::optional<std::string>& given)>
      record_unit;
  // The instrument's raw samples count pulses per sample interval: the call's output_unit was pulse
  // and is now pulse/s (io/output_record.h read_pulse_counts_as_rates). read_record and
  // read_timed_record return pulse/s already; a procedure that reads its records itself multiplies
  // their outputs by their sample rate.
  bool pulse_counts = false;
  // Progress of a long computation (a terminal's on the command line, the campaign's in a plan).
  ProgressCallback progress;
  // Where a plan's exports go (the campaign's staging directory, moved beside its results.json once
  // every step has run); empty on the command line.
  std::string output_directory;

  // A file the procedure writes (an export): a relative path is in output_directory (its directories
  // made there), so that a plan's exports land beside its results.json; on the command line, in the
  // working directory. With an output_directory, a path outside it (absolute, or climbing out with
  // "..") is an Error: it would escape the staging that keeps a failed campaign from leaving output.
  // On the command line, an export onto one of the call's input files (by any path to it) is an
  // Error: a mistyped --export replaced the record it was made from. (A campaign checks its exports
  // against every data file of the plan before it runs.)
  std::string output_path(const std::string& path) const;
};

// Runs work on the call with its one input file, if it has one, as the place of an Error that has
// none (with_file_context): how the command and the plan step both run a declared procedure.
template <typename Work>
auto with_call_file_context(const ProcedureCall& call, Work&& work) {
  return call.files.size() == 1 ? with_file_context(call.files.begin()->second, work) : work();
}

// What a procedure's run gives: the result's fields by name (procedure_json writes them) and, for
// a result that writes a text of its own (ProcedureDefinition::written_by), that text; empty: the
// generic text of the fields (procedure_text).
struct ProcedureOutput {
  nlohmann::json fields;
  std::string text;
};

// The whole description of one procedure. Built with ProcedureDefinition below.
struct ProcedureSpec {
  std::string kind;    // snake_case plan kind; the CLI command is its kebab-case form (or command_path)
  // The CLI command when it is a contract that differs from the kind's: a subcommand of a group,
  // e.g. {"misalignment", "gyro"} for `inertest misalignment gyro`; empty: {kebab_case(kind)}.
  std::vector<std::string> command_path;
  std::string command_group_doc;  // the group's --help, "" when another spec of the group gives it
  std::string json_procedure;  // the JSON's "procedure": the kind, or a contract that differs from it
  std::string title;   // e.g. "Polarity"
  std::string clause;  // e.g. "GJB 2426A-2004 5.7"
  std::string doc;     // the method in a few lines, for --help
  std::string title_zh;  // the title in GJB 2426A's Chinese terms, for the report
  // The method in one paragraph, for the report, in English and Chinese ("" when doc says enough).
  std::string method_en;
  std::string method_zh;
  std::vector<ParameterSpec> parameters;
  std::map<std::string, nlohmann::json> defaults;  // by parameter name; absent: optional, no default
  std::vector<InputSpec> inputs;
  std::vector<FieldSpec> fields;
  // A worked example: the command line's arguments after the command, paths relative to the source
  // tree (e.g. {"examples/power_consumption/supplies.csv"}). Its `--json` output is a golden file
  // (tests/golden/<kind>_example.json) and its result is reported when the golden campaign lacks
  // the kind, so that a procedure can be added without touching a shared file.
  std::vector<std::string> example;
  // Checks the parameters (Options::validate) and the runs given before any input is read; throws Error.
  std::function<void(const ProcedureCall&)> check;
  // Runs the procedure.
  std::function<ProcedureOutput(const ProcedureCall&)> run;
  // The Result writes its JSON object itself (ProcedureDefinition::written_by): its nulls are kept.
  bool writes_own_json = false;
  // The fields of a Result computed elsewhere (e.g. Python on arrays): `result` holds a
  // `const Result*` of the procedure's Result type (std::bad_any_cast otherwise).
  std::function<nlohmann::json(const std::any& result)> fields_of;

  const ParameterSpec* find_parameter(const std::string& name) const;
};

// Every declared procedure, sorted by kind (generated list, see above).
const std::vector<ProcedureSpec>& procedure_specs();
const ProcedureSpec* find_procedure_spec(const std::string& kind);

// Throws Error naming the spec when `field`'s unit (FieldSpec::unit) names a parameter the spec does
// not declare, or, fixed or with each parameter's default, is no unit (core/units.h).
void check_unit_template(const ProcedureSpec& spec, const FieldSpec& field);

// Throws Error at the later run (RunInput::where, else its file) when a runs input names one file
// twice: each run is a record of its own (one record at two rates, or a run listed twice, weighed
// one test as two).
void check_runs_distinct(const ProcedureCall& call);

// Throws ParameterError unless each given text parameter named "..._unit" (output_unit, rate_unit,
// input_unit...) is a unit core/units.h reads, or a list per channel (NAME=UNIT,...) its procedure
// reads: "banana" was taken as an output unit and printed.
void check_unit_parameters(const ProcedureCall& call);

// Throws Error("<who>give exactly one of A, B or C") unless exactly one input of each group of
// alternatives (InputSpec::alternative_in) is given; `name_of` names an input as its caller takes it.
void check_alternatives(const ProcedureSpec& spec, const std::string& who,
                        const std::function<bool(const InputSpec&)>& given,
                        const std::function<std::string(const InputSpec&)>& name_of);

// The JSON object of a result: "procedure" (json_procedure), "clause", the fields (nulls left out
// unless the result writes its own JSON) and "warnings".
// A field named "clause" (e.g. the subclause of the method used) replaces the spec's clause, here
// and in the text.
nlohmann::json procedure_json(const ProcedureSpec& spec, const nlohmann::json& fields);

// The unit `field` is reported in when a procedure runs with `parameters` (ProcedureCall::parameters,
// by name): FieldSpec::unit with each "{name}" replaced by that parameter's text; nullopt when the
// field declares none or a parameter it names has no text value (not given, no default).
std::optional<std::string> declared_unit(const FieldSpec& field, const nlohmann::json& parameters);

// The text report of a result, the same shape for every procedure: a title line with the clause,
// then one line per headline and detail field, "label  value ± uncertainty unit" for a figure
// ("[a, b, c] ± [ua, ub, uc] unit" for a figure whose value and uncertainty are arrays: a vector or
// a matrix), then the warnings.
std::string procedure_text(const ProcedureSpec& spec, const nlohmann::json& fields);
// The text of a run: its own (ProcedureOutput::text), else procedure_text of its fields.
std::string procedure_text(const ProcedureSpec& spec, const ProcedureOutput& output);

template <typename T>
inline constexpr bool is_optional = false;
template <typename T>
inline constexpr bool is_optional<std::optional<T>> = true;

// T, or the value type of a std::optional<T>.
template <typename T>
struct optional_value {
  using type = T;
};
template <typename T>
struct optional_value<std::optional<T>> {
  using type = T;
};

template <typename T>
constexpr FieldValue field_value_of() {
  if constexpr (is_optional<T>) {
    return field_value_of<typename T::value_type>();
  } else if constexpr (std::is_same_v<T, Figure>) {
    return FieldValue::figure;
  } else if constexpr (std::is_same_v<T, bool>) {
    return FieldValue::boolean;
  } else if constexpr (std::is_integral_v<T>) {
    return FieldValue::whole_number;
  } else if constexpr (std::is_floating_point_v<T>) {
    return FieldValue::number;
  } else if constexpr (std::is_same_v<T, std::string>) {
    return FieldValue::text;
  } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
    return FieldValue::texts;
  } else if constexpr (requires { typename T::value_type; } && !std::is_same_v<T, nlohmann::json>) {
    return FieldValue::rows;
  } else {
    return FieldValue::structured;
  }
}

// Typed construction of a ProcedureSpec: parameters bound to Options members, fields read from
// Result members, and the computation.
template <typename Options, typename Result>
class ProcedureDefinition {
 public:
  using Binder = std::function<void(Options&, const nlohmann::json&)>;

  ProcedureDefinition(std::string kind, std::string title, std::string clause, std::string doc) {
    spec_.kind = std::move(kind);
    spec_.title = std::move(title);
    spec_.clause = std::move(clause);
    spec_.doc = std::move(doc);
    spec_.json_procedure = spec_.kind;
  }

  // The CLI command as a subcommand of a group (ProcedureSpec::command_path), a contract.
  ProcedureDefinition& command_is(std::string group, std::string name, std::string group_doc = "") {
    spec_.command_path = {std::move(group), std::move(name)};
    spec_.command_group_doc = std::move(group_doc);
    return *this;
  }

  // The JSON's "procedure" when it is a contract that differs from the kind (e.g.
  // "scale_factor_temperature_sensitivity" for the kind "scale_factor_temperature").
  ProcedureDefinition& json_procedure_is(std::string name) {
    spec_.json_procedure = std::move(name);
    return *this;
  }

  // A parameter stored in an Options member; its default is the member's default value unless the
  // parameter is required; a std::optional member has none (absent unless given).
  // A std::size_t member is a whole number (checked by the command line and plans); the other types
  // are as ParameterType says.
  template <typename T>
  ProcedureDefinition& parameter(ParameterSpec parameter, T Options::*member) {
    return member_parameter<T>(std::move(parameter), [member](Options& options) -> T& { return options.*member; });
  }

  // A parameter stored in a member of an Options member (e.g. &Options::scale_factor,
  // &ScaleFactorOptions::rate_unit); its default is that member's default value unless required.
  template <typename Part, typename T>
  ProcedureDefinition& parameter(ParameterSpec parameter, Part Options::*part, T Part::*member) {
    return member_parameter<T>(std::move(parameter),
                               [part, member](Options& options) -> T& { return options.*part.*member; });
  }

  // A parameter without a default (optional, or required on the command line) stored through `bind`.
  ProcedureDefinition& parameter(ParameterSpec parameter, Binder bind) {
    binders_.emplace_back(parameter.name, std::move(bind));
    spec_.parameters.push_back(std::move(parameter));
    return *this;
  }

  // A parameter with the default `default_value` stored through `bind` (e.g. a text choice that
  // sets a flag of the Options).
  ProcedureDefinition& parameter(ParameterSpec parameter, nlohmann::json default_value, Binder bind) {
    spec_.defaults[parameter.name] = std::move(default_value);
    return this->parameter(std::move(parameter), std::move(bind));
  }

  // The title in GJB 2426A's Chinese terms (the report in Chinese).
  ProcedureDefinition& chinese_title(std::string title) {
    spec_.title_zh = std::move(title);
    return *this;
  }

  // The method in one paragraph for the report, in English and in Chinese.
  ProcedureDefinition& report_method(std::string english, std::string chinese) {
    spec_.method_en = std::move(english);
    spec_.method_zh = std::move(chinese);
    return *this;
  }

  // The worked example (ProcedureSpec::example).
  ProcedureDefinition& example(std::vector<std::string> arguments) {
    spec_.example = std::move(arguments);
    return *this;
  }

  // Replaces the check before any input is read (Options::validate by default; an Options without
  // validate() needs one), e.g. to check only what the procedure uses of a shared Options or the
  // number of runs an option asks for.
  ProcedureDefinition& checked_by(std::function<void(const ProcedureCall&, const Options&)> check) {
    check_ = std::move(check);
    return *this;
  }

  ProcedureDefinition& input(InputSpec input) {
    spec_.inputs.push_back(std::move(input));
    return *this;
  }

  // A field read from a Result member (anything nlohmann::json converts, e.g. Figure; a std::optional
  // of it, left out when empty).
  template <typename T>
  ProcedureDefinition& field(FieldSpec field, T Result::*member) {
    field.value = field_value_of<T>();
    return field_from(std::move(field), [member](const Result& result) {
      if constexpr (is_optional<T>) {
        return result.*member ? nlohmann::json(*(result.*member)) : nlohmann::json();
      } else {
        return nlohmann::json(result.*member);
      }
    });
  }

  // A figure computed from the Result (e.g. a member of a member).
  ProcedureDefinition& figure_from(FieldSpec field, std::function<Figure(const Result&)> figure) {
    field.value = FieldValue::figure;
    return field_from(std::move(field), [figure = std::move(figure)](const Result& result) {
      return nlohmann::json(figure(result));
    });
  }

  // A Result that writes its JSON object and its text itself, for a shape of its own (allan: one
  // object, or one per channel of an IMU): `json` gives the fields (procedure_json adds "procedure"
  // and "clause"), `text` the text. Its keys are declared with declare(), not read by field().
  ProcedureDefinition& written_by(std::function<nlohmann::json(const Result&)> json,
                                  std::function<std::string(const Result&)> text) {
    written_json_ = std::move(json);
    written_text_ = std::move(text);
    spec_.writes_own_json = true;
    return *this;
  }

  // The unit of a field declared already, fixed or a template of the parameters declared already
  // (FieldSpec::unit): .unit_of("scale_factor", "{output_unit}/({rate_unit})").
  ProcedureDefinition& unit_of(const std::string& field_name, std::string unit) {
    for (FieldSpec& field : spec_.fields) {
      if (field.name == field_name) {
        field.unit = std::move(unit);
        check_unit_template(spec_, field);
        return *this;
      }
    }
    throw Error("procedure spec " + spec_.kind + ": unit_of an undeclared field '" + field_name + "'");
  }

  // The declared yes/no field with which the procedure judges its own specification
  // (FieldSpec::states_verdict).
  ProcedureDefinition& verdict_is(const std::string& field_name) {
    for (FieldSpec& field : spec_.fields) {
      if (field.name == field_name) {
        field.states_verdict = true;
        return *this;
      }
    }
    throw Error("procedure spec " + spec_.kind + ": verdict_is an undeclared field '" + field_name + "'");
  }

  // A key of the JSON that written_by writes: for the report, the plan's limits and the stubs.
  ProcedureDefinition& declare(FieldSpec field) {
    spec_.fields.push_back(std::move(field));
    return *this;
  }

  // A field computed from the Result (e.g. a sign spelled out); null leaves it out.
  ProcedureDefinition& field_from(FieldSpec field, std::function<nlohmann::json(const Result&)> value) {
    if (field.value == FieldValue::structured && (field.role == FieldRole::table || field.role == FieldRole::curve)) {
      field.value = FieldValue::rows;
    }
    getters_.emplace_back(field.name, std::move(value));
    spec_.fields.push_back(std::move(field));
    return *this;
  }

  // The computation: the call's inputs and files, and the Options made from its parameters.
  ProcedureSpec compute(std::function<Result(const ProcedureCall&, const Options&)> procedure) const {
    ProcedureSpec spec = spec_;
    auto options_of = [binders = binders_](const ProcedureCall& call) {
      Options options;
      for (const auto& [name, bind] : binders) {
        if (call.parameters.contains(name)) bind(options, call.parameters.at(name));
      }
      return options;
    };
    spec.check = [options_of, check = check_](const ProcedureCall& call) {
      check_runs_distinct(call);
      check_unit_parameters(call);
      if (check) {
        check(call, options_of(call));
      } else if constexpr (requires(const Options& options) { options.validate(); }) {
        options_of(call).validate();
      }
    };
    spec.fields_of = [getters = getters_, written = written_json_](const std::any& result) {
      const Result& value = *std::any_cast<const Result*>(result);
      if (written) return written(value);
      nlohmann::json fields = nlohmann::json::object();
      for (const auto& [name, get] : getters) fields[name] = get(value);
      return fields;
    };
    spec.run = [options_of, fields_of = spec.fields_of, text = written_text_, procedure](const ProcedureCall& call) {
      const Result result = procedure(call, options_of(call));
      return ProcedureOutput{fields_of(&result), text ? text(result) : std::string()};
    };
    return spec;
  }

 private:
  // A parameter stored in the member of the Options that `member_of` returns.
  template <typename T>
  ProcedureDefinition& member_parameter(ParameterSpec parameter, std::function<T&(Options&)> member_of) {
    using Value = typename optional_value<T>::type;
    static_assert(std::is_same_v<Value, double> || std::is_same_v<Value, std::string> ||
                      std::is_same_v<Value, std::size_t> || std::is_same_v<Value, std::vector<double>> ||
                      std::is_same_v<Value, bool> || std::is_same_v<Value, std::vector<std::string>>,
                  "number, whole number, text, numbers, boolean or texts parameters");
    if constexpr (!is_optional<T>) {
      Options defaults;
      if (!parameter.required) spec_.defaults[parameter.name] = member_of(defaults);
    }
    parameter.type = std::is_same_v<Value, std::string>                ? ParameterType::text
                     : std::is_same_v<Value, std::vector<double>>      ? ParameterType::numbers
                     : std::is_same_v<Value, bool>                     ? ParameterType::boolean
                     : std::is_same_v<Value, std::vector<std::string>> ? ParameterType::texts
                                                                       : ParameterType::number;
    parameter.whole = std::is_same_v<Value, std::size_t>;
    binders_.emplace_back(parameter.name, [member_of](Options& options, const nlohmann::json& value) {
      if constexpr (std::is_same_v<Value, std::size_t>) {
        member_of(options) = static_cast<std::size_t>(value.get<double>());
      } else {
        member_of(options) = value.get<Value>();
      }
    });
    spec_.parameters.push_back(std::move(parameter));
    return *this;
  }

  ProcedureSpec spec_;
  std::vector<std::pair<std::string, Binder>> binders_;
  std::vector<std::pair<std::string, std::function<nlohmann::json(const Result&)>>> getters_;
  std::function<void(const ProcedureCall&, const Options&)> check_;
  std::function<nlohmann::json(const Result&)> written_json_;
  std::function<std::string(const Result&)> written_text_;
};

}  // namespace inertest
