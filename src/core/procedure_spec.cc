#include "inertest/core/procedure_spec.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/json_text.h"
#include "inertest/core/units.h"

namespace inertest {

// Defined in the generated procedure_spec_list.cc: every spec of src/procedures/*_spec.cc.
std::vector<ProcedureSpec> declared_procedure_specs();

const ParameterSpec* ProcedureSpec::find_parameter(const std::string& name) const {
  const auto found = std::find_if(parameters.begin(), parameters.end(), [&](const auto& p) { return p.name == name; });
  return found == parameters.end() ? nullptr : &*found;
}

const std::vector<ProcedureSpec>& procedure_specs() {
  static const std::vector<ProcedureSpec> specs = [] {
    std::vector<ProcedureSpec> all = declared_procedure_specs();
    std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.kind < b.kind; });
    return all;
  }();
  return specs;
}

const ProcedureSpec* find_procedure_spec(const std::string& kind) {
  const auto& specs = procedure_specs();
  const auto found = std::find_if(specs.begin(), specs.end(), [&](const auto& s) { return s.kind == kind; });
  return found == specs.end() ? nullptr : &*found;
}

namespace {

// "1st", "2nd", "3rd", "4th", ... "11th", "21st".
std::string ordinal(std::size_t n) {
  const std::size_t last = n % 10;
  const char* suffix = (n % 100 >= 11 && n % 100 <= 13) || last == 0 || last > 3 ? "th" : last == 1 ? "st" : last == 2 ? "nd" : "rd";
  return std::to_string(n) + suffix;
}

}  // namespace

void check_unit_parameters(const ProcedureCall& call) {
  for (const auto& item : call.parameters.items()) {
    if (!item.key().ends_with("_unit") || !item.value().is_string()) continue;
    // Empty: none given. Of a list per channel ("gx=deg/s,ax=m/s^2", allan's) each unit is checked
    // here, and the list is its procedure's to read, with its own messages (a list without names,
    // "deg/s,deg/h", says so there); "ch=banana" passed as a unit.
    const std::string& text = item.value().get_ref<const std::string&>();
    if (text.empty()) continue;
    for (std::size_t begin = 0; begin <= text.size();) {
      const std::size_t end = std::min(text.find(',', begin), text.size());
      std::string_view unit = std::string_view(text).substr(begin, end - begin);
      if (const std::size_t equals = unit.find('='); equals != std::string_view::npos) unit.remove_prefix(equals + 1);
      check_parameter(item.key(), [unit] { Unit::parse(unit); });
      begin = end + 1;
    }
  }
}

void check_runs_distinct(const ProcedureCall& call) {
  for (const auto& [name, runs] : call.runs) {
    std::map<std::filesystem::path, std::size_t> seen;  // the first run of each file, by place
    for (std::size_t i = 0; i < runs.size(); ++i) {
      std::error_code error;
      std::filesystem::path same = std::filesystem::weakly_canonical(runs[i].file, error);
      if (error) same = std::filesystem::path(runs[i].file).lexically_normal();
      const auto [first, inserted] = seen.emplace(same, i);
      if (inserted) continue;
      const RunInput& run = runs[i];
      const RunInput& earlier = runs[first->second];
      // At the later run's place (a plan's key, a listing's row), else at the file itself.
      const bool placed = !run.where.file.empty();
      throw Error(placed ? run.where : SourceLocation{run.file, 0, 0},
                  fmt::format("the {} and {} runs name one file{}{}: each run is a record of its own",
                              ordinal(first->second + 1), ordinal(i + 1), placed ? ", '" + run.file + "'" : "",
                              earlier.where.file.empty() || earlier.where.to_string() == run.where.to_string()
                                  ? ""
                                  : " (the first at " + earlier.where.to_string() + ")"));
    }
  }
}

void check_alternatives(const ProcedureSpec& spec, const std::string& who,
                        const std::function<bool(const InputSpec&)>& given,
                        const std::function<std::string(const InputSpec&)>& name_of) {
  std::map<std::string, std::pair<int, std::vector<std::string>>> groups;  // given count, names
  for (const InputSpec& input : spec.inputs) {
    if (input.alternatives.empty()) continue;
    auto& [count, names] = groups[input.alternatives];
    count += given(input) ? 1 : 0;
    names.push_back(name_of(input));
  }
  for (const auto& [group, entry] : groups) {
    const auto& [count, names] = entry;
    if (count == 1) continue;
    std::string list = names.front();
    for (std::size_t i = 1; i < names.size(); ++i) list += (i + 1 == names.size() ? " or " : ", ") + names[i];
    throw Error(who + "give exactly one of " + list);
  }
}

std::string ProcedureCall::output_path(const std::string& path) const {
  if (output_directory.empty()) {
    const auto refuse_input = [&](const std::string& input) {
      std::error_code error;  // equivalent() is false, with an error, when either does not exist
      if (std::filesystem::equivalent(path, input, error)) {
        throw Error("the export '" + path + "' would replace the input file '" + input + "': give the export another name");
      }
    };
    for (const auto& [name, file] : files) refuse_input(file);
    for (const auto& [name, list] : runs) {
      for (const RunInput& run : list) refuse_input(run.file);
    }
    return path;
  }
  if (!is_inside_output_directory(path)) {
    throw Error("'" + path + "' is outside the output directory: an export is a relative path beside results.json");
  }
  const std::filesystem::path inside = std::filesystem::path(output_directory) / path;
  std::filesystem::create_directories(inside.parent_path());
  return inside.string();
}

bool is_inside_output_directory(const std::string& path) {
  const std::filesystem::path normal = std::filesystem::path(path).lexically_normal();
  if (path.empty() || normal.is_absolute() || normal.has_root_name() || normal.empty() || normal == ".") return false;
  return *normal.begin() != "..";
}

std::string kebab_case(const std::string& name) {
  std::string flag = name;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

namespace {

// The JSON pointer of the first number in `value` that is NaN or infinite ("" when none).
std::string first_non_finite(const nlohmann::json& value, const std::string& at) {
  if (value.is_number_float()) return std::isfinite(value.get<double>()) ? std::string() : (at.empty() ? "/" : at);
  if (value.is_object()) {
    for (const auto& [key, item] : value.items()) {
      if (std::string found = first_non_finite(item, at + "/" + key); !found.empty()) return found;
    }
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) {
      if (std::string found = first_non_finite(value[i], at + "/" + std::to_string(i)); !found.empty()) return found;
    }
  }
  return {};
}

}  // namespace

namespace {

// A unit template (FieldSpec::unit) with each "{name}" replaced by value_of(name); nullopt when
// value_of gives none, or at a '{' without its '}'.
std::optional<std::string> filled_unit(const std::string& unit,
                                       const std::function<std::optional<std::string>(const std::string&)>& value_of) {
  std::string filled;
  std::size_t at = 0;
  for (std::size_t open = unit.find('{'); open != std::string::npos; open = unit.find('{', at)) {
    const std::size_t close = unit.find('}', open);
    if (close == std::string::npos) return std::nullopt;
    const std::optional<std::string> value = value_of(unit.substr(open + 1, close - open - 1));
    if (!value) return std::nullopt;
    filled += unit.substr(at, open - at) + *value;
    at = close + 1;
  }
  return filled + unit.substr(at);
}

}  // namespace

std::optional<std::string> declared_unit(const FieldSpec& field, const nlohmann::json& parameters) {
  if (field.unit.empty()) return std::nullopt;
  return filled_unit(field.unit, [&](const std::string& name) -> std::optional<std::string> {
    const auto value = parameters.find(name);
    if (value == parameters.end() || !value->is_string()) return std::nullopt;
    return value->get<std::string>();
  });
}

void check_unit_template(const ProcedureSpec& spec, const FieldSpec& field) {
  const std::string who = "procedure spec " + spec.kind + ": the unit of '" + field.name + "' (" + field.unit + ")";
  // Filled with each parameter's default, "1" where it has none (the instrument gives it).
  const std::optional<std::string> unit = filled_unit(field.unit, [&](const std::string& name) {
    if (spec.find_parameter(name) == nullptr) throw Error(who + " names no parameter of the procedure");
    const auto fallback = spec.defaults.find(name);
    return std::optional<std::string>(fallback != spec.defaults.end() && fallback->second.is_string()
                                          ? fallback->second.get<std::string>()
                                          : "1");
  });
  if (!unit) throw Error(who + " has a '{' without '}'");
  try {
    Unit::parse(*unit);
  } catch (const Error& e) {
    throw Error(who + ": " + e.message());
  }
}

nlohmann::json procedure_json(const ProcedureSpec& spec, const nlohmann::json& fields) {
  // A figure that overflowed or cancelled to NaN would be written as null, exit 0 (a scale factor of
  // outputs near 1e300 gave "fit_residual_rms": null): every procedure's output is refused instead.
  if (const std::string at = first_non_finite(fields, ""); !at.empty()) {
    throw Error(fmt::format("{}: {} is not a finite number: the data overflow a double (give them in a larger unit)",
                            spec.kind, at));
  }
  nlohmann::json json = {{"procedure", spec.json_procedure}, {"clause", spec.clause}};
  for (const auto& [name, value] : fields.items()) {
    if (!value.is_null() || spec.writes_own_json) json[name] = value;
  }
  return json;
}

namespace {

bool is_figure(const nlohmann::json& value) {
  return value.is_object() && value.contains("value") && value.contains("unit");
}

// A number to `digits` significant digits, or an array of them (a vector or matrix figure) as "[a, b, c]".
std::string numbers_text(const nlohmann::json& value, int digits) {
  if (!value.is_array()) return fmt::format("{:.{}g}", value.get<double>(), digits);
  std::string text;
  for (const auto& element : value) text += (text.empty() ? "[" : ", ") + numbers_text(element, digits);
  return text + "]";
}

// A figure ({"value", "unit", "uncertainty"}, the value a number or an array of them) as
// "v ± u unit"; one the data could not give (value null, with its "reason") as "not measured
// (reason)"; a plain number to 9 digits as a figure's; other values as they read.
std::string value_text(const nlohmann::json& value) {
  if (is_figure(value) && value.at("value").is_null()) {
    const auto reason = value.find("reason");
    return reason != value.end() && reason->is_string() ? "not measured (" + reason->get<std::string>() + ")"
                                                        : "not measured";
  }
  if (is_figure(value)) {
    std::string text = numbers_text(value.at("value"), 9);
    if (value.contains("uncertainty")) text += " ± " + numbers_text(value.at("uncertainty"), 3);
    const auto unit = value.at("unit").get<std::string>();
    if (unit != "1") text += " " + unit;
    return text;
  }
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "yes" : "no";
  if (value.is_number_float()) return numbers_text(value, 9);  // as a figure's value reads
  return json_text(value);
}

bool is_nested_rows(const nlohmann::json& value) {
  return value.is_array() && !value.empty() && std::all_of(value.begin(), value.end(), [](const nlohmann::json& element) {
           return element.is_object() && !is_figure(element);
         });
}

// The rows of a table, a row a line `indent` deep: a figure as it reads, another object as its cells
// "key value" (keys in JSON order); a cell that is a table of its own (threshold's points of each
// direction) follows its row, a row a line, deeper (it was printed as raw JSON).
std::string rows_text(const nlohmann::json& rows, std::size_t indent) {
  std::string text;
  for (const auto& row : rows) {
    std::string line;
    std::string nested;
    if (row.is_object() && !is_figure(row)) {
      for (const auto& [key, cell] : row.items()) {
        if (is_nested_rows(cell)) {
          line += (line.empty() ? "" : ", ") + fmt::format("{} ({} below)", key, cell.size());
          nested += fmt::format("{}{}:\n", std::string(indent + 2, ' '), key) + rows_text(cell, indent + 4);
        } else {
          line += (line.empty() ? "" : ", ") + key + " " + value_text(cell);
        }
      }
    } else {
      // A figure with members of its own says what it is of first (bias stability: "smoothing_s 10: ...").
      if (row.is_object()) {
        for (const auto& [key, cell] : row.items()) {
          if (key != "value" && key != "unit" && key != "uncertainty" && key != "measured" && key != "reason") {
            line += (line.empty() ? "" : ", ") + key + " " + value_text(cell);
          }
        }
      }
      line += (line.empty() ? "" : ": ") + value_text(row);
    }
    text += std::string(indent, ' ') + line + "\n" + nested;
  }
  return text;
}

// A table field: its label, then its rows.
std::string table_text(const FieldSpec& field, const nlohmann::json& rows) {
  return fmt::format("  {}\n", field.label_en) + rows_text(rows, 4);
}

// A field whose value is an object (figures by name, or objects of them): its label, then a member
// a line, nested objects indented under their key.
std::string object_text(const std::string& label, const nlohmann::json& object, std::size_t depth) {
  std::string text = fmt::format("{}{}\n", std::string(2 * depth, ' '), label);
  for (const auto& [key, member] : object.items()) {
    if (member.is_object() && !is_figure(member)) {
      text += object_text(key, member, depth + 1);
    } else {
      text += fmt::format("{}{:<24} {}\n", std::string(2 * depth + 2, ' '), key, value_text(member));
    }
  }
  return text;
}

}  // namespace

std::string procedure_text(const ProcedureSpec& spec, const nlohmann::json& fields) {
  std::string text = fmt::format("{} ({})\n", spec.title, fields.value("clause", spec.clause));
  for (const FieldSpec& field : spec.fields) {
    if (field.role == FieldRole::hidden || !fields.contains(field.name) || fields.at(field.name).is_null()) continue;
    const nlohmann::json& value = fields.at(field.name);
    if (field.role == FieldRole::table && value.is_array()) {
      text += table_text(field, value);
    } else if (field.role == FieldRole::curve && value.is_array()) {
      text += fmt::format("  {:<32} {} points (plotted in the report)\n", field.label_en, value.size());
    } else if (value.is_object() && !is_figure(value)) {
      text += object_text(field.label_en, value, 1);
    } else {
      const auto word = field.value_words.find(value.dump());
      text += fmt::format("  {:<32} {}\n", field.label_en,
                          word == field.value_words.end() ? value_text(value) : word->second);
    }
  }
  if (fields.contains("warnings")) {
    for (const auto& warning : fields.at("warnings")) text += "  warning: " + warning.get<std::string>() + "\n";
  }
  return text;
}

std::string procedure_text(const ProcedureSpec& spec, const ProcedureOutput& output) {
  return output.text.empty() ? procedure_text(spec, output.fields) : output.text;
}

}  // namespace inertest
