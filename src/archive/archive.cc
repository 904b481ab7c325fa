// The archive over either back-end: the schema and its migrations, reading a results.json into a
// campaign row and figure rows, and the queries. Every value reaches the SQL as a parameter.
#include "inertest/archive/archive.h"

#include <algorithm>
#include <cctype>
#include <csignal>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include <fast_float/fast_float.h>
#include <fmt/format.h>

#include "archive/database.h"
#include "inertest/core/calendar_date.h"
#include "inertest/core/error.h"
#include "inertest/core/instrument_id.h"
#include "inertest/core/json_text.h"
#include "inertest/core/sha256.h"
#include "inertest/core/units.h"

namespace inertest::archive {

// ---- Row accessors: SQLite hands back typed values, PostgreSQL text. ----

std::string Row::text(std::size_t i) const {
  const Value& v = columns.at(i);
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  if (const auto* d = std::get_if<double>(&v)) return fmt::format("{}", *d);
  if (const auto* n = std::get_if<std::int64_t>(&v)) return std::to_string(*n);
  return "";
}

double Row::real(std::size_t i) const {
  const Value& v = columns.at(i);
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* n = std::get_if<std::int64_t>(&v)) return static_cast<double>(*n);
  if (const auto* s = std::get_if<std::string>(&v)) {
    double value = 0.0;
    const auto [end, error] = fast_float::from_chars(s->data(), s->data() + s->size(), value);
    if (error == std::errc() && end == s->data() + s->size()) return value;
    throw DatabaseError("archive: '" + *s + "' is not a number");
  }
  throw DatabaseError("archive: a number is missing");
}

std::optional<double> Row::optional_real(std::size_t i) const {
  if (is_null(i)) return std::nullopt;
  return real(i);
}

std::int64_t Row::integer(std::size_t i) const {
  const Value& v = columns.at(i);
  if (const auto* n = std::get_if<std::int64_t>(&v)) return *n;
  if (const auto* s = std::get_if<std::string>(&v)) return std::stoll(*s);
  throw DatabaseError("archive: an integer is missing");
}

namespace {

// ---- Reading results.json ----

// The results_schema_version this inertest reads (campaign.cc writes it; absent means 1).
constexpr int results_schema_version = 1;

struct FigureRow {
  std::string procedure;
  std::string figure;
  std::optional<double> value;  // none: not measured (null in results.json)
  std::string unit;
  std::optional<double> uncertainty;
  std::optional<std::string> verdict;
  std::optional<double> lower_limit;
  std::optional<double> upper_limit;
  // Where a row of a table a limit names lies in it: the row's plain numbers ("smoothing_s = 10"),
  // none for a figure that is no such row or a row without them.
  std::optional<std::string> abscissa;
  // The records its step read: the SHA-256 of their sorted digests (records_identity); none when
  // the results name no records (inline data, results written before they did).
  std::optional<std::string> records;
};

struct CampaignRecord {
  CampaignEntry entry;
  std::string operator_name;
  std::string station;
  std::string inertest_version;
  std::string results_text;
  std::vector<FigureRow> figures;
};

[[noreturn]] void malformed(const std::string& source, const std::string& message) {
  throw Error(SourceLocation{source, 0, 0}, "not an inertest results file: " + message);
}

const nlohmann::json& member(const nlohmann::json& object, const char* key, nlohmann::json::value_t type,
                             const std::string& source, const std::string& where) {
  const auto it = object.find(key);
  const bool ok = it != object.end() && (it->type() == type || (type == nlohmann::json::value_t::number_integer &&
                                                                it->is_number_unsigned()));
  if (!ok) malformed(source, fmt::format("{}\"{}\" {}", where, key, it == object.end() ? "is missing" : "has the wrong type"));
  return *it;
}

std::optional<std::string> optional_string(const nlohmann::json& object, const char* key, const std::string& source) {
  const auto it = object.find(key);
  if (it == object.end() || it->is_null()) return std::nullopt;
  if (!it->is_string()) malformed(source, fmt::format("\"{}\" must be a string", key));
  return it->get<std::string>();
}

}  // namespace

// Exactly YYYY-MM-DD, a day of the Gregorian calendar: what sorts and compares as text (2026-13-45
// would sort, and mean nothing; "2026-04-04x" or a time after the day compared after the day itself).
bool is_test_date(const std::string& text) { return parse_calendar_date(text).has_value(); }

namespace {

// Results nest about ten levels (a procedure's result, a figure, a 3x3 value). The archive walks
// them recursively (collecting figures, dumping the JSON), so a file nested deeper than this is
// refused: 20 000 levels ran out of stack.
constexpr int max_results_nesting = 64;

// Whether node nests more than levels arrays or objects deep; recurses at most levels deep.
bool nested_deeper_than(const nlohmann::json& node, int levels) {
  if (!node.is_structured()) return false;
  if (levels == 0) return true;
  for (const auto& child : node) {
    if (nested_deeper_than(child, levels - 1)) return true;
  }
  return false;
}

// An instrument id names pages and routes of `inertest serve`: no control character, not made of
// dots only ("." and ".." are path segments a browser or a file system resolves), at most 256 bytes.
void check_instrument_id(const std::string& id, const std::string& source) {
  if (const std::optional<std::string> problem = instrument_id_problem(id)) malformed(source, "instrument: \"id\" " + *problem);
}

// One figure's value (a number, or the numbers of an array figure, e.g. a triad's [x, y, z] or a 3x3,
// each named by its path and its place in "value": "accelerometer/bias/value/0"), with the
// uncertainty at the same place.
void collect_values(const nlohmann::json& value, const nlohmann::json* uncertainty, const std::string& unit,
                    const std::string& procedure, const std::string& path, const std::string& source,
                    std::vector<FigureRow>& out) {
  if (value.is_array() && !value.empty()) {
    for (std::size_t i = 0; i < value.size(); ++i) {
      const nlohmann::json* element =
          uncertainty != nullptr && uncertainty->is_array() && i < uncertainty->size() ? &(*uncertainty)[i] : nullptr;
      collect_values(value[i], element, unit, procedure, fmt::format("{}/{}", path, i), source, out);
    }
    return;
  }
  // null: a figure the procedure could not compute (NaN is written null), archived as not measured.
  if (!value.is_number() && !value.is_null()) {
    malformed(source, "figure '" + procedure + "/" + path + "': \"value\" is not a number");
  }
  try {
    Unit::parse(unit);  // a unit nothing converts would fail every fleet and history of the figure
  } catch (const Error& e) {
    malformed(source, "figure '" + procedure + "/" + path + "': \"unit\" '" + unit + "': " + e.message());
  }
  FigureRow row;
  row.procedure = procedure;
  row.figure = path;
  if (value.is_number()) row.value = value.get<double>();
  row.unit = unit;
  // A 1-sigma uncertainty is a number of 0 or more (-5 was shown as "± -5", "0.001" dropped unsaid).
  if (uncertainty != nullptr && !uncertainty->is_null() &&
      !(uncertainty->is_number() && uncertainty->get<double>() >= 0.0)) {
    malformed(source, "figure '" + procedure + "/" + path + "': \"uncertainty\" is not a number of 0 or more");
  }
  if (uncertainty != nullptr && uncertainty->is_number()) row.uncertainty = uncertainty->get<double>();
  out.push_back(std::move(row));
}

// Every {"value": number (or array of numbers), "unit": string} object under result, named by its
// path of keys.
void collect_figures(const nlohmann::json& node, const std::string& procedure, const std::string& path,
                     const std::string& source, std::vector<FigureRow>& out) {
  if (!node.is_object()) return;
  if (node.contains("value") && node.contains("unit") && node.at("unit").is_string()) {
    const auto& value = node.at("value");
    const auto uncertainty = node.find("uncertainty");
    collect_values(value, uncertainty == node.end() ? nullptr : &*uncertainty, node.at("unit").get<std::string>(),
                   procedure, value.is_array() ? path + "/value" : path, source, out);
    return;
  }
  for (const auto& [key, child] : node.items()) {
    if (key.find('/') != std::string::npos) continue;  // not nameable as PROCEDURE/FIGURE
    collect_figures(child, procedure, path.empty() ? key : path + "/" + key, source, out);
  }
}

// The node a verdict's figure names in a result ("scale_factor", "/bias_stability/1"), or null: none
// there, or no JSON pointer into it (the campaign wrote the verdict).
const nlohmann::json* figure_at(const nlohmann::json& result, const std::string& figure) {
  try {
    const nlohmann::json::json_pointer pointer("/" + figure);
    return result.contains(pointer) ? &result.at(pointer) : nullptr;
  } catch (const nlohmann::json::exception&) {
    return nullptr;
  }
}

// The figures a limit names inside a list (a row of a table, e.g. "/bias_stability/1", bias
// stability at the second smoothing time): collect_figures leaves lists out (their rows are curves
// and tables, hundreds of points), but a figure the plan puts a limit on is archived wherever it is,
// so that its history and the archive's report show it with its limits. rows[first, end) are the
// procedure's figures collected already.
void collect_limited_figures(const nlohmann::json& result, const std::string& procedure,
                             const std::map<std::pair<std::string, std::string>, const nlohmann::json*>& verdicts,
                             std::size_t first, const std::string& source, std::vector<FigureRow>& rows) {
  const std::size_t end = rows.size();
  for (const auto& entry : verdicts) {
    const auto& key = entry.first;  // not a structured binding: the lambda below captures it
    if (key.first != procedure) continue;
    const auto collected = [&key](const FigureRow& row) { return row.figure == key.second; };
    if (std::any_of(rows.begin() + static_cast<std::ptrdiff_t>(first), rows.begin() + static_cast<std::ptrdiff_t>(end),
                    collected)) {
      continue;
    }
    const nlohmann::json* node = figure_at(result, key.second);
    if (node == nullptr || !node->is_object()) continue;
    const std::size_t row_figures = rows.size();
    collect_figures(*node, procedure, key.second, source, rows);
    // The row's plain numbers name its place (smoothing_s = 10); its flags and texts are results
    // (measured = false, a reason), which differ from test to test.
    std::string abscissa;
    for (const auto& [member, value] : node->items()) {
      if (member == "value" || member == "uncertainty" || !value.is_number()) continue;
      // As a double (10.0, as inertest writes it): 10 and 10.0 are one place (they were two quantities).
      abscissa += (abscissa.empty() ? "" : ", ") + member + " = " + nlohmann::json(value.get<double>()).dump();
    }
    if (abscissa.empty()) continue;
    for (std::size_t i = row_figures; i < rows.size(); ++i) rows[i].abscissa = abscissa;
  }
}

// A results.json as compared for identity: less the moment it was processed, every number a double
// (108 and 108.0 are one value).
nlohmann::json comparable_content(nlohmann::json results) {
  results.erase("processed_at");
  const auto as_doubles = [](auto& self, nlohmann::json& node) -> void {
    if (node.is_number_integer()) node = node.get<double>();
    if (!node.is_structured()) return;
    for (auto& child : node) self(self, child);
  };
  as_doubles(as_doubles, results);
  return results;
}

// What identifies the records a step read: the SHA-256 of their digests, sorted, one a line; none
// when it names none. Their names and order are left out: the same records moved, renamed or listed
// in another order (the runs of a temperature plan reordered, or given to their right temperatures
// after a mix-up) are the same test, processed again.
std::optional<std::string> records_identity(const nlohmann::json& procedure, const std::string& name,
                                            const std::string& source) {
  const auto it = procedure.find("records");
  if (it == procedure.end()) return std::nullopt;
  if (!it->is_array()) malformed(source, "procedure '" + name + "': \"records\" must be an array");
  std::set<std::string> sorted;
  for (const auto& record : *it) {
    const auto digest = record.is_object() ? record.find("sha256") : record.end();
    std::string hex = digest != record.end() && digest->is_string() ? digest->get<std::string>() : std::string();
    std::transform(hex.begin(), hex.end(), hex.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (hex.size() != 64 || hex.find_first_not_of("0123456789abcdef") != std::string::npos) {
      malformed(source, "procedure '" + name + "': each of \"records\" needs a \"sha256\" of 64 hex digits");
    }
    sorted.insert(hex);
  }
  if (sorted.empty()) return std::nullopt;
  std::string digests;
  for (const std::string& hex : sorted) digests += hex + "\n";
  return sha256_hex(digests);
}

CampaignRecord read_campaign(const nlohmann::json& results, const std::string& source) {
  using type = nlohmann::json::value_t;
  if (!results.is_object()) malformed(source, "expected a JSON object");
  if (nested_deeper_than(results, max_results_nesting)) {
    malformed(source, fmt::format("nested more than {} levels deep", max_results_nesting));
  }
  if (const auto it = results.find("results_schema_version"); it != results.end()) {
    if (!it->is_number_integer() || it->get<std::int64_t>() != results_schema_version) {
      throw Error(SourceLocation{source, 0, 0},
                  fmt::format("results_schema_version {} is not one this inertest reads ({})", it->dump(),
                              results_schema_version));
    }
  }
  CampaignRecord record;
  record.inertest_version = member(results, "inertest_version", type::string, source, "").get<std::string>();
  const auto& instrument = member(results, "instrument", type::object, source, "");
  record.entry.instrument = member(instrument, "id", type::string, source, "instrument: ").get<std::string>();
  check_instrument_id(record.entry.instrument, source);
  record.entry.verdict = member(results, "verdict", type::string, source, "").get<std::string>();
  if (record.entry.verdict != "PASS" && record.entry.verdict != "FAIL" && record.entry.verdict != "NONE") {
    malformed(source, "\"verdict\" must be PASS, FAIL or NONE, not '" + record.entry.verdict + "'");
  }
  const nlohmann::json plan = results.contains("plan") ? member(results, "plan", type::object, source, "")
                                                        : nlohmann::json::object();
  record.entry.title = optional_string(plan, "title", source).value_or("");
  record.operator_name = optional_string(plan, "operator", source).value_or("");
  record.station = optional_string(plan, "station", source).value_or("");
  record.entry.processed_at = optional_string(results, "processed_at", source).value_or("");
  // When the test was done: results.json "tested_on", else the plan's date, else the day it was
  // processed (results written before tested_on existed).
  record.entry.tested_on = optional_string(results, "tested_on", source)
                               .value_or(optional_string(plan, "date", source)
                                             .value_or(record.entry.processed_at.substr(0, std::min<std::size_t>(
                                                                                         10, record.entry.processed_at.size()))));
  if (!is_test_date(record.entry.tested_on)) {
    malformed(source, "the test date '" + record.entry.tested_on + "' is not YYYY-MM-DD (\"tested_on\" or plan \"date\")");
  }

  // Limits and verdicts, keyed by procedure and figure (a plan names a limit by key or JSON pointer).
  std::map<std::pair<std::string, std::string>, const nlohmann::json*> verdicts;
  if (results.contains("verdicts")) {
    for (const auto& verdict : member(results, "verdicts", type::array, source, "")) {
      if (!verdict.is_object()) malformed(source, "\"verdicts\": each entry must be an object");
      std::string figure = member(verdict, "figure", type::string, source, "verdicts: ").get<std::string>();
      if (!figure.empty() && figure.front() == '/') figure.erase(0, 1);
      verdicts[{member(verdict, "procedure", type::string, source, "verdicts: ").get<std::string>(), figure}] = &verdict;
      member(verdict, "pass", type::boolean, source, "verdicts: ");
    }
  }

  for (const auto& procedure : member(results, "procedures", type::array, source, "")) {
    if (!procedure.is_object()) malformed(source, "\"procedures\": each entry must be an object");
    const std::string name = member(procedure, "name", type::string, source, "procedures: ").get<std::string>();
    if (name.empty() || name.find('/') != std::string::npos) {
      malformed(source, "procedure name '" + name + "' is empty or contains '/'");
    }
    const nlohmann::json& result = member(procedure, "result", type::object, source, "procedure '" + name + "': ");
    const std::size_t first = record.figures.size();
    collect_figures(result, name, "", source, record.figures);
    collect_limited_figures(result, name, verdicts, first, source, record.figures);
    const std::optional<std::string> records = records_identity(procedure, name, source);
    for (std::size_t i = first; i < record.figures.size(); ++i) record.figures[i].records = records;
  }
  // One row per figure: two steps of one name (a plan's two steps of one kind, both named by it)
  // would store one figure twice, and which of the two a history shows would be chance.
  std::set<std::pair<std::string, std::string>> seen;
  for (const auto& row : record.figures) {
    if (!seen.emplace(row.procedure, row.figure).second) {
      const auto& procedures = results.at("procedures");
      const auto named = std::count_if(procedures.begin(), procedures.end(), [&](const nlohmann::json& p) {
        return p.is_object() && p.value("name", "") == row.procedure;
      });
      malformed(source, "figure '" + row.procedure + "/" + row.figure + "' appears twice" +
                            (named > 1 ? fmt::format(" ({} procedures are named '{}': give each step a name of its own)",
                                                     named, row.procedure)
                                       : std::string()));
    }
  }
  for (auto& row : record.figures) {
    const auto it = verdicts.find({row.procedure, row.figure});
    if (it == verdicts.end()) continue;
    const nlohmann::json& verdict = *it->second;
    row.verdict = verdict.at("pass").get<bool>() ? "PASS" : "FAIL";
    // The limits in the figure's unit (the plan may state them in another).
    const std::string limit_unit = verdict.value("unit", row.unit);
    for (const char* end : {"min", "max"}) {
      // A limit that is no number ("max": "inf") was dropped: the history showed no limit at all.
      if (verdict.contains(end) && !verdict.at(end).is_number()) {
        malformed(source, fmt::format("limit on '{}/{}': \"{}\" must be a number", row.procedure, row.figure, end));
      }
    }
    try {
      if (verdict.contains("min")) row.lower_limit = convert(verdict.at("min").get<double>(), limit_unit, row.unit);
      if (verdict.contains("max")) row.upper_limit = convert(verdict.at("max").get<double>(), limit_unit, row.unit);
    } catch (const Error& e) {
      malformed(source, "limit on '" + row.procedure + "/" + row.figure + "': " + e.message());
    }
    // As a plan refuses it: the fleet's capability of min 36001.8, max 35998.2 was Cp -854.8.
    if (row.lower_limit && row.upper_limit && *row.lower_limit > *row.upper_limit) {
      malformed(source, fmt::format("limit on '{}/{}': min {} is above max {}", row.procedure, row.figure,
                                    *row.lower_limit, *row.upper_limit));
    }
  }
  // A limit names a figure: one without its unit would not be archived, and its history would lose
  // that test without a word.
  for (const auto& entry : verdicts) {
    const auto& key = entry.first;  // not a structured binding: the lambda below captures it (clang)
    const bool archived = std::any_of(record.figures.begin(), record.figures.end(), [&key](const FigureRow& row) {
      return row.procedure == key.first && row.figure == key.second;
    });
    if (archived) continue;
    for (const auto& procedure : results.at("procedures")) {
      if (!procedure.is_object() || procedure.value("name", "") != key.first) continue;
      const nlohmann::json* node = procedure.contains("result") ? figure_at(procedure.at("result"), key.second) : nullptr;
      if (node != nullptr && node->is_object() && node->contains("value") && !node->contains("unit")) {
        malformed(source, "figure '" + key.first + "/" + key.second + "': a limit names it, but it has no \"unit\"");
      }
    }
  }

  // The identity is the content, less the moment it was processed: the same file added twice,
  // or the same records processed again by the same inertest, is one campaign.
  nlohmann::json content = results;
  content.erase("processed_at");
  record.entry.id = sha256_hex(json_text(content)).substr(0, 16);
  record.results_text = json_text(results);
  return record;
}

// ---- The schema. Migration i brings version i to version i + 1; never edit a released one. ----

const std::vector<std::vector<std::string>> migrations = {
    {
        // Version 1: campaigns stored whole, one row per figure.
        "CREATE TABLE campaign ("
        " id TEXT PRIMARY KEY,"
        " instrument TEXT NOT NULL,"
        " title TEXT NOT NULL,"
        " tested_on TEXT NOT NULL,"
        " processed_at TEXT NOT NULL,"
        " operator TEXT,"
        " station TEXT,"
        " verdict TEXT NOT NULL,"
        " inertest_version TEXT NOT NULL,"
        " results TEXT NOT NULL)",
        "CREATE INDEX campaign_by_instrument ON campaign (instrument, tested_on)",
        "CREATE TABLE figure ("
        " campaign TEXT NOT NULL REFERENCES campaign (id),"
        " procedure TEXT NOT NULL,"
        " figure TEXT NOT NULL,"
        " value DOUBLE PRECISION NOT NULL,"
        " unit TEXT NOT NULL,"
        " uncertainty DOUBLE PRECISION,"
        " verdict TEXT,"
        " lower_limit DOUBLE PRECISION,"
        " upper_limit DOUBLE PRECISION,"
        " PRIMARY KEY (campaign, procedure, figure))",
        "CREATE INDEX figure_by_name ON figure (procedure, figure)",
    },
    {
        // Version 2: a figure not measured (null in results.json) is a row with a null value. Both
        // back-ends rebuild the table (SQLite cannot drop a NOT NULL); fill_not_measured_figures then
        // adds the rows version 1 left out.
        "CREATE TABLE figure_v2 ("
        " campaign TEXT NOT NULL REFERENCES campaign (id),"
        " procedure TEXT NOT NULL,"
        " figure TEXT NOT NULL,"
        " value DOUBLE PRECISION,"
        " unit TEXT NOT NULL,"
        " uncertainty DOUBLE PRECISION,"
        " verdict TEXT,"
        " lower_limit DOUBLE PRECISION,"
        " upper_limit DOUBLE PRECISION,"
        " PRIMARY KEY (campaign, procedure, figure))",
        "INSERT INTO figure_v2 (campaign, procedure, figure, value, unit, uncertainty, verdict, lower_limit, upper_limit)"
        " SELECT campaign, procedure, figure, value, unit, uncertainty, verdict, lower_limit, upper_limit FROM figure",
        "DROP TABLE figure",
        "ALTER TABLE figure_v2 RENAME TO figure",
        "CREATE INDEX figure_by_name ON figure (procedure, figure)",
    },
    {
        // Version 3: where a limited row of a table lies in it (FigureRow::abscissa), so that rows
        // of one name at other places are not taken for one quantity; filled in from the stored
        // results (fill_from_stored_results).
        "ALTER TABLE figure ADD COLUMN abscissa TEXT",
    },
    {
        // Version 4: the records a figure's step read (FigureRow::records), and the campaign whose
        // later processing of them supersedes the row (DatabaseArchive::supersede). Archives of
        // version 3 stored no records: their rows supersede nothing and are superseded by nothing.
        "ALTER TABLE figure ADD COLUMN records TEXT",
        "ALTER TABLE figure ADD COLUMN superseded_by TEXT",
        "CREATE INDEX figure_by_records ON figure (records)",
    },
};
static_assert(schema_version == 4, "one migration per schema version");

void insert_figure(Database& db, const std::string& campaign, const FigureRow& row, bool unless_stored) {
  const auto optional = [](const auto& v) -> Value { return v ? Value(*v) : Value(std::monostate{}); };
  db.query(std::string("INSERT INTO figure (campaign, procedure, figure, value, unit, uncertainty, verdict, lower_limit,"
                       " upper_limit, abscissa, records) VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11)") +
               (unless_stored ? " ON CONFLICT DO NOTHING" : ""),
           {campaign, row.procedure, row.figure, optional(row.value), row.unit, optional(row.uncertainty),
            optional(row.verdict), optional(row.lower_limit), optional(row.upper_limit), optional(row.abscissa),
            optional(row.records)});
}

// What an archive of schema version `from` did not store, read again from each campaign's stored
// results, one campaign at a time: the figures not measured (version 1 left them out) and where a
// limited row lies in its table (version 3). A campaign today's checks refuse (an instrument id
// since made stricter), or stored results that are no JSON, keep the rows they have; a failure of
// the database is no such case: it fails the migration, which then changes nothing.
void fill_from_stored_results(Database& db, const std::string& location, std::int64_t from) {
  for (const auto& campaign : db.query("SELECT id FROM campaign ORDER BY id")) {
    const std::string id = campaign.text(0);
    const auto stored = db.query("SELECT results FROM campaign WHERE id = $1", {id});
    std::vector<FigureRow> figures;
    try {
      figures = read_campaign(nlohmann::json::parse(stored.front().text(0)), location).figures;
    } catch (const nlohmann::json::exception&) {
      continue;  // not JSON (stored by hand): nothing to read
    } catch (const Error&) {
      continue;  // refused today: its figures stay as they were
    }
    for (const auto& row : figures) {
      if (from < 2 && !row.value) insert_figure(db, id, row, true);
      if (from < 3 && row.abscissa) {
        db.query("UPDATE figure SET abscissa = $1 WHERE campaign = $2 AND procedure = $3 AND figure = $4",
                 {*row.abscissa, id, row.procedure, row.figure});
      }
    }
  }
}

// The schema version stored, 0 when none is; nullopt when the database has no schema_version table
// to ask (a new file or database, or another program's: refuse_foreign_database said which).
std::optional<std::int64_t> stored_schema_version(Database& db) {
  std::vector<Row> rows;
  try {
    rows = db.query("SELECT MAX(version) FROM schema_version");
  } catch (const DatabaseError& e) {
    // No such table (outside a transaction: nothing to roll back): SQLite's "no such table",
    // PostgreSQL's "relation ... does not exist". Anything else (a corrupt file: "database disk
    // image is malformed") is the error: read as no archive, the file was written to make one.
    const std::string& message = e.message();
    if (message.find("no such table") != std::string::npos || message.find("does not exist") != std::string::npos) {
      return std::nullopt;
    }
    throw;
  }
  return rows.empty() || rows.front().is_null(0) ? 0 : rows.front().integer(0);
}

void refuse_newer_schema(std::int64_t current, const std::string& location) {
  if (current > schema_version) {
    throw Error(SourceLocation{location, 0, 0},
                fmt::format("the archive's schema version is {}, newer than this inertest knows ({}): "
                            "use a newer inertest",
                            current, schema_version));
  }
}

// A read-only archive (Database::read_only) is read as it is: one of this version, or an error.
void check_read_only_schema(Database& db, const std::string& location) {
  const std::optional<std::int64_t> stored = stored_schema_version(db);
  if (!stored) throw Error(SourceLocation{location, 0, 0}, "holds no archive, and this process cannot write it to make one");
  const std::int64_t current = *stored;
  refuse_newer_schema(current, location);
  if (current < schema_version) {
    throw Error(SourceLocation{location, 0, 0},
                fmt::format("the archive's schema version is {} and this inertest reads {}; this process cannot write "
                            "the file or its directory to migrate it: open it once where it can",
                            current, schema_version));
  }
}

void migrate(Database& db, const std::string& location) {
  if (db.read_only()) return check_read_only_schema(db, location);
  // An archive at this version is opened without a write: a PostgreSQL role that may only read (a
  // lab's web view) opens it (CREATE TABLE IF NOT EXISTS alone needs the right to create).
  if (const std::optional<std::int64_t> stored = stored_schema_version(db)) {
    refuse_newer_schema(*stored, location);
    if (*stored == schema_version) return;
  }
  Transaction transaction(db, true);  // one process migrates; the others wait, then find it done
  db.query("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)");
  const std::int64_t current = stored_schema_version(db).value_or(0);
  refuse_newer_schema(current, location);
  for (std::int64_t version = current; version < schema_version; ++version) {
    for (const auto& statement : migrations[static_cast<std::size_t>(version)]) db.query(statement);
  }
  if (current > 0 && current < schema_version) fill_from_stored_results(db, location, current);
  if (current < schema_version) {
    db.query("DELETE FROM schema_version");
    db.query("INSERT INTO schema_version (version) VALUES ($1)", {std::int64_t{schema_version}});
  }
  transaction.commit();
}

// PROCEDURE/FIGURE split at the first '/'.
std::pair<std::string, std::string> split_figure(const std::string& name) {
  const auto slash = name.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == name.size()) {
    throw Error("figure '" + name + "': name it PROCEDURE/FIGURE as in results.json, e.g. scale_factor/scale_factor");
  }
  return {name.substr(0, slash), name.substr(slash + 1)};
}

// The archived figures (PROCEDURE/FIGURE) a message about one that is not names: the procedure's own
// when it is archived, else all, as a comma list of at most 20 and the count of the others.
std::string figures_to_name(const std::vector<std::string>& known, const std::string& procedure) {
  constexpr std::size_t kMostNamed = 20;
  const auto own = [&](const std::string& name) { return name.starts_with(procedure + "/"); };
  const bool procedure_known = std::any_of(known.begin(), known.end(), own);
  std::string names;
  std::size_t named = 0, others = 0;
  for (const std::string& name : known) {
    if (procedure_known && !own(name)) continue;
    if (named == kMostNamed) {
      ++others;
      continue;
    }
    names += (names.empty() ? "" : ", ") + name;
    ++named;
  }
  return others == 0 ? names : fmt::format("{} and {} more", names, others);
}

// Throws NotOneQuantity unless every row's unit (column 4) converts to the first's, and every row
// that says where it lies in its table (column 8, the abscissa; null where unknown: a campaign the
// migration could not read again) lies at one place.
void require_one_quantity(const std::vector<Row>& rows, const std::string& figure) {
  // Of one dimension is not enough: degC and K do not convert as bare temperatures (an absolute one
  // needs an offset a difference does not), and history, fleet and the report failed on them.
  // The units in groups that convert within: pulse/s/(deg/s) and pulse/ms/(deg/s) are one, V/(deg/s)
  // another (the message listed all as not converting to one another).
  std::vector<std::map<std::string, std::set<std::string>>> tests_by_unit_group;
  std::map<std::string, std::set<std::string>> tests_by_abscissa;
  for (const auto& row : rows) {
    const std::string unit = row.text(4);
    auto group = std::find_if(tests_by_unit_group.begin(), tests_by_unit_group.end(),
                              [&unit](const auto& units) { return converts(unit, units.begin()->first); });
    if (group == tests_by_unit_group.end()) group = tests_by_unit_group.emplace(tests_by_unit_group.end());
    (*group)[unit].insert(row.text(5) + " " + row.text(0));
    if (!row.is_null(8)) tests_by_abscissa[row.text(8)].insert(row.text(5) + " " + row.text(0));
  }
  // Each key with its first tests (a fleet's hundred would make the message a page long).
  const auto listed = [](const std::map<std::string, std::set<std::string>>& groups) {
    constexpr std::size_t kShown = 3;
    std::vector<std::string> texts;
    for (const auto& [key, members] : groups) {
      std::vector<std::string> shown(members.begin(), std::next(members.begin(), std::min(members.size(), kShown)));
      if (members.size() > kShown) shown.push_back(fmt::format("{} more", members.size() - kShown));
      texts.push_back(fmt::format("{} ({})", key, fmt::join(shown, ", ")));
    }
    return fmt::format("{}", fmt::join(texts, "; "));
  };
  if (tests_by_unit_group.size() > 1) {
    std::vector<std::string> groups;
    for (const auto& units : tests_by_unit_group) groups.push_back(fmt::format("[{}]", listed(units)));
    throw NotOneQuantity(fmt::format("figure '{}' is archived in units that do not convert to one another: {}; "
                                     "these cannot be charted as one figure (name the step differently in one kind "
                                     "of plan)",
                                     figure, fmt::join(groups, " and ")));
  }
  if (tests_by_abscissa.size() > 1) {
    throw NotOneQuantity(fmt::format("figure '{}' names rows at different places in their table: {}; these are different "
                                     "quantities under one name (the plans' tables differ, e.g. in their smoothing times)",
                                     figure, listed(tests_by_abscissa)));
  }
}

// Where the rows of a figure lie in their table (one place: require_one_quantity), if they say.
std::optional<std::string> place_of(const std::vector<Row>& rows) {
  for (const auto& row : rows) {
    if (!row.is_null(8)) return row.text(8);
  }
  return std::nullopt;
}

// Points converted into unit (the first point's), value and uncertainty alike.
FigurePoint point_from_row(const Row& row, const std::string& unit) {
  FigurePoint point;
  point.tested_on = row.text(0);
  point.value = row.optional_real(1);
  point.uncertainty = row.optional_real(2);
  point.campaign = row.text(3);
  point.instrument = row.text(5);
  const std::string row_unit = row.text(4);
  if (row_unit != unit) {
    if (point.value) point.value = convert(*point.value, row_unit, unit);
    if (point.uncertainty) point.uncertainty = std::abs(convert(*point.uncertainty, row_unit, unit) - convert(0.0, row_unit, unit));
  }
  return point;
}

// The limits of the latest test that set any, converted into unit (rows ordered by test date
// within an instrument; across instruments the latest date wins). A max alone bounds the magnitude,
// as the campaign judged it (campaign.cc: |value| <= max): the spec is then [-max, max], lower is
// -max and on_magnitude is set. Derived here, at query time, from the stored limits, so that
// campaigns archived before need no migration.
void take_limits(const std::vector<Row>& rows, const std::string& unit, std::optional<double>& lower,
                 std::optional<double>& upper, bool& on_magnitude) {
  std::string limits_tested_on;
  for (const auto& row : rows) {
    if ((row.is_null(6) && row.is_null(7)) || row.text(0) < limits_tested_on) continue;
    limits_tested_on = row.text(0);
    const std::string row_unit = row.text(4);
    const auto in_unit = [&](std::optional<double> v) -> std::optional<double> {
      return v ? std::optional<double>(convert(*v, row_unit, unit)) : std::nullopt;
    };
    lower = in_unit(row.optional_real(6));
    upper = in_unit(row.optional_real(7));
  }
  on_magnitude = upper && !lower && *upper >= 0.0;
  if (on_magnitude) lower = -*upper;
}

constexpr const char* figure_columns =
    "SELECT c.tested_on, f.value, f.uncertainty, c.id, f.unit, c.instrument, f.lower_limit, f.upper_limit, f.abscissa "
    "FROM figure f JOIN campaign c ON c.id = f.campaign WHERE f.superseded_by IS NULL ";

// Fault injection for the kill tests (archive_test.cc): INERTEST_ARCHIVE_KILL_AFTER_FIGURES=N
// makes an add kill its own process (SIGKILL: no clean-up, as a power cut or `kill -9`) after
// writing N figure rows inside its transaction (of all its files). -1 (unset) never.
long fault_injection_kill_after() {
  const char* value = std::getenv("INERTEST_ARCHIVE_KILL_AFTER_FIGURES");
  return value == nullptr ? -1 : std::strtol(value, nullptr, 10);
}

class DatabaseArchive final : public Archive {
 public:
  DatabaseArchive(std::unique_ptr<Database> db, const std::string& location) : db_(std::move(db)), location_(location) {
    migrate(*db_, location);
  }

  AddOutcome add(const nlohmann::json& results, const std::string& source) override {
    const CampaignRecord record = read_campaign(results, source);
    require_writable();
    Transaction transaction(*db_, true);
    long figures_written = 0;
    const AddOutcome outcome = insert(record, figures_written);
    transaction.commit();
    return outcome;
  }

  std::vector<AddOutcome> add_all(const std::vector<std::pair<nlohmann::json, std::string>>& files) override {
    std::vector<CampaignRecord> records;
    for (const auto& [results, source] : files) records.push_back(read_campaign(results, source));
    require_writable();
    std::vector<AddOutcome> outcomes;
    Transaction transaction(*db_, true);
    long figures_written = 0;
    for (const auto& record : records) outcomes.push_back(insert(record, figures_written));
    transaction.commit();
    return outcomes;
  }

  std::vector<CampaignEntry> list(const std::optional<std::string>& instrument) override {
    const std::string select = "SELECT id, instrument, title, tested_on, processed_at, verdict FROM campaign ";
    const std::string order = " ORDER BY tested_on, processed_at, id";
    const auto rows = instrument ? db_->query(select + "WHERE instrument = $1" + order, {*instrument})
                                 : db_->query(select + order);
    std::map<std::string, std::vector<std::string>> superseded;
    for (const auto& row : db_->query("SELECT DISTINCT campaign, superseded_by FROM figure WHERE superseded_by IS NOT NULL"
                                      " ORDER BY campaign, superseded_by")) {
      superseded[row.text(0)].push_back(row.text(1));
    }
    std::vector<CampaignEntry> entries;
    for (const auto& row : rows) {
      entries.push_back({row.text(0), row.text(1), row.text(2), row.text(3), row.text(4), row.text(5), superseded[row.text(0)]});
    }
    return entries;
  }

  FigureHistory history(const std::string& instrument, const std::string& figure) override {
    const auto parts = split_figure(figure);  // not a structured binding: the lambda below captures it
    const std::string& procedure = parts.first;
    const std::string& name = parts.second;
    const auto rows = db_->query(std::string(figure_columns) +
                                     "AND c.instrument = $1 AND f.procedure = $2 AND f.figure = $3"
                                     " ORDER BY c.tested_on, c.processed_at, c.id",
                                 {instrument, procedure, name});
    if (rows.empty()) {
      const auto known = db_->query(
          "SELECT DISTINCT f.procedure, f.figure FROM figure f JOIN campaign c ON c.id = f.campaign"
          " WHERE c.instrument = $1 AND f.superseded_by IS NULL ORDER BY f.procedure, f.figure",
          {instrument});
      if (known.empty() && db_->query("SELECT id FROM campaign WHERE instrument = $1", {instrument}).empty()) {
        throw Error("instrument '" + instrument + "' has no campaign in the archive");
      }
      std::vector<std::string> names;
      for (const auto& row : known) names.push_back(row.text(0) + "/" + row.text(1));
      throw Error("figure '" + figure + "' is not archived for instrument '" + instrument +
                  "' (archived: " + figures_to_name(names, procedure) + ")");
    }
    require_one_quantity(rows, figure);
    FigureHistory history{instrument, figure, rows.front().text(4), {}, place_of(rows), std::nullopt, std::nullopt, false};
    for (const auto& row : rows) history.points.push_back(point_from_row(row, history.unit));
    take_limits(rows, history.unit, history.lower_limit, history.upper_limit, history.limit_on_magnitude);
    return history;
  }

  FleetFigure fleet(const std::string& figure, const std::optional<std::string>& since) override {
    const auto [procedure, name] = split_figure(figure);
    const std::string where = "AND f.procedure = $1 AND f.figure = $2";
    const std::string order = " ORDER BY c.instrument, c.tested_on, c.processed_at, c.id";
    if (since && !is_test_date(*since)) throw Error("--since '" + *since + "': expected YYYY-MM-DD");
    const auto rows = since ? db_->query(std::string(figure_columns) + where + " AND c.tested_on >= $3" + order,
                                         {procedure, name, *since})
                            : db_->query(std::string(figure_columns) + where + order, {procedure, name});
    if (rows.empty()) {
      const std::vector<std::string> known = figures(false);
      if (std::find(known.begin(), known.end(), figure) != known.end()) {
        throw Error("figure '" + figure + "' has no test archived since " + since.value_or(""));
      }
      throw Error("figure '" + figure + "' is not archived" + (since ? " for tests since " + *since : std::string()) +
                  (known.empty() ? std::string() : " (archived: " + figures_to_name(known, procedure) + ")"));
    }
    require_one_quantity(rows, figure);
    FleetFigure fleet{figure, rows.front().text(4), {}, place_of(rows), std::nullopt, std::nullopt, false};
    for (const auto& row : rows) fleet.points.push_back(point_from_row(row, fleet.unit));
    take_limits(rows, fleet.unit, fleet.lower_limit, fleet.upper_limit, fleet.limit_on_magnitude);
    return fleet;
  }

  std::vector<std::string> figures(bool with_limits_only) override {
    const auto rows = db_->query(
        std::string("SELECT DISTINCT procedure, figure FROM figure WHERE superseded_by IS NULL") +
        (with_limits_only ? " AND (lower_limit IS NOT NULL OR upper_limit IS NOT NULL)" : "") +
        " ORDER BY procedure, figure");
    std::vector<std::string> names;
    for (const auto& row : rows) names.push_back(row.text(0) + "/" + row.text(1));
    return names;
  }

  nlohmann::json results(const std::string& id) override {
    const auto rows = db_->query("SELECT results FROM campaign WHERE id = $1", {id});
    if (rows.empty()) throw Error("campaign '" + id + "' is not in the archive");
    return nlohmann::json::parse(rows.front().text(0));
  }

  std::string backend() const override { return db_->backend(); }

 private:
  // Stores one campaign read and checked, inside the caller's transaction; nothing when the same
  // content is archived already. figures_written counts the figure rows of the transaction (for
  // the fault injection).
  AddOutcome insert(const CampaignRecord& record, long& figures_written) {
    AddOutcome outcome;
    outcome.id = record.entry.id;
    outcome.instrument = record.entry.instrument;
    // The same content with its numbers spelt otherwise (108 for 108.0, as jq rewrites a file) hashes
    // to another id: compared by value with the instrument's campaigns of that day, it is the one
    // archived (it was stored twice, and repeatability counted the test twice). The id stays the hash
    // of the text as written, so that the ids of archives already made stay theirs.
    const nlohmann::json content = comparable_content(nlohmann::json::parse(record.results_text));
    for (const Row& row : db_->query("SELECT id, results FROM campaign WHERE instrument = $1 AND tested_on = $2",
                                     {record.entry.instrument, record.entry.tested_on})) {
      if (comparable_content(nlohmann::json::parse(row.text(1))) == content) {
        outcome.id = row.text(0);
        return outcome;
      }
    }
    const auto inserted = db_->query(
        "INSERT INTO campaign (id, instrument, title, tested_on, processed_at, operator, station, verdict,"
        " inertest_version, results) VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10)"
        " ON CONFLICT (id) DO NOTHING RETURNING id",
        {record.entry.id, record.entry.instrument, record.entry.title, record.entry.tested_on,
         record.entry.processed_at, record.operator_name, record.station, record.entry.verdict,
         record.inertest_version, record.results_text});
    if (!inserted.empty()) {
      const long kill_after = fault_injection_kill_after();
      for (const auto& row : record.figures) {
        if (++figures_written > kill_after && kill_after >= 0) ::raise(SIGKILL);
        insert_figure(*db_, record.entry.id, row, false);
      }
      outcome.added = true;
      supersede(record, outcome);
    }
    return outcome;
  }

  // Marks, figure by figure, the earlier processing of the same records by a step of the same name
  // (same instrument) as superseded by the latest (Archive::add): the campaign just stored where it
  // was processed last (or in the same second), else the latest stored, which then supersedes the
  // new campaign's figure. A figure the latest does not state stays the one that does.
  void supersede(const CampaignRecord& record, AddOutcome& outcome) {
    const std::string& id = record.entry.id;
    std::set<std::pair<std::string, std::string>> steps;  // procedure, records
    for (const auto& row : record.figures) {
      if (row.records) steps.emplace(row.procedure, *row.records);
    }
    // The current rows of this step (same instrument, name and records) in the other campaigns ...
    const std::string current =
        "FROM figure g JOIN campaign c ON c.id = g.campaign WHERE c.instrument = $1 AND g.procedure = $2 AND "
        "g.records = $3 AND g.superseded_by IS NULL AND c.id <> $4";
    // ... of the figures the new campaign states, processed before it or in the same second;
    const std::string earlier =
        current + " AND c.processed_at <= $5 AND g.figure IN (SELECT figure FROM figure WHERE campaign = $4 AND "
                  "procedure = $2)";
    // ... and the latest processed after it that states the figure of the new campaign's row.
    const std::string latest =
        "(SELECT c.id " + current + " AND c.processed_at > $5 AND g.figure = figure.figure ORDER BY c.processed_at DESC, "
        "c.id LIMIT 1)";
    std::set<std::string> supersedes;
    std::set<std::string> superseded_by;
    for (const auto& [procedure, records] : steps) {
      const std::vector<Value> parameters = {record.entry.instrument, procedure, records, id, record.entry.processed_at};
      for (const auto& row : db_->query("SELECT DISTINCT c.id " + earlier, parameters)) supersedes.insert(row.text(0));
      db_->query("UPDATE figure SET superseded_by = $4 WHERE (campaign, procedure, figure) IN (SELECT g.campaign, "
                 "g.procedure, g.figure " + earlier + ")",
                 parameters);
      for (const auto& row : db_->query("SELECT DISTINCT " + latest + " FROM figure WHERE campaign = $4 AND procedure = $2"
                                        " AND " + latest + " IS NOT NULL",
                                        parameters)) {
        superseded_by.insert(row.text(0));
      }
      db_->query("UPDATE figure SET superseded_by = " + latest + " WHERE campaign = $4 AND procedure = $2 AND " + latest +
                     " IS NOT NULL",
                 parameters);
    }
    outcome.supersedes.assign(supersedes.begin(), supersedes.end());
    outcome.superseded_by.assign(superseded_by.begin(), superseded_by.end());
  }

  void require_writable() const {
    if (db_->read_only()) {
      throw Error(SourceLocation{location_, 0, 0},
                  "this process cannot write the archive (the file or its directory is read-only to it): nothing added");
    }
  }

  std::unique_ptr<Database> db_;
  std::string location_;
};

}  // namespace

nlohmann::json AddOutcome::to_json(const std::string& file) const {
  return {{"id", id},
          {"instrument", instrument},
          {"file", file},
          {"added", added},
          {"supersedes", supersedes},
          {"superseded_by", superseded_by}};
}

std::string AddOutcome::to_text(const std::string& file) const {
  std::string text = fmt::format("{} {} {} ({})", added ? "added  " : "already", id, instrument, file);
  if (!supersedes.empty()) {
    text += fmt::format("; supersedes {}, an earlier processing of the same records", fmt::join(supersedes, ", "));
  }
  if (!superseded_by.empty()) {
    text += fmt::format("; superseded by {}, a later processing of the same records", fmt::join(superseded_by, ", "));
  }
  return text;
}

nlohmann::json FigureHistory::to_json() const {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& p : points) {
    list.push_back({{"tested_on", p.tested_on},
                    {"value", p.value ? nlohmann::json(*p.value) : nlohmann::json(nullptr)},
                    {"uncertainty", p.uncertainty ? nlohmann::json(*p.uncertainty) : nlohmann::json(nullptr)},
                    {"campaign", p.campaign}});
  }
  const auto optional = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  nlohmann::json json = {{"instrument", instrument},         {"figure", figure},
                         {"unit", unit},                     {"points", std::move(list)},
                         {"lower_limit", optional(lower_limit)}, {"upper_limit", optional(upper_limit)},
                         {"limit_on_magnitude", limit_on_magnitude}};
  if (place) json["place"] = *place;
  return json;
}

void check_results(const nlohmann::json& results, const std::string& source) { read_campaign(results, source); }

bool is_server_location(const std::string& location) {
  return location.starts_with("postgresql://") || location.starts_with("postgres://");
}

std::unique_ptr<Archive> open_archive(const std::string& location, ArchiveOpening opening) {
  if (location.empty()) throw Error("archive: no location given (a file path or a postgresql:// URL)");
  const bool is_url = is_server_location(location);
  if (!is_url && opening == ArchiveOpening::existing && !std::filesystem::is_regular_file(location)) {
    throw Error(SourceLocation{location, 0, 0}, "no archive here (inertest archive add creates one)");
  }
  auto db = is_url ? open_postgresql(location) : open_sqlite(location);
  return std::make_unique<DatabaseArchive>(std::move(db), location);
}

void refuse_foreign_database(const std::vector<std::string>& tables, const std::string& location) {
  if (tables.empty() || std::find(tables.begin(), tables.end(), "schema_version") != tables.end()) return;
  std::string names;
  for (std::size_t i = 0; i < tables.size() && i < 5; ++i) names += (i == 0 ? "" : ", ") + tables[i];
  if (tables.size() > 5) names += ", ...";
  throw Error(SourceLocation{location, 0, 0},
              "not an inertest archive: the database holds other tables (" + names +
                  ") and no inertest schema; give a new file or an empty database");
}

std::string default_archive_location() {
  if (const char* db = std::getenv("INERTEST_DB"); db != nullptr && *db != '\0') return db;
  const char* home = std::getenv("HOME");
  if (home == nullptr || *home == '\0') throw Error("archive: neither --db, $INERTEST_DB nor $HOME is set");
  return std::string(home) + "/.local/share/inertest/archive.sqlite";
}

nlohmann::json read_results_file(const std::string& path) {
  if (std::filesystem::is_directory(path)) throw Error(SourceLocation{path, 0, 0}, "a directory, not a results.json");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(SourceLocation{path, 0, 0}, "cannot read the file");
  const std::string text{std::istreambuf_iterator<char>(file), {}};
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is 1-based: the offending byte. Count lines and columns up to it.
    const std::size_t end = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < end; ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    // "[json.exception.parse_error.101] parse error at line 1, column 9: <what>": the what, which
    // may quote the text read ("last read: 'N'").
    std::string message = e.what();
    if (const auto at = message.find("column "); at != std::string::npos) {
      if (const auto colon = message.find(": ", at); colon != std::string::npos) message = message.substr(colon + 2);
    }
    if (end < text.size() && (text[end] == 'N' || text[end] == 'I')) {
      message += " (JSON has no NaN or Infinity: null stands for a missing number)";
    }
    throw Error(SourceLocation{path, line, column}, "not valid JSON: " + message);
  } catch (const nlohmann::json::exception& e) {
    // A number beyond a double ("[json.exception.out_of_range.406] number overflow parsing
    // '1e400'"): a fault of the file, at the number's first place in it.
    std::string message = e.what();
    if (const auto bracket = message.find("] "); bracket != std::string::npos) message.erase(0, bracket + 2);
    std::size_t line = 0, column = 0;
    const auto quote = message.find('\'');
    const auto end_quote = quote == std::string::npos ? std::string::npos : message.find('\'', quote + 1);
    if (end_quote != std::string::npos) {
      if (const auto at = text.find(message.substr(quote + 1, end_quote - quote - 1)); at != std::string::npos) {
        line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
        const auto line_start = text.rfind('\n', at);
        column = at - (line_start == std::string::npos ? 0 : line_start + 1) + 1;
      }
    }
    throw Error(SourceLocation{path, line, column}, "not valid JSON: " + message);
  }
}

}  // namespace inertest::archive
