#include "inertest/campaign/campaign.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <fmt/format.h>
#include <toml++/toml.h>

#include "campaign/plan_table.h"
#include "campaign/step_registry.h"
#include "inertest/core/error.h"
#include "inertest/core/figure.h"
#include "inertest/core/instrument_id.h"
#include "inertest/core/json_text.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/core/records_read.h"
#include "inertest/core/sha256.h"
#include "inertest/core/units.h"
#include "inertest/io/atomic_write.h"
#include "inertest/version.h"

namespace inertest {
namespace {

using campaign::PlanContext;
using campaign::PlanTable;

// A specification limit on one figure of a procedure's result (IEEE Std 952-1997 specification
// format: "bias stability at most 0.01 deg/h"). `figure` is a key of the result or a JSON pointer
// into it (e.g. "/bias_stability/1"). `max` alone bounds the magnitude |value|, as a specification
// "bias <= 0.05 deg/h" or "misalignment <= 1'" does (judged on the signed value, a bias of -7000
// deg/h passed it); `min` alone bounds the signed value from below, and `min` with `max` the signed
// value on both sides (a scale factor's range).
struct Limit {
  std::string figure;
  std::optional<double> min;
  std::optional<double> max;
  std::string unit;  // empty: the figure's own unit
  SourceLocation where;
  // Set by check_declared_figures: the declared field the key is, so a result without it (or with
  // it null) is a figure the data could not give: judged "not measured", FAIL.
  std::optional<FieldSpec> declared;
  // A declared plain number (a count such as run_count): judged as it is, without a unit.
  bool plain_number = false;
  // The step's own specification (PreparedAction::limits, FieldSpec::states_verdict), not the plan's
  // [procedure.limits]: judged where the result gives the figure, no verdict where it leaves it out.
  bool stated = false;
  // A yes/no (1 or 0, judged against 1): the step's own pass/fail, a verdict field or a check by eye.
  bool yes_no = false;
};

struct PreparedStep {
  std::string name;
  std::string kind;
  std::vector<Limit> limits;
  campaign::StepAction action;
  nlohmann::json parameters;  // of a declared procedure, by name (PreparedAction)
  SourceLocation where;  // the [[procedure]] table, for errors from data that carry no location
  std::vector<std::string> records_read;  // the record files its preparation opened (RecordsRead)
};

struct Plan {
  std::string path;
  nlohmann::json header;  // [plan] title, date, operator ... as given
  PlanContext context;
  std::vector<PreparedStep> steps;
  campaign::PlanTable::DataFiles data_files;  // every data file the steps read, where each is named
};

toml::table parse_toml(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw Error(SourceLocation{path, 0, 0}, "plan file not found");
  try {
    return toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    const auto& begin = e.source().begin;
    throw Error(SourceLocation{path, static_cast<std::size_t>(begin.line), static_cast<std::size_t>(begin.column)},
                std::string(e.description()));
  }
}

std::vector<Limit> read_limits(PlanTable& step) {
  std::vector<Limit> limits;
  auto table = step.optional_table("limits");
  if (!table) return limits;
  // In the plan's order (toml++ iterates keys sorted), so verdicts follow the plan.
  std::vector<std::pair<std::string, const toml::node*>> entries;
  for (const auto& [key, node] : table->raw()) entries.emplace_back(std::string(key.str()), &node);
  std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    const auto& x = a.second->source().begin;
    const auto& y = b.second->source().begin;
    return x.line != y.line ? x.line < y.line : x.column < y.column;
  });
  for (const auto& [figure, node] : entries) {
    auto limit_table = table->optional_table(figure);
    Limit limit;
    limit.figure = figure;
    limit.min = limit_table->optional_number("min");
    limit.max = limit_table->optional_number("max");
    limit.unit = limit_table->string_or("unit", "");
    const auto& begin = node->source().begin;
    limit.where = {step.plan_path(), static_cast<std::size_t>(begin.line), static_cast<std::size_t>(begin.column)};
    if (!limit.min && !limit.max) limit_table->fail("a limit needs 'min', 'max' or both");
    // A limit no figure can meet, or every figure meets, is a mistake in the plan, not a verdict.
    for (const auto& [key, bound] : {std::pair{"min", limit.min}, std::pair{"max", limit.max}}) {
      if (bound && !std::isfinite(*bound)) limit_table->fail_at(key, "must be a finite number (not nan or inf)");
    }
    if (limit.min && limit.max && *limit.min > *limit.max) {
      limit_table->fail_at("min", fmt::format("({}) is above 'max' ({}): no value meets the limit", *limit.min, *limit.max));
    }
    if (limit.max && !limit.min && *limit.max < 0.0) {
      limit_table->fail_at("max", fmt::format("({}) alone bounds the magnitude and cannot be negative (a signed range "
                                              "takes 'min' too)", *limit.max));
    }
    if (figure.front() == '/') {
      try {
        const nlohmann::json::json_pointer pointer(figure);
      } catch (const nlohmann::json::exception&) {
        throw Error(limit.where, "limit on '" + figure +
                                     "': not a valid JSON pointer (RFC 6901: '~' must be followed by '0' or '1')");
      }
    }
    if (!limit.unit.empty()) {
      try {
        Unit::parse(limit.unit);
      } catch (const Error& e) {
        limit_table->fail_at("unit", e.message());
      }
    }
    limit_table->require_all_used();
    limits.push_back(std::move(limit));
  }
  return limits;
}

// The reference tokens of a JSON pointer ("/a/b~1c" -> a, b/c); a key alone is one token.
std::vector<std::string> pointer_tokens(const std::string& figure) {
  if (figure.front() != '/') return {figure};
  std::vector<std::string> tokens;
  nlohmann::json::json_pointer pointer(figure);  // its syntax was checked by read_limits
  while (!pointer.empty()) {
    tokens.insert(tokens.begin(), pointer.back());
    pointer.pop_back();
  }
  return tokens;
}

// A limit on an array figure (a triad's [x, y, z], a 3x3 matrix) names one element, as the report
// lists it and the archive keeps it: "/accelerometer/bias/value/0", "/gyro/misalignment/value/0/1".
// Anything else under a field that holds array figures (the triad, a whole vector) is a plan error.
void check_array_figure_limit(const FieldSpec& field, const std::vector<std::string>& tokens, const Limit& limit) {
  std::string elements;
  for (const auto& [member, rank] : field.array_figures) {
    elements += fmt::format("{}'/{}/{}/value/I{}'", elements.empty() ? "" : ", ", field.name, member,
                            rank == 2 ? "/J" : "");
  }
  const auto refuse = [&](const std::string& what) {
    throw Error(limit.where, "limit on '" + limit.figure + "': " + what + "; a limit names one element: " + elements +
                                 " with I" + (elements.find("/J") != std::string::npos ? " and J" : "") +
                                 " in 0, 1, 2 (x, y, z), as the report lists them");
  };
  if (tokens.size() < 2) refuse("'" + field.name + "' holds array figures, not one figure");
  const auto member = field.array_figures.find(tokens[1]);
  if (member == field.array_figures.end()) return;  // another member: judged as it is found
  const std::size_t rank = static_cast<std::size_t>(member->second);
  if (tokens.size() == 2 || tokens[2] != "value" || tokens.size() != 3 + rank) {
    refuse(fmt::format("'/{}/{}' is {} figure", field.name, tokens[1], rank == 2 ? "a 3x3 (matrix)" : "an [x, y, z] (vector)"));
  }
  for (std::size_t i = 3; i < tokens.size(); ++i) {
    if (tokens[i] != "0" && tokens[i] != "1" && tokens[i] != "2") refuse("no element '" + tokens[i] + "'");
  }
}

// A step's limits are checked against its declared fields (a procedure's, or the figures a special
// step declares: PreparedAction::figures) before anything runs: a limit on a key (or a JSON
// pointer's first key) it never reports, or on a key whose value is not a figure or a number (a
// text, a list of rows), is a plan error at the limit; so is a unit on a plain number (it has none)
// and a limit on a whole array figure.
void check_declared_figures(const std::vector<FieldSpec>& fields, PreparedStep& step) {
  for (Limit& limit : step.limits) {
    const bool pointer = limit.figure.front() == '/';
    const std::vector<std::string> tokens = pointer_tokens(limit.figure);
    const std::string key = tokens.empty() ? "" : tokens.front();
    const auto field = std::find_if(fields.begin(), fields.end(),
                                    [&](const FieldSpec& declared) { return declared.name == key; });
    if (field == fields.end()) {
      std::string known;
      for (const FieldSpec& declared : fields) known += (known.empty() ? "" : ", ") + declared.name;
      throw Error(limit.where, "limit on '" + limit.figure + "': procedure '" + step.name +
                                   "' reports no such figure (it reports: " + known + ")");
    }
    const bool measurable = field->value == FieldValue::figure || field->value == FieldValue::number ||
                            field->value == FieldValue::whole_number || field->value == FieldValue::structured;
    if (!pointer && !measurable) {
      throw Error(limit.where, "limit on '" + limit.figure + "': procedure '" + step.name + "' reports it as " +
                                   (field->value == FieldValue::rows ? "a list of rows (name one with a JSON pointer, "
                                                                       "e.g. '/" + key + "/0/...')"
                                                                     : "a text or a yes/no, not a figure or a number"));
    }
    limit.declared = *field;
    if (!field->array_figures.empty()) check_array_figure_limit(*field, tokens, limit);
    const bool number = field->value == FieldValue::number || field->value == FieldValue::whole_number;
    if (number && tokens.size() == 1) {
      if (!limit.unit.empty()) {
        throw Error(limit.where, "limit on '" + limit.figure + "': procedure '" + step.name +
                                     "' reports it as a plain number without a unit: give the limit without 'unit'");
      }
      limit.plain_number = true;
    }
  }
}

// A limit in a unit the figure's does not convert to (a delay in ppm, a scale factor in deg/s) is a
// plan error at the limit, as soon as the figure's declared unit is known (declared_unit: a fixed
// one at once, one made of the parameters once the step has read them); it failed only after the
// step had run.
void check_limit_units(const PreparedStep& step) {
  for (const Limit& limit : step.limits) {
    if (limit.unit.empty() || limit.plain_number || !limit.declared) continue;
    const std::optional<std::string> unit = declared_unit(*limit.declared, step.parameters);
    if (!unit) continue;
    try {
      convert(1.0, *unit, limit.unit);
    } catch (const Error& e) {
      throw Error(limit.where, "limit on '" + limit.figure + "': procedure '" + step.name + "' reports it in '" + *unit +
                                   "': " + e.message());
    }
  }
}

// A limit on a row of a table with one row per element of a list parameter names one of them:
// "/bias_stability/5" with three smoothing times, or "/bias_stability/x", is a plan error at the
// limit once the step's parameters are read; it was found only after the step had run.
void check_limit_rows(const PreparedStep& step) {
  for (const Limit& limit : step.limits) {
    if (!limit.declared || limit.declared->one_row_per.empty() || limit.figure.front() != '/') continue;
    const std::vector<std::string> tokens = pointer_tokens(limit.figure);
    const auto list = step.parameters.find(limit.declared->one_row_per);
    if (tokens.size() < 2 || list == step.parameters.end() || !list->is_array()) continue;
    const std::string& row = tokens[1];
    const bool number = !row.empty() && row.size() <= 9 && std::all_of(row.begin(), row.end(), [](char c) {
      return c >= '0' && c <= '9';
    }) && (row == "0" || row.front() != '0');
    if (!number || std::stoul(row) >= list->size()) {
      throw Error(limit.where, fmt::format("limit on '{}': procedure '{}' reports {} rows of '{}', one per {} ({}), "
                                           "numbered from 0: '{}' is none of them",
                                           limit.figure, step.name, list->size(), tokens.front(),
                                           limit.declared->one_row_per, list->dump(), row));
    }
  }
}

// The specification a step states itself, judged with the plan's limits (its verdicts count in the
// campaign's): a hand check's min and max, a pass/fail check's "pass" (its figure 1, min 1), and a
// yes/no a procedure judges itself with (polarity's pass against `expected`). A failed insulation
// check or a reversed polarity left the campaign's verdict PASS.
void add_stated_limits(const std::vector<FieldSpec>& fields, const std::vector<campaign::StatedLimit>& stated,
                       PreparedStep& step) {
  const auto add = [&step](const std::string& figure, std::optional<double> min, std::optional<double> max,
                           const SourceLocation& where) -> Limit& {
    Limit& limit = step.limits.emplace_back();
    limit.figure = figure;
    limit.min = min;
    limit.max = max;
    limit.where = where;
    limit.stated = true;
    return limit;
  };
  for (const campaign::StatedLimit& own : stated) add(own.figure, own.min, own.max, own.where).yes_no = own.yes_no;
  for (const FieldSpec& field : fields) {
    if (!field.states_verdict) continue;
    Limit& limit = add(field.name, 1.0, std::nullopt, step.where);
    limit.declared = field;
    limit.plain_number = true;
    limit.yes_no = true;
  }
}

Plan load_plan(const std::string& path) {
  const toml::table root = parse_toml(path);
  const std::string directory = std::filesystem::path(path).parent_path().string();
  PlanTable top(root, path, directory.empty() ? "." : directory, "plan");
  Plan plan;
  plan.path = path;

  auto header = top.optional_table("plan");
  auto instrument = top.optional_table("instrument");
  auto site = top.optional_table("site");
  auto steps = top.tables("procedure");
  top.require_all_used();

  if (header) {
    plan.header = nlohmann::json::object();
    for (const char* key : {"title", "operator", "station", "laboratory", "standard"}) {
      if (auto value = header->optional_string(key)) plan.header[key] = *value;
    }
    // results.json's tested_on, by which the archive orders campaigns: a real day, checked now.
    if (auto date = header->optional_date("date")) plan.header["date"] = *date;
    header->require_all_used();
  }

  if (!instrument) top.fail("missing [instrument] table");
  auto& in = plan.context.instrument;
  in.id = instrument->string("id");
  // The archive keys the instrument's campaigns by it: an id it refuses (run --archive wrote the
  // results, then refused them) or one with blanks around it ("FOG-001 ", an instrument of its own
  // that prints as FOG-001) is a plan error.
  if (const std::optional<std::string> problem = instrument_id_problem(in.id)) instrument->fail_at("id", *problem);
  in.type = instrument->string_or("type", "gyro");
  if (in.type != "gyro" && in.type != "accelerometer") instrument->fail_at("type", "must be \"gyro\" or \"accelerometer\"");
  in.output_unit = instrument->string_or("output_unit", "1");
  try {
    Unit::parse(in.output_unit);
  } catch (const Error& e) {
    instrument->fail_at("output_unit", e.message());
  }
  in.nominal_scale_factor = instrument->optional_number("nominal_scale_factor");
  in.sample_rate_hz = instrument->optional_number("sample_rate_hz");
  if (in.sample_rate_hz && *in.sample_rate_hz <= 0) instrument->fail_at("sample_rate_hz", "must be positive");
  instrument->require_all_used();

  if (site) {
    auto& s = plan.context.site;
    s.name = site->string_or("name", "");
    s.latitude_deg = site->optional_number("latitude_deg");
    if (s.latitude_deg && (*s.latitude_deg < -90 || *s.latitude_deg > 90)) {
      site->fail_at("latitude_deg", "must lie in [-90, 90]");
    }
    s.gravity_m_s2 = site->number_or("gravity_m_s2", 9.80665);
    if (s.gravity_m_s2 <= 0) site->fail_at("gravity_m_s2", "must be positive");
    s.heading_deg = site->number_or("heading_deg", 0.0);
    site->require_all_used();
  }

  if (steps.empty()) top.fail("no [[procedure]] tables: nothing to run");
  // Step names key the results, the verdicts and the archive's figures (PROCEDURE/FIGURE): two
  // steps of one name (two unnamed steps of one kind) would share their verdicts and could not be
  // archived, so the second is an error at its name (or its table), naming the first.
  std::map<std::string, SourceLocation> named;
  std::size_t index = 0;
  for (auto& step : steps) {
    ++index;
    PreparedStep prepared;
    prepared.kind = step.string("kind");
    prepared.name = step.string_or("name", prepared.kind);
    const SourceLocation name_at = step.location_of_key(step.contains("name") ? "name" : "kind");
    // The archive names a figure PROCEDURE/FIGURE, and the report and the verdicts print the name.
    if (prepared.name.empty() || prepared.name.find('/') != std::string::npos ||
        prepared.name.find_first_of(" \t") == 0 || prepared.name.find_last_of(" \t") == prepared.name.size() - 1) {
      step.fail_at("name", "must be a non-empty name without '/' and without blanks around it");
    }
    if (const auto [first, inserted] = named.emplace(prepared.name, name_at); !inserted) {
      throw Error(name_at, fmt::format("plan.procedure[{}]: a procedure named '{}' is already at {}{}: give each "
                                       "[[procedure]] a 'name' of its own (results, verdicts and the archive key "
                                       "figures by it)",
                                       index, prepared.name, first->second.to_string(),
                                       step.contains("name") ? "" : " (a step without 'name' is named by its kind)"));
    }
    const auto* preparer = campaign::find_step(prepared.kind);
    if (preparer == nullptr) {
      std::string known;
      for (const auto& k : campaign::registered_step_kinds()) known += (known.empty() ? "" : ", ") + k;
      step.fail_at("kind", "'" + prepared.kind + "' is not a known procedure (known: " + known + ")");
    }
    const auto& begin = step.raw().source().begin;
    prepared.where = {path, static_cast<std::size_t>(begin.line), static_cast<std::size_t>(begin.column)};
    prepared.limits = read_limits(step);
    const ProcedureSpec* spec = find_procedure_spec(prepared.kind);
    if (spec) check_declared_figures(spec->fields, prepared);
    check_limit_units(prepared);  // the fixed units, before the step's own keys are read
    RecordsRead records;
    campaign::PreparedAction action = (*preparer)(step, plan.context);
    prepared.records_read = records.paths();
    prepared.action = std::move(action.run);
    prepared.parameters = std::move(action.parameters);
    if (!spec) check_declared_figures(action.figures, prepared);
    check_limit_units(prepared);  // and those its parameters make
    check_limit_rows(prepared);
    add_stated_limits(spec ? spec->fields : action.figures, action.limits, prepared);
    step.require_all_used();
    plan.steps.push_back(std::move(prepared));
  }
  plan.data_files = top.data_files();
  return plan;
}

// When the results are processed, UTC ISO 8601 to the second. SOURCE_DATE_EPOCH (seconds since
// 1970, the reproducible-builds convention) overrides the clock, so that a run can be made
// byte-identical to another; the determinism tests set it.
std::string processing_time() {
  std::time_t seconds = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH"); epoch != nullptr && *epoch != '\0') {
    char* end = nullptr;
    const long long value = std::strtoll(epoch, &end, 10);
    if (*end != '\0' || value < 0) throw Error("SOURCE_DATE_EPOCH='" + std::string(epoch) + "': expected whole seconds since 1970");
    seconds = static_cast<std::time_t>(value);
  }
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}Z", utc.tm_year + 1900, utc.tm_mon + 1, utc.tm_mday,
                     utc.tm_hour, utc.tm_min, utc.tm_sec);
}

const nlohmann::json* find_figure(const nlohmann::json& result, const std::string& figure) {
  if (!figure.empty() && figure.front() == '/') {
    try {
      const nlohmann::json::json_pointer pointer(figure);  // its syntax was checked by read_limits
      return result.contains(pointer) ? &result.at(pointer) : nullptr;
    } catch (const nlohmann::json::exception&) {
      return nullptr;  // an array index beyond any size: no such figure
    }
  }
  return result.contains(figure) ? &result.at(figure) : nullptr;
}

// The verdict on a limit whose figure the data could not give (a smoothing time longer than half the
// record, a random walk coefficient of too short a record, a value that came out NaN): FAIL, with
// the reason, since a specification is met only by a measurement.
nlohmann::json not_measured_verdict(const Limit& limit, const std::string& step_name, const std::string& unit,
                                    const std::string& reason) {
  nlohmann::json verdict = {{"procedure", step_name}, {"figure", limit.figure}, {"value", nullptr},
                            {"unit", limit.unit.empty() ? unit : limit.unit},
                            {"pass", false},          {"measured", false},       {"reason", reason}};
  if (limit.min) verdict["min"] = *limit.min;
  if (limit.max) verdict["max"] = *limit.max;
  return verdict;
}

// An element of an array figure named by its pointer ("/accelerometer/bias/value/0"): the element
// with the figure's unit and the uncertainty at the same place; nothing when the pointer names none.
std::optional<Figure> array_figure_element(const nlohmann::json& result, const std::string& figure) {
  const std::size_t at = figure.rfind("/value/");
  if (figure.front() != '/' || at == std::string::npos) return std::nullopt;
  const nlohmann::json* parent = find_figure(result, figure.substr(0, at));
  const nlohmann::json* element = find_figure(result, figure);
  if (parent == nullptr || element == nullptr || !parent->is_object() || !parent->contains("unit") ||
      !parent->at("value").is_array() || !element->is_number()) {
    return std::nullopt;
  }
  Figure value{element->get<double>(), parent->at("unit").get<std::string>(), std::nullopt};
  if (const auto uncertainty = parent->find("uncertainty"); uncertainty != parent->end()) {
    const nlohmann::json::json_pointer place("/uncertainty" + figure.substr(at + 6));
    if (parent->contains(place) && parent->at(place).is_number()) value.uncertainty = parent->at(place).get<double>();
  }
  return value;
}

std::optional<nlohmann::json> check_limit(const Limit& limit, const std::string& step_name, const nlohmann::json& result) {
  const nlohmann::json* node = find_figure(result, limit.figure);
  const std::string key = pointer_tokens(limit.figure).front();
  if (limit.stated && (node == nullptr || node->is_null())) return std::nullopt;
  // A declared field the result leaves out or null: the data could not give it.
  if (limit.declared && (!result.contains(key) || result.at(key).is_null())) {
    return not_measured_verdict(limit, step_name, "", "the procedure could not give it (see its warnings)");
  }
  std::optional<Figure> element = array_figure_element(result, limit.figure);
  if (node != nullptr && node->is_object() && node->contains("value") && node->at("value").is_array()) {
    throw Error(limit.where, "limit on '" + limit.figure + "': an array figure; a limit names one element, e.g. '" +
                                 limit.figure + "/value/0'");
  }
  // A declared key holding a plain number (a count a field_from gives) is judged as one, as a
  // declared number field is; it has no unit to convert to.
  // A yes/no the procedure judges itself with (FieldSpec::states_verdict) is 1 or 0, as a hand check's.
  const bool yes_no = node != nullptr && node->is_boolean() && limit.stated;
  const bool plain = yes_no || (node != nullptr && node->is_number() &&
                                (limit.plain_number || (limit.declared && limit.figure.find('/', 1) == std::string::npos)));
  if (plain && !limit.unit.empty()) {
    throw Error(limit.where, "limit on '" + limit.figure + "': procedure '" + step_name +
                                 "' reports it as a plain number without a unit: give the limit without 'unit'");
  }
  if (!element && !plain &&
      (node == nullptr || !node->is_object() || !node->contains("value") || !node->contains("unit"))) {
    throw Error(limit.where, "limit on '" + limit.figure + "': procedure '" + step_name + "' reports no such figure");
  }
  // A figure that came out null (a row the data could not give, with its reason; NaN is written null)
  // is not measured.
  if (!element && !plain && node->at("value").is_null() && node->value("identified", true)) {
    return not_measured_verdict(limit, step_name, node->at("unit").get<std::string>(),
                                node->value("reason", std::string("the procedure gave no value")));
  }
  // A figure the analysis could not identify ({"value": null, "identified": false, "upper_bound"})
  // is judged by its upper bound: it passes a maximum the bound meets, and a minimum only at or below 0.
  const bool identified = element || plain || node->value("identified", true);
  const Figure figure = element  ? *element
                        : plain  ? Figure{yes_no ? (node->get<bool>() ? 1.0 : 0.0) : node->get<double>(), "", std::nullopt}
                        : identified ? node->get<Figure>()
                                     : Figure{node->at("upper_bound").get<double>(), node->at("unit").get<std::string>(),
                                              std::nullopt};
  const std::string unit = limit.unit.empty() ? figure.unit : limit.unit;
  double value = figure.value;
  try {
    if (!plain) value = convert(figure.value, figure.unit, unit);
  } catch (const Error& e) {
    throw Error(limit.where, "limit on '" + limit.figure + "': " + e.message());
  }
  const bool magnitude = limit.max && !limit.min;
  const double judged = magnitude ? std::abs(value) : value;
  // Not identified: the figure (a noise term, never negative) lies in [0, bound], inside a range whose
  // minimum is at most 0 and whose maximum the bound meets.
  const bool pass = identified ? (!limit.min || judged >= *limit.min) && (!limit.max || judged <= *limit.max)
                               : (!limit.min || *limit.min <= 0.0) && (!limit.max || value <= *limit.max);
  nlohmann::json verdict = {{"procedure", step_name}, {"figure", limit.figure}, {"value", value},
                            {"unit", unit},           {"pass", pass}};
  if (!identified) verdict["identified"] = false;  // value: the upper bound
  if (yes_no || limit.yes_no) verdict["yes_no"] = true;  // value 1 or 0, judged against 1
  if (magnitude && value < 0.0) verdict["magnitude"] = true;  // judged as |value|
  if (limit.min) verdict["min"] = *limit.min;
  if (limit.max) verdict["max"] = *limit.max;
  return verdict;
}

}  // namespace

nlohmann::json validate_plan(const std::string& plan_path) {
  const Plan plan = load_plan(plan_path);
  nlohmann::json steps = nlohmann::json::array();
  for (const auto& step : plan.steps) {
    // What each step will run with: its defaults and the [instrument]'s values applied (none for a
    // step that is no declared procedure).
    steps.push_back({{"name", step.name}, {"kind", step.kind}, {"parameters", step.parameters}});
  }
  return {{"instrument", plan.context.instrument.to_json()}, {"site", plan.context.site.to_json()}, {"procedures", steps}};
}

namespace {

// The outermost directory that creating `out` makes (empty when it exists): what a failed run
// removes again, and nothing else. The path is taken lexically normal, as it is written to: with
// "staging/../reports" the run writes into reports, which it did not make and must keep.
std::filesystem::path first_missing(const std::filesystem::path& out) {
  std::filesystem::path missing;
  for (std::filesystem::path p = out; !p.empty() && !std::filesystem::exists(p); p = p.parent_path()) {
    if (p == p.parent_path()) break;
    missing = p;
  }
  return missing;
}

// The records a step read (those its preparation and its run opened, listed files included), each
// named from the plan's directory (its whole path when it lies elsewhere) with its size and SHA-256:
// what a lab checks with `sha256sum`, and what the archive knows a reprocessing of the same records
// by (archive.cc, superseded figures). `digests` keeps each file's, for the steps that read it too.
nlohmann::json records_of(const Plan& plan, const std::vector<std::string>& prepared, const std::vector<std::string>& run,
                          std::map<std::string, FileDigest>& digests) {
  const std::filesystem::path plan_directory = std::filesystem::path(plan.path).parent_path().lexically_normal();
  std::vector<std::string> paths = prepared;
  for (const auto& path : run) {
    if (std::find(paths.begin(), paths.end(), path) == paths.end()) paths.push_back(path);
  }
  nlohmann::json records = nlohmann::json::array();
  for (const auto& path : paths) {
    auto known = digests.find(path);
    if (known == digests.end()) known = digests.emplace(path, file_sha256(path)).first;
    const FileDigest& digest = known->second;
    const std::filesystem::path relative =
        plan_directory.empty() ? std::filesystem::path(path) : std::filesystem::path(path).lexically_relative(plan_directory);
    const bool inside = !relative.empty() && *relative.begin() != "..";
    records.push_back({{"file", inside ? relative.generic_string() : path}, {"bytes", digest.bytes}, {"sha256", digest.sha256}});
  }
  return records;
}

// results.json of a run: the steps' results and verdicts under the plan's header.
nlohmann::json campaign_results(const Plan& plan, nlohmann::json procedures, nlohmann::json verdicts) {
  bool all_pass = true;
  for (const auto& v : verdicts) all_pass = all_pass && v.at("pass").get<bool>();
  const char* verdict = verdicts.empty() ? "NONE" : (all_pass ? "PASS" : "FAIL");
  // When the test was done (the plan's date, else the day it is processed) and when processed:
  // the archive orders a campaign's figures by the first and shows the second.
  const std::string processed_at = processing_time();
  const std::string tested_on = plan.header.is_object() && plan.header.contains("date")
                                    ? plan.header.at("date").get<std::string>()
                                    : processed_at.substr(0, 10);
  return {
      {"results_schema_version", 1},
      {"inertest_version", version()},
      {"tested_on", tested_on},
      {"processed_at", processed_at},
      {"plan", plan.header.is_null() ? nlohmann::json::object() : plan.header},
      {"instrument", plan.context.instrument.to_json()},
      {"site", plan.context.site.to_json()},
      {"procedures", std::move(procedures)},
      {"verdicts", std::move(verdicts)},
      {"verdict", verdict},
  };
}

// The data file of the plan, or the plan itself, that `path` is by any path to it, with where the
// plan names it; nullopt when it is none of them.
std::optional<std::pair<std::string, SourceLocation>> file_the_plan_reads(const Plan& plan,
                                                                          const std::filesystem::path& path) {
  const auto is_path = [&path](const std::string& file) {
    std::error_code error;  // equivalent() is false, with an error, when either does not exist
    return std::filesystem::equivalent(path, file, error);
  };
  for (const auto& data : plan.data_files) {
    if (is_path(data.first)) return data;
  }
  if (is_path(plan.path)) return std::pair{plan.path, SourceLocation{plan.path, 0, 0}};
  return std::nullopt;
}

// An export that would land on a data file of the plan (by any path to it) is an error at the
// export before anything runs: `--out .` with an export named as a record replaced the record, and
// a step that reads what an earlier step exports read the file of the run before (a plan's data
// are the files as they are when it starts).
void require_exports_replace_no_data(const Plan& plan, const std::filesystem::path& out, const nlohmann::json& earlier) {
  std::vector<std::pair<std::string, SourceLocation>> writes(plan.context.outputs.claims().begin(),
                                                             plan.context.outputs.claims().end());
  for (const char* own : {"results.json", "report.html"}) writes.emplace_back(own, SourceLocation{plan.path, 0, 0});
  // What an earlier run of this plan wrote there (its list; without one, its results and report).
  std::set<std::filesystem::path> ours;
  if (std::filesystem::is_regular_file(out / "results.json")) ours = {"results.json", "report.html"};
  if (!earlier.is_null()) {
    for (const auto& entry : earlier.at("files")) {
      if (entry.is_object() && entry.contains("path") && entry.at("path").is_string()) {
        ours.insert(std::filesystem::path(entry.at("path").get<std::string>()).lexically_normal());
      }
    }
  }
  for (const auto& [path, where] : writes) {
    const std::filesystem::path name = std::filesystem::path(path).lexically_normal();
    // The run's own bookkeeping: an export staged there was removed with it.
    if (name.begin()->string().starts_with(".inertest-")) {
      throw Error(where, "'" + path + "' is inside the run's own files (.inertest-exports, .inertest-written): give the "
                             "export another name");
    }
    if (const auto read = file_the_plan_reads(plan, out / path)) {
      throw Error(where, "the run would write '" + path + "' over '" + read->first + "', which the plan reads (at " +
                             read->second.to_string() + "): give the export another name, or the run another --out; "
                             "a step cannot read what another exports in the same run");
    }
    std::error_code error;  // (a directory there is the move's error, naming it)
    if (std::filesystem::exists(out / name, error) && !std::filesystem::is_directory(out / name, error) &&
        !ours.contains(name)) {
      throw Error(where, "the run would write '" + path + "' over '" + (out / name).string() +
                             "', which no earlier run of this plan wrote: give the export another name, or the run "
                             "another --out (or move that file away)");
    }
  }
}

// What a run wrote into its output directory, for the next run of the same plan there:
// {"plan": the plan file's canonical path, "files": [{"path" (relative), "size", "modified" (the
// file time's count)}]}.
constexpr const char* written_list = ".inertest-written";

// What names a campaign in an output directory: its instrument, and its plan's title and date.
std::string campaign_named(const nlohmann::json& instrument_id, const nlohmann::json& header) {
  const auto text = [](const nlohmann::json& v) { return v.is_string() ? v.get<std::string>() : std::string(); };
  const auto of_header = [&](const char* key) {
    return header.is_object() && header.contains(key) ? text(header.at(key)) : std::string();
  };
  return fmt::format("instrument '{}', title '{}', date '{}'", text(instrument_id), of_header("title"), of_header("date"));
}

std::string canonical_plan(const Plan& plan) {
  std::error_code error;
  const std::filesystem::path path = std::filesystem::weakly_canonical(plan.path, error);
  return error ? plan.path : path.string();
}

// The list of an earlier run in out, or null when there is none or it cannot be read (then nothing of
// it is removed).
nlohmann::json read_written_list(const std::filesystem::path& out) {
  std::ifstream in(out / written_list, std::ios::binary);
  if (!in) return nullptr;
  const nlohmann::json list = nlohmann::json::parse(in, nullptr, false);
  const bool usable = list.is_object() && list.contains("plan") && list.at("plan").is_string() &&
                      list.contains("files") && list.at("files").is_array();
  return usable ? list : nullptr;
}

// An output directory holding another campaign's results.json (another instrument, plan title or
// date, a results.json inertest did not write, or the results of another plan file) is refused
// before anything runs: the run would replace that campaign's results and report and leave its
// exports beside the new ones. A run of the same plan replaces its own: the earlier run's list is
// returned (null when it has none), for remove_earlier_files.
nlohmann::json earlier_run_of_this_plan(const Plan& plan, const std::filesystem::path& out) {
  const std::filesystem::path file = out / "results.json";
  if (!std::filesystem::is_regular_file(file)) return nullptr;
  std::string ours = campaign_named(plan.context.instrument.id, plan.header);
  std::string theirs;
  try {
    std::ifstream in(file, std::ios::binary);
    const nlohmann::json earlier = nlohmann::json::parse(in);
    theirs = campaign_named(earlier.at("instrument").at("id"), earlier.contains("plan") ? earlier.at("plan") : nlohmann::json());
  } catch (const nlohmann::json::exception&) {
    theirs = "not an inertest results file";
  }
  nlohmann::json list = read_written_list(out);
  if (theirs == ours && !list.is_null() && list.at("plan") != canonical_plan(plan)) {
    theirs += ", of the plan " + list.at("plan").get<std::string>();
    ours += ", of the plan " + canonical_plan(plan);
  }
  if (theirs != ours) {
    throw Error(SourceLocation{file.string(), 0, 0},
                "holds the results of another campaign (" + theirs + "; this one is " + ours +
                    "): give the run another --out, or move that directory's files away first");
  }
  return list;
}

// Removes what the earlier run of this plan wrote into out and this one did not (an export the plan
// no longer names), and only that: a plain relative path inside out, not a file the plan reads, and
// still the size and time the earlier run left it with (a file edited or replaced since is kept).
// Returns the paths removed.
std::vector<std::string> remove_earlier_files(const Plan& plan, const std::filesystem::path& out,
                                              const nlohmann::json& earlier, const std::vector<std::filesystem::path>& written) {
  std::vector<std::string> removed;
  if (earlier.is_null()) return removed;
  for (const auto& entry : earlier.at("files")) {
    if (!entry.is_object() || !entry.contains("path") || !entry.at("path").is_string()) continue;
    const std::filesystem::path name = std::filesystem::path(entry.at("path").get<std::string>()).lexically_normal();
    const bool inside = !name.empty() && name.is_relative() && *name.begin() != "..";
    if (!inside || std::find(written.begin(), written.end(), name) != written.end()) continue;
    const std::filesystem::path path = out / name;
    if (file_the_plan_reads(plan, path)) continue;
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) continue;
    const auto size = std::filesystem::file_size(path, error);
    if (error) continue;
    const auto modified = std::filesystem::last_write_time(path, error).time_since_epoch().count();
    if (error || entry.value("size", nlohmann::json()) != size || entry.value("modified", nlohmann::json()) != modified) {
      continue;  // edited or replaced since
    }
    if (std::filesystem::remove(path, error)) removed.push_back(path.string());
  }
  return removed;
}

// The list is written after the results are in place; one that cannot be written (a full disk) fails
// nothing: the next run of the plan then finds the last list, whose files it removes only as above.
void write_written_list(const Plan& plan, const std::filesystem::path& out, const std::vector<std::filesystem::path>& written) {
  nlohmann::json files = nlohmann::json::array();
  for (const auto& name : written) {
    std::error_code size_error;
    std::error_code time_error;
    const auto size = std::filesystem::file_size(out / name, size_error);
    const auto modified = std::filesystem::last_write_time(out / name, time_error).time_since_epoch().count();
    if (!size_error && !time_error) files.push_back({{"path", name.generic_string()}, {"size", size}, {"modified", modified}});
  }
  try {
    write_file_atomically((out / written_list).string(),
                          json_text(nlohmann::json{{"plan", canonical_plan(plan)}, {"files", files}}, 2) + "\n");
  } catch (const Error&) {
    // see above
  }
}

}  // namespace

CampaignSummary run_campaign(const std::string& plan_path, const std::string& out_dir, const CampaignOptions& options) {
  const Plan plan = load_plan(plan_path);
  // Everything the run writes (the steps' exports, results.json, the report) goes first into a
  // staging directory and is moved into the output directory once all of it is there: a failed
  // campaign leaves no partial output, overwrites nothing of an earlier run, and removes what it
  // made of the output directory's path (and only that).
  const std::filesystem::path out = std::filesystem::path(out_dir).lexically_normal();
  require_output_directory(out);
  const nlohmann::json earlier = earlier_run_of_this_plan(plan, out);
  require_exports_replace_no_data(plan, out, earlier);
  const std::filesystem::path made = first_missing(out);
  std::filesystem::create_directories(out);
  const std::filesystem::path staging = out / ".inertest-exports";
  std::filesystem::remove_all(staging);
  std::filesystem::create_directories(staging);
  campaign::StepRunContext context{options.progress, staging.string()};

  CampaignSummary summary;
  std::vector<std::filesystem::path> staged;
  try {
    nlohmann::json procedures = nlohmann::json::array();
    std::map<std::string, FileDigest> digests;  // of the records read, each file once
    nlohmann::json verdicts = nlohmann::json::array();
    for (std::size_t i = 0; i < plan.steps.size(); ++i) {
      const auto& step = plan.steps[i];
      if (options.progress) options.progress(step.name, static_cast<double>(i) / static_cast<double>(plan.steps.size()));
      nlohmann::json result;
      RecordsRead records;
      try {
        result = step.action(context);
      } catch (const Error& e) {
        // The place stays the data's (Python's Error.file, .line, .column were None); the step is named.
        throw Error(e.location() ? *e.location() : step.where, "procedure '" + step.name + "': " + e.message());
      }
      for (const auto& limit : step.limits) {
        if (std::optional<nlohmann::json> verdict = check_limit(limit, step.name, result)) verdicts.push_back(*verdict);
      }
      procedures.push_back({{"name", step.name},
                            {"kind", step.kind},
                            {"records", records_of(plan, step.records_read, records.paths(), digests)},
                            {"result", std::move(result)}});
    }
    summary.results = campaign_results(plan, std::move(procedures), std::move(verdicts));
    write_file_atomically((staging / "results.json").string(), json_text(summary.results, 2) + "\n");
    if (options.report_page) write_file_atomically((staging / "report.html").string(), options.report_page(summary.results));
    for (const auto& entry : std::filesystem::recursive_directory_iterator(staging)) {
      if (entry.is_regular_file()) staged.push_back(entry.path().lexically_relative(staging));
    }
    // results.json first, so that written_files.front() is it; the rest in the order found.
    std::stable_partition(staged.begin(), staged.end(), [](const auto& p) { return p == "results.json"; });
    move_staged_files(staging, out, staged);
  } catch (...) {
    std::filesystem::remove_all(made.empty() ? staging : made);
    throw;
  }
  for (const auto& relative : staged) summary.written_files.push_back((out / relative).string());
  std::filesystem::remove_all(staging);
  summary.removed_files = remove_earlier_files(plan, out, earlier, staged);
  write_written_list(plan, out, staged);
  if (options.progress) options.progress("done", 1.0);
  return summary;
}

std::vector<std::string> plan_kinds() { return campaign::registered_step_kinds(); }

}  // namespace inertest
