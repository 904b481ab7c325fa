// specs: every declared procedure (core/procedure_spec.h) that has no array-based function of its
// own in this module becomes `inertest.<kind>(**keywords)`, made from its spec as the CLI command
// and the plan step are: the keywords are the spec's plan keys (ParameterSpec::plan_name), each
// value-or-record input `NAME` takes a number or an array of samples (their mean, as NAME_file
// takes a record's mean in a plan), each file input takes its plan key (a path), and each runs input
// its plan key: a list of paths (runs 1, 2, ...) or of (number, path) pairs; output records are read
// as a plan reads them, with the keywords `column` and `format`. `inertest.procedure(kind, **keywords)`
// runs any declared procedure so, also those with an array-based function. The type stubs of these
// functions are generated from procedure_specs() at build time (generate_stubs.py).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "bindings.h"
#include "inertest/io/output_record.h"
#include "inertest/numerics/statistics.h"

namespace inertest::python {
namespace {

struct SpecTag {};

// The keyword of an input: its name for a value, its plan key for a file or runs.
const std::string& keyword_of(const InputSpec& input) {
  return input.kind == InputKind::value_or_record ? input.name : input.plan_key;
}

bool reads_records(const ProcedureSpec& spec) {
  return std::any_of(spec.inputs.begin(), spec.inputs.end(), [](const InputSpec& input) { return input.records; });
}

bool reads_timed_records(const ProcedureSpec& spec) {
  return std::any_of(spec.inputs.begin(), spec.inputs.end(), [](const InputSpec& input) { return input.timed; });
}

// The Python keywords of a spec, in declaration order: parameters, inputs, then column and format
// when it reads output records and sample_rate_hz and time_column when they are timed.
std::vector<std::string> keywords_of(const ProcedureSpec& spec) {
  std::vector<std::string> keywords;
  for (const ParameterSpec& parameter : spec.parameters) keywords.push_back(parameter.plan_name());
  for (const InputSpec& input : spec.inputs) keywords.push_back(keyword_of(input));
  if (reads_records(spec)) keywords.insert(keywords.end(), {"column", "format"});
  if (reads_timed_records(spec)) keywords.insert(keywords.end(), {"sample_rate_hz", "time_column"});
  return keywords;
}

nlohmann::json parameter_value(const ParameterSpec& parameter, const py::handle& value) {
  if (parameter.type == ParameterType::boolean) {
    if (!py::isinstance<py::bool_>(value)) throw Error(fmt::format("{} must be True or False", parameter.plan_name()));
    return value.cast<bool>();
  }
  if (parameter.type == ParameterType::numbers || parameter.type == ParameterType::texts) {
    const bool texts = parameter.type == ParameterType::texts;
    const std::string what = fmt::format("{} must be a list of {}", parameter.plan_name(), texts ? "strings" : "numbers");
    if (py::isinstance<py::str>(value)) throw Error(what);
    try {
      if (texts) return value.cast<std::vector<std::string>>();
      return value.cast<std::vector<double>>();
    } catch (const py::cast_error&) {
      throw Error(what);
    }
  }
  if (parameter.type == ParameterType::number) {
    if (!is_number(value)) throw Error(fmt::format("{} must be a number", parameter.plan_name()));
    const double number = py::float_(py::reinterpret_borrow<py::object>(value));
    if (parameter.whole && !(number >= 0.0 && number == std::floor(number))) {
      throw Error(fmt::format("{} must be a whole number, got {}", parameter.plan_name(), number));
    }
    return number;
  }
  if (!py::isinstance<py::str>(value)) throw Error(fmt::format("{} must be a string", parameter.plan_name()));
  const auto text = value.cast<std::string>();
  if (!parameter.choices.empty() &&
      std::find(parameter.choices.begin(), parameter.choices.end(), text) == parameter.choices.end()) {
    throw Error(fmt::format("{} must be one of {}", parameter.plan_name(), fmt::join(parameter.choices, ", ")));
  }
  return text;
}

// A number, or the mean of an array of samples (compensated, as a record's mean).
InputValue input_value(const InputSpec& input, const py::handle& value) {
  if (is_number(value)) return {py::float_(py::reinterpret_borrow<py::object>(value)), std::nullopt};
  if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value)) {
    throw Error(fmt::format("{} must be a number or an array of samples", input.name));
  }
  const DoubleArray samples = real_array(value);
  const std::span<const double> span = as_span(samples, input.name.c_str());
  if (span.empty()) throw Error(fmt::format("{} has no samples", input.name));
  const MeanWithError mean = mean_with_error(span);
  return {mean.mean, mean.standard_error};
}

// A list of paths (numbered 1, 2, ...) or of (number, path) pairs; at least the input's minimum
// (`function` names the call in the message).
std::vector<RunInput> runs_of(const std::string& function, const InputSpec& input, const py::handle& value) {
  if (py::isinstance<py::str>(value)) throw Error(fmt::format("{} must be a list of runs, not one path", input.plan_key));
  std::vector<RunInput> runs;
  for (const py::handle item : value) {
    if (py::isinstance<py::tuple>(item) || py::isinstance<py::list>(item)) {
      const auto pair = item.cast<py::sequence>();
      if (pair.size() != 2) throw Error(fmt::format("{}: a run is (number, path)", input.plan_key));
      // A real number: Python's or numpy's float or integer (not a bool, a complex or a string).
      const py::module_ numpy = py::module_::import("numpy");
      const bool real = !py::isinstance<py::bool_>(pair[0]) &&
                        (py::isinstance<py::float_>(pair[0]) || py::isinstance<py::int_>(pair[0]) ||
                         py::isinstance(pair[0], numpy.attr("floating")) || py::isinstance(pair[0], numpy.attr("integer")));
      if (!real) {
        throw Error(fmt::format("{}: run {}: its {} must be a number, got {}", input.plan_key, runs.size() + 1,
                                input.number_key.empty() ? "number" : input.number_key, py::repr(pair[0]).cast<std::string>()));
      }
      const auto file = py::str(pair[1]).cast<std::string>();
      runs.push_back({py::float_(pair[0]).cast<double>(), file, file});
    } else {
      if (!input.number_key.empty()) {
        throw Error(fmt::format("{}: each run is ({}, path)", input.plan_key, input.number_key));
      }
      const auto file = py::str(item).cast<std::string>();
      runs.push_back({static_cast<double>(runs.size() + 1), file, file});
    }
  }
  if (runs.size() < input.minimum_runs) {
    throw Error(fmt::format("{} needs at least {} runs in {} ({}), got {}", function, input.minimum_runs, input.plan_key,
                            input.minimum_why, runs.size()));
  }
  return runs;
}

// `function` names the call in messages: "scale_factor()" or "procedure('scale_factor')".
ProcedureCall call_of(const ProcedureSpec& spec, const py::kwargs& keywords, const std::string& function) {
  const std::vector<std::string> accepted = keywords_of(spec);
  for (const auto& [key, value] : keywords) {
    const auto name = key.cast<std::string>();
    if (std::find(accepted.begin(), accepted.end(), name) == accepted.end()) {
      throw Error(
          fmt::format("{} got an unknown keyword '{}'; it takes {}", function, name, fmt::join(accepted, ", ")));
    }
  }
  ProcedureCall call;
  for (const auto& [name, value] : spec.defaults) call.parameters[name] = value;
  for (const ParameterSpec& parameter : spec.parameters) {
    if (const std::string& keyword = parameter.plan_name(); keywords.contains(keyword)) {
      call.parameters[parameter.name] = parameter_value(parameter, keywords[keyword.c_str()]);
    } else if (parameter.required) {
      throw Error(fmt::format("{} needs {} ({})", function, parameter.plan_name(), parameter.doc));
    }
  }
  check_alternatives(
      spec, function + ": ", [&](const InputSpec& input) { return keywords.contains(keyword_of(input)); }, keyword_of);
  for (const InputSpec& input : spec.inputs) {
    const std::string& key = keyword_of(input);
    if (!keywords.contains(key) && !input.alternatives.empty()) continue;
    if (!keywords.contains(key)) throw Error(fmt::format("{} needs {} ({})", function, key, input.doc));
    const py::handle value = keywords[key.c_str()];
    switch (input.kind) {
      case InputKind::file: call.files[input.name] = py::str(value).cast<std::string>(); break;
      case InputKind::runs: call.runs[input.name] = runs_of(function, input, value); break;
      case InputKind::value_or_record: call.inputs[input.name] = input_value(input, value); break;
    }
  }
  OutputRecordSource source;
  if (keywords.contains("column")) source.column = py::str(keywords["column"]).cast<std::string>();
  if (keywords.contains("format")) source.format = py::str(keywords["format"]).cast<std::string>();
  std::optional<double> rate;
  if (keywords.contains("sample_rate_hz")) rate = keywords["sample_rate_hz"].cast<double>();
  const std::string time_column = keywords.contains("time_column") ? py::str(keywords["time_column"]).cast<std::string>() : "";
  set_record_readers(call, source, minimum_samples_of(spec.inputs), rate, time_column);
  read_pulse_counts_as_rates(
      call, spec, [&](const InputSpec& input) { return keywords.contains(keyword_of(input)); }, rate);
  return call;
}

std::string docstring_of(const ProcedureSpec& spec) {
  std::string text = fmt::format("{} ({}).\n{}\nKeywords:\n", spec.title, spec.clause, spec.doc);
  for (const ParameterSpec& parameter : spec.parameters) {
    text += fmt::format("  {}: {}{}", parameter.plan_name(), parameter.doc, parameter.unit.empty() ? "" : " (" + parameter.unit + ")");
    if (const auto found = spec.defaults.find(parameter.name); found != spec.defaults.end()) {
      text += fmt::format(", default {}", found->second.dump());
    } else if (parameter.required) {
      text += ", required";
    }
    text += "\n";
  }
  for (const InputSpec& input : spec.inputs) {
    switch (input.kind) {
      case InputKind::file: text += fmt::format("  {}: path of {}\n", input.plan_key, input.doc); break;
      case InputKind::runs:
        text += input.number_key.empty()
                    ? fmt::format("  {}: {}, a list of paths\n", input.plan_key, input.doc)
                    : fmt::format("  {}: {}, a list of ({}, path)\n", input.plan_key, input.doc, input.number_key);
        break;
      case InputKind::value_or_record:
        text += fmt::format("  {}: {}, a number or an array of samples (their mean)\n", input.name, input.doc);
        break;
    }
  }
  if (reads_records(spec)) text += "  column, format: how the records are stored, as in a plan\n";
  if (reads_timed_records(spec)) text += "  sample_rate_hz, time_column: the time of each sample, as in a plan\n";
  return text + "Returns a ProcedureResult (members as in the CLI's --json); raises inertest.Error.";
}

// The spec as plain data, for the stub generator and for users who script around the registry.
nlohmann::json description_of(const ProcedureSpec& spec, bool generic_function) {
  static const std::vector<std::string> parameter_type_names = {"number", "text", "numbers", "boolean", "texts"};  // ParameterType
  nlohmann::json parameters = nlohmann::json::array();
  for (const ParameterSpec& parameter : spec.parameters) {
    const auto found = spec.defaults.find(parameter.name);
    parameters.push_back({{"name", parameter.plan_name()},
                          {"type", parameter_type_names.at(static_cast<std::size_t>(parameter.type))},
                          {"unit", parameter.unit},
                          {"doc", parameter.doc},
                          {"choices", parameter.choices},
                          {"required", parameter.required},
                          {"whole", parameter.whole},
                          {"default", found == spec.defaults.end() ? nlohmann::json() : found->second}});
  }
  nlohmann::json inputs = nlohmann::json::array();
  for (const InputSpec& input : spec.inputs) {
    const char* kind = input.kind == InputKind::file ? "file" : input.kind == InputKind::runs ? "runs" : "value_or_record";
    inputs.push_back({{"name", keyword_of(input)}, {"kind", kind}, {"number_key", input.number_key}, {"doc", input.doc},
                      {"alternative", !input.alternatives.empty()}});
  }
  nlohmann::json fields = nlohmann::json::array();
  for (const FieldSpec& field : spec.fields) fields.push_back(field.name);
  return {{"kind", spec.kind},          {"title", spec.title},   {"clause", spec.clause},
          {"parameters", parameters},   {"inputs", inputs},      {"fields", fields},
          {"reads_records", reads_records(spec)}, {"reads_timed_records", reads_timed_records(spec)},
          {"generic_function", generic_function}};
}

// The Python type of a field's JSON value (as Record presents it) in the stubs.
const char* python_type(FieldValue value) {
  switch (value) {
    case FieldValue::figure: return "Figure";
    case FieldValue::number: return "float";
    case FieldValue::whole_number: return "int";
    case FieldValue::boolean: return "bool";
    case FieldValue::text: return "str";
    case FieldValue::texts: return "list[str]";
    case FieldValue::rows: return "list[Record]";
    case FieldValue::structured: break;
  }
  return "Any";
}

// The procedure of `spec` run with `keywords` as the command and the plan step run it; `function`
// names the call in messages.
ResultOf<SpecTag> run_spec(const ProcedureSpec& spec, const py::kwargs& keywords, const std::string& function) {
  ProcedureCall call;
  try {
    call = call_of(spec, keywords, function);
    spec.check(call);
  } catch (const ParameterError& e) {
    throw Error(e.message_naming(spec.find_parameter(e.parameter)->plan_name()));
  }
  ProcedureOutput output;
  nlohmann::json json;
  {
    py::gil_scoped_release release;
    // As the command and the plan step: a complaint about the data of its one file names it.
    json = with_call_file_context(call, [&] {
      output = spec.run(call);
      return procedure_json(spec, output.fields);
    });
  }
  return ResultOf<SpecTag>(json, procedure_text(spec, output));
}

}  // namespace

std::string result_doc(const ProcedureSpec& spec) {
  std::string text = fmt::format("{} ({}): members as in the CLI's --json object.\nMembers:\n    procedure: str\n",
                                 spec.title, spec.clause);
  const bool declares_clause = std::any_of(spec.fields.begin(), spec.fields.end(),
                                           [](const FieldSpec& field) { return field.name == "clause"; });
  if (!declares_clause) text += "    clause: str\n";
  for (const FieldSpec& field : spec.fields) {
    text += fmt::format("    {}: {}  # {}{}\n", field.name, python_type(field.value), field.label_en,
                        field.equation.empty() ? "" : ", " + field.equation);
  }
  return text;
}

void wrap_specs(py::module_& module) {
  bind_result<SpecTag>(module, "ProcedureResult",
                       "The result of a declared procedure: members as in the CLI's --json object (figures with\n"
                       "value, unit and uncertainty); report() is the CLI's text.");
  std::set<std::string> generic;
  for (const ProcedureSpec& spec : procedure_specs()) {
    if (py::hasattr(module, spec.kind.c_str())) continue;  // it has an array-based function of its own
    generic.insert(spec.kind);
    module.def(
        spec.kind.c_str(), [&spec](const py::kwargs& keywords) { return run_spec(spec, keywords, spec.kind + "()"); },
        docstring_of(spec).c_str());
  }
  module.def(
      "procedure",
      [](const std::string& kind, const py::kwargs& keywords) {
        const ProcedureSpec* spec = find_procedure_spec(kind);
        if (spec == nullptr) {
          throw Error(
              fmt::format("no declared procedure '{}': inertest.procedure_specs() lists the kinds it runs (a "
                          "plan's other kinds have functions of their own, e.g. inertest.hand_checks)",
                          kind));
        }
        return run_spec(*spec, keywords, fmt::format("procedure('{}')", kind));
      },
      py::arg("kind"),
      "Runs the declared procedure `kind` (one inertest.procedure_specs() lists) with the keywords of its spec, as\n"
      "inertest.<kind> does for the functions made from specs: the spec's plan keys\n"
      "(inertest.procedure_specs()), each file input its plan key, records with column and format.\n"
      "It reaches every input of the procedures that have an array-based function of their own, e.g.\n"
      "a scale factor from one long record: procedure(\"scale_factor\", record=\"long.csv\",\n"
      "sample_rate_hz=100). Returns a ProcedureResult; raises inertest.Error.");
  module.def(
      "procedure_specs",
      [generic] {
        nlohmann::json list = nlohmann::json::array();
        for (const ProcedureSpec& spec : procedure_specs()) list.push_back(description_of(spec, generic.contains(spec.kind)));
        return to_plain_python(list);
      },
      "Every declared procedure as a dict: kind, title, clause, parameters (name, type, unit, doc,\n"
      "choices, required, default), inputs (name, kind, doc), fields (the JSON keys) and\n"
      "generic_function (True when inertest.<kind> is made from the spec).");
}

}  // namespace inertest::python
