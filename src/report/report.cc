#include "inertest/report/report.h"

#include <fmt/format.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/io/atomic_write.h"
#include "inertest/io/output_record.h"
#include "report/figure_format.h"
#include "report/labels.h"
#include "report/procedure_plots.h"
#include "report/report_style.h"
#include "report/result_access.h"

namespace inertest::report {
namespace {

using nlohmann::json;

std::string html(const std::string& text) { return escape_xml(text); }

// An array too long to list figure by figure (a record or a curve): plotted, not listed.
bool is_long_array(const json& value) {
  constexpr std::size_t kMaxListed = 12;
  return value.is_array() && value.size() > kMaxListed;
}

// Members of a result that describe it rather than measure it, and members that hold curves and
// records (plotted, not listed): a key naming a curve, or a long array. (A declared procedure
// says which are which: FieldSpec::role.)
bool is_listed_member(const std::string& key, const json& value) {
  static const char* kMeta[] = {"procedure", "clause", "warnings", "method"};
  for (const char* meta : kMeta) {
    if (key == meta) return false;
  }
  static const char* kDataSuffixes[] = {"curve", "record", "points", "samples", "series", "sweep"};
  for (const std::string suffix : kDataSuffixes) {
    if (key.size() >= suffix.size() && key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0) {
      return false;
    }
  }
  return !is_long_array(value);
}

std::string escape_pointer_token(const std::string& token) {
  std::string out;
  for (char c : token) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

// One figure of a procedure's result: its JSON pointer inside the result and a readable name.
struct FigureRow {
  std::string pointer;
  std::string name;
  json figure;
  int depth = 0;         // tokens in the pointer
  bool headline = true;  // shown in the summary (not a detail of a fit, an influence study...)
  bool in_table = false;  // a cell of a declared table: in the figure tables only under a limit
};

// Members whose figures are details of the analysis: listed in the procedure's section only.
bool is_detail_member(const std::string& key) {
  static const char* kDetails[] = {"influence", "fit", "site", "slope_method", "harmonic_fit", "by_rate", "by_run"};
  for (const char* detail : kDetails) {
    if (key == detail) return true;
  }
  return false;
}

// The readable unit a key's suffix names ("smoothing_s" -> "s", "rate_dps" -> "°/s"), "" for none.
std::string unit_of_key(const std::string& key) {
  static const std::pair<const char*, const char*> kSuffixes[] = {{"_s", "s"},     {"_hz", "Hz"}, {"_deg", "°"},
                                                                  {"_dps", "°/s"}, {"_g", "g"},   {"_degC", "°C"}};
  std::string unit;
  for (const auto& [suffix, readable] : kSuffixes) {
    const std::string s(suffix);
    if (key.size() > s.size() && key.compare(key.size() - s.size(), s.size(), s) == 0) unit = readable;
  }
  return unit;
}

// "10 s, power -2" for a figure element that carries its abscissa, e.g. {"smoothing_s": 10, "value":
// ...}: a number with a unit in its key as that, one without under its key; "" when none.
std::string abscissa_of(const json& element) {
  std::string text;
  for (const auto& [key, value] : element.items()) {
    if (key == "value" || key == "uncertainty" || key == "upper_bound" || !value.is_number()) continue;
    const std::string unit = unit_of_key(key);
    if (!text.empty()) text += ", ";
    if (unit.empty()) text += key + " ";
    text += format_number(value.get<double>());
    if (!unit.empty()) text += " " + unit;
  }
  return text;
}

// " (10 s)" for a figure element that carries its abscissa (abscissa_of), "" for one without.
std::string qualifier_of(const json& element) {
  const std::string text = abscissa_of(element);
  return text.empty() ? text : " (" + text + ")";
}

bool is_number_member(const json& node, std::string_view key) {
  const auto* value = member(node, key);
  return value != nullptr && value->is_number();
}

// A verdict's measured value: the number, "not measured" for a figure the data could not give, or
// for a term the analysis could not identify, its upper bound as such (it was shown as a value).
std::string verdict_value_text(const json& verdict, const Labels& labels) {
  const auto* value = member(verdict, "value");
  if (value == nullptr || !value->is_number()) return labels("ui.not_measured");
  if (verdict.value("yes_no", false)) return labels(value->get<double>() == 1.0 ? "ui.yes" : "ui.no");
  const auto* identified = member(verdict, "identified");
  if (identified != nullptr && identified->is_boolean() && !identified->get<bool>()) {
    return labels("ui.not_identified") + " (< " + format_number(value->get<double>()) + ")";
  }
  return format_number(value->get<double>());
}

// One row per element of an array figure, named by its axes ("x", "xy"), its pointer the element's
// value; a matrix's elements held at zero by the figure's convention (zero with zero uncertainty,
// e.g. a misalignment's diagonal) are left out.
void collect_array_figure(const json& node, const std::string& pointer, const std::string& name, int depth,
                          bool headline, std::vector<FigureRow>& rows) {
  constexpr std::string_view kAxes = "xyz";
  const json& values = node.at("value");
  const json* uncertainties = member(node, "uncertainty");
  const auto add = [&](const json& value, const json* uncertainty, const std::string& axes, const std::string& path,
                       bool skip_fixed) {
    if (!value.is_number()) return;
    json figure = {{"value", value}, {"unit", node.at("unit")}};
    if (uncertainty != nullptr && uncertainty->is_number()) figure["uncertainty"] = *uncertainty;
    if (skip_fixed && value.get<double>() == 0.0 && figure.value("uncertainty", 0.0) == 0.0) return;
    rows.push_back({pointer + "/value" + path, name + " " + axes, std::move(figure), depth + 1, headline && depth + 1 <= 2});
  };
  const auto element = [](const json* array, std::size_t i) -> const json* {
    return array != nullptr && array->is_array() && i < array->size() ? &(*array)[i] : nullptr;
  };
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::string row_axis = i < kAxes.size() ? std::string(1, kAxes[i]) : std::to_string(i + 1);
    if (!values[i].is_array()) {
      add(values[i], element(uncertainties, i), row_axis, fmt::format("/{}", i), false);
      continue;
    }
    for (std::size_t j = 0; j < values[i].size(); ++j) {
      const std::string column_axis = j < kAxes.size() ? std::string(1, kAxes[j]) : std::to_string(j + 1);
      add(values[i][j], element(element(uncertainties, i), j), row_axis + column_axis, fmt::format("/{}/{}", i, j), true);
    }
  }
}

void collect_figures(const json& node, const std::string& pointer, const std::string& name, const Labels& labels,
                     int depth, bool headline, std::vector<FigureRow>& rows);

// The channels of one record (an IMU's axes, issue 19): each listed as a result of its own, under
// its name.
void collect_channels(const json& channels, const std::string& pointer, const std::string& name, const Labels& labels,
                      int depth, bool headline, std::vector<FigureRow>& rows) {
  for (const auto& [channel, result] : channels.items()) {
    collect_figures(result, pointer + "/" + escape_pointer_token(channel), name.empty() ? channel : name + " · " + channel,
                    labels, depth, headline, rows);
  }
}

// Results nest figures up to 6 levels (an IMU channel's PSD fit); the bound only stops runaway
// nesting, and says so in the report rather than dropping what lies below it.
constexpr int kMaxNesting = 32;

void collect_figures(const json& node, const std::string& pointer, const std::string& name, const Labels& labels,
                     int depth, bool headline, std::vector<FigureRow>& rows) {
  if (is_scalar_figure(node)) {
    rows.push_back({pointer, name, node, depth, headline && depth <= 2});
    return;
  }
  if (is_array_figure(node)) {
    collect_array_figure(node, pointer, name, depth, headline, rows);
    return;
  }
  if (depth >= kMaxNesting && (node.is_object() || node.is_array()) && !node.empty()) {
    rows.push_back({pointer, name, json{{"value", labels("ui.nested_too_deep")}, {"unit", ""}}, depth, false});
    return;
  }
  if (node.is_object()) {
    // In the order of the label table (scale factor before its nonlinearity...), then by name.
    std::vector<std::pair<std::size_t, std::string>> keys;
    for (const auto& [key, value] : node.items()) keys.emplace_back(Labels::rank(key), key);
    std::sort(keys.begin(), keys.end());
    for (const auto& [rank, key] : keys) {
      const json& value = node.at(key);
      if (key == "channels" && value.is_object()) {
        collect_channels(value, pointer + "/channels", name, labels, depth, headline, rows);
        continue;
      }
      if (!is_listed_member(key, value)) continue;
      const std::string label = labels(key);
      collect_figures(value, pointer + "/" + escape_pointer_token(key), name.empty() ? label : name + " · " + label,
                      labels, depth + 1, headline && !is_detail_member(key), rows);
    }
  } else if (node.is_array()) {
    // Arrays of figures are listed, each under its qualifier (" (10 s)") or number.
    const bool of_figures =
        std::all_of(node.begin(), node.end(), [](const json& e) { return is_figure(e) || is_unmeasured_figure(e); });
    for (std::size_t i = 0; i < node.size(); ++i) {
      if (of_figures) {
        const std::string qualifier = qualifier_of(node[i]);
        rows.push_back({fmt::format("{}/{}", pointer, i),
                        name + (qualifier.empty() ? fmt::format(" #{}", i + 1) : qualifier), node[i], depth + 1,
                        headline && depth + 1 <= 2});
        continue;
      }
      // Elements that name themselves ("name", "label", "position") are listed under their names,
      // the others under their place (" #2"): the peaks of a PSD, the points of a short sweep.
      std::string element = fmt::format("#{}", i + 1);
      for (const char* naming : {"name", "label", "position"}) {
        if (const auto* n = member(node[i], naming); n != nullptr && n->is_string()) element = n->get<std::string>();
      }
      collect_figures(node[i], fmt::format("{}/{}", pointer, i), name + " " + element, labels, depth + 1, headline,
                      rows);
    }
  }
}

// A declared table (FieldRole::table) as the report shows it: a row per element of the array, a
// column per member of the elements (a member object's members as "amplitudes/k0"; a figure, even
// a triad's, is one column), the element itself (column "") when it is a figure or a plain value.
// An array of objects inside a row is a table of its own (its cell counts its rows).
struct RowTable {
  struct Row {
    std::string pointer;             // the element's, e.g. "/sensors/0"
    std::string name;                // its naming member, its abscissa ("0.5 Hz") or its place ("#1")
    std::vector<const json*> cells;  // one per column, null where the element lacks the member
  };
  std::string pointer;  // the array's, e.g. "/sensors"
  std::string title;
  std::vector<std::string> columns;  // pointers inside an element, escaped ("residual_rms", "amplitudes/k0")
  std::vector<std::string> headings;
  std::vector<Row> rows;
};

// At most this many rows of a table are shown; the others are counted ("N more rows in results.json").
constexpr std::size_t kMaxTableRows = 40;

// The members whose text names an element in its table, in this order of preference.
constexpr const char* kNamingMembers[] = {"name", "label", "position", "supply", "sensor"};

bool is_figure_node(const json& node) {
  return is_scalar_figure(node) || is_array_figure(node);
}

// An array that is a table of its own inside a row: its elements are objects (figures or rows).
bool is_nested_table(const json& node) {
  return node.is_array() && !node.empty() && std::all_of(node.begin(), node.end(), [](const json& e) {
           return e.is_object();
         });
}

// The columns of one element, added in its order to those the elements before it gave.
void add_columns(const json& node, const std::string& prefix, int depth, std::vector<std::string>& columns) {
  const auto add = [&columns](const std::string& column) {
    if (std::find(columns.begin(), columns.end(), column) == columns.end()) columns.push_back(column);
  };
  if (!node.is_object() || (prefix.empty() && is_figure_node(node))) {
    add("");
    if (!node.is_object()) return;
  }
  for (const auto& [key, value] : node.items()) {
    if (prefix.empty() && is_figure_node(node) &&
        (key == "value" || key == "unit" || key == "uncertainty" || key == "identified" || key == "upper_bound" ||
         key == "measured")) {
      continue;
    }
    const std::string column = prefix + escape_pointer_token(key);
    if (value.is_object() && !value.empty() && !is_figure_node(value) && depth < kMaxNesting) {
      add_columns(value, column + "/", depth + 1, columns);
    } else {
      add(column);
    }
  }
}

const json* cell_of(const json& element, const std::string& column) {
  if (column.empty()) return &element;
  const json::json_pointer pointer("/" + column);
  return element.contains(pointer) ? &element.at(pointer) : nullptr;
}

// A member's heading: its label, with the unit its key names ("Frequency (Hz)" for "frequency_hz",
// "Smoothing (s)" for "smoothing_s"), since its cells are plain numbers.
std::string member_heading(const std::string& key, const Labels& labels) {
  const std::string unit = unit_of_key(key);
  if (unit.empty()) return labels(key);
  std::string label = labels(key);
  if (label == humanise_key(key)) label = humanise_key(key.substr(0, key.rfind('_')));
  return label + " (" + unit + ")";
}

// "Amplitudes · K0" for "amplitudes/k0"; the element itself is its "Value".
std::string heading_of(const std::string& column, const Labels& labels) {
  if (column.empty()) return labels("ui.value");
  std::string heading;
  for (json::json_pointer pointer("/" + column); !pointer.empty(); pointer.pop_back()) {  // tokens unescaped, last first
    heading = member_heading(pointer.back(), labels) + (heading.empty() ? "" : " · ") + heading;
  }
  return heading;
}

// An element's name in its table: its naming member, else its abscissa (a figure's qualifier, a
// number whose key names a unit: "0.5 Hz"), else its place "#1".
std::string row_name_of(const json& element, std::size_t index) {
  for (const char* naming : kNamingMembers) {
    if (const auto* n = member(element, naming); n != nullptr && n->is_string()) return n->get<std::string>();
  }
  if (is_figure_node(element)) {
    if (std::string abscissa = abscissa_of(element); !abscissa.empty()) return abscissa;
  } else if (element.is_object()) {
    for (const auto& [key, value] : element.items()) {
      if (const std::string unit = unit_of_key(key); !unit.empty() && value.is_number()) {
        return format_number(value.get<double>()) + " " + unit;
      }
    }
  }
  return fmt::format("#{}", index + 1);
}

// The table of the array at `pointer`, then the tables inside its rows, into `tables`.
void collect_tables(const json& array, const std::string& pointer, const std::string& title, const Labels& labels,
                    int depth, std::vector<RowTable>& tables) {
  RowTable table{pointer, title, {}, {}, {}};
  for (const json& element : array) add_columns(element, "", depth, table.columns);
  // Names first, then the other plain values (abscissas, counts), then figures and nested values.
  const auto rank = [&](const std::string& column) {
    for (const char* naming : kNamingMembers) {
      if (column == naming) return 0;
    }
    for (const json& element : array) {
      if (const json* cell = cell_of(element, column); cell != nullptr && !cell->is_null()) {
        return cell->is_primitive() && !column.empty() ? 1 : 2;
      }
    }
    return 2;
  };
  std::stable_sort(table.columns.begin(), table.columns.end(),
                   [&](const std::string& a, const std::string& b) { return rank(a) < rank(b); });
  for (const std::string& column : table.columns) table.headings.push_back(heading_of(column, labels));
  for (std::size_t i = 0; i < array.size(); ++i) {
    RowTable::Row row{fmt::format("{}/{}", pointer, i), row_name_of(array[i], i), {}};
    for (const std::string& column : table.columns) row.cells.push_back(cell_of(array[i], column));
    table.rows.push_back(std::move(row));
  }
  tables.push_back(table);
  if (depth >= kMaxNesting) return;
  for (const RowTable::Row& row : table.rows) {
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
      const json* cell = row.cells[c];
      if (cell == nullptr || table.columns[c].empty() || !is_nested_table(*cell)) continue;
      collect_tables(*cell, row.pointer + "/" + table.columns[c], title + " · " + row.name + " · " + table.headings[c],
                     labels, depth + 1, tables);
    }
  }
}

// The pointer of a cell of a row.
std::string cell_pointer(const RowTable::Row& row, const std::string& column) {
  return column.empty() ? row.pointer : row.pointer + "/" + column;
}

// "[0.1, 0.2, 0.3]" for the numbers of an array, nested for a matrix.
std::string numbers_text(const json& node) {
  if (node.is_number()) return format_number(node.get<double>());
  if (!node.is_array()) return node.dump();
  std::string text = "[";
  for (const json& element : node) text += (text.size() > 1 ? ", " : "") + numbers_text(element);
  return text + "]";
}

// A cell as text: a figure as value ± uncertainty and unit (format_figure); a number, a text or a
// yes/no as itself; a table inside the row by its rows' count (it follows); a short array of plain
// values listed, a long one counted; a missing member empty, a null "—".
std::string cell_text(const json* cell, const Labels& labels) {
  if (cell == nullptr) return "";
  if (cell->is_null()) return "—";
  if (is_scalar_figure(*cell)) return figure_text(*cell, labels);
  if (is_array_figure(*cell)) {
    const std::string unit = pretty_unit(cell->at("unit").get<std::string>());
    const auto* u = member(*cell, "uncertainty");
    return numbers_text(cell->at("value")) + (u != nullptr && u->is_array() ? " ± " + numbers_text(*u) : "") +
           (unit.empty() ? "" : " " + unit);
  }
  if (cell->is_boolean()) return labels(cell->get<bool>() ? "ui.yes" : "ui.no");
  if (cell->is_number()) return format_number(cell->get<double>());
  if (cell->is_string()) return cell->get<std::string>();
  if (is_nested_table(*cell)) return fmt::format(fmt::runtime(labels("ui.rows_below")), cell->size());
  if (cell->is_array()) {
    if (cell->empty()) return "—";
    if (is_long_array(*cell)) return fmt::format(fmt::runtime(labels("ui.values_in_results")), cell->size());
    std::string text;
    for (const json& element : *cell) text += (text.empty() ? "" : ", ") + cell_text(&element, labels);
    return text;
  }
  return cell->empty() ? "—" : cell->dump();
}

// The figures of a table as figure rows (for limits on them and their names): an element that is a
// figure as "Title (10 s)" or "Title #2", a figure member as "Title · coil · Residual rms".
void collect_table_figures(const std::vector<RowTable>& tables, std::vector<FigureRow>& rows) {
  for (const RowTable& table : tables) {
    for (const RowTable::Row& row : table.rows) {
      for (std::size_t c = 0; c < table.columns.size(); ++c) {
        const json* cell = row.cells[c];
        if (cell == nullptr || !is_scalar_figure(*cell)) continue;
        const std::string name =
            table.columns[c].empty()
                ? table.title + (row.name.starts_with('#') ? " " + row.name : " (" + row.name + ")")
                : table.title + " · " + row.name + " · " + table.headings[c];
        FigureRow figure_row{cell_pointer(row, table.columns[c]), name, *cell, 0, false};
        figure_row.in_table = true;
        rows.push_back(std::move(figure_row));
      }
    }
  }
}

std::string normalised_pointer(const std::string& figure) {
  if (!figure.empty() && figure.front() == '/') return figure;
  std::string pointer(1, '/');
  pointer += escape_pointer_token(figure);
  return pointer;
}

std::string verdict_key(const std::string& procedure, const std::string& pointer) {
  return procedure + '\x1f' + pointer;
}

// "≤ 100 ppm", "|value| ≤ 0.05 °/h" (a negative value judged by its magnitude), "≥ 4999",
// verdict_value_text with the unit of a measured number ("not measured", not "not measured °/h";
// "yes", not "yes 1").
std::string verdict_measured_text(const json& verdict, const Labels& labels) {
  const std::string unit = pretty_unit(verdict.value("unit", ""));
  const bool with_unit = is_number_member(verdict, "value") && !verdict.value("yes_no", false) && !unit.empty();
  return verdict_value_text(verdict, labels) + (with_unit ? " " + unit : "");
}

// "4999 … 5001 pulse/s/(°/s)"; "yes" for a yes/no the procedure judges itself with (it is 1 or 0).
std::string limit_text(const json& verdict, const Labels& labels) {
  if (verdict.value("yes_no", false)) return labels("ui.yes");
  const std::string unit = pretty_unit(verdict.value("unit", ""));
  const std::string suffix = unit.empty() ? "" : " " + unit;
  const auto* min = member(verdict, "min");
  const auto* max = member(verdict, "max");
  if (min && max) return format_number(min->get<double>()) + " … " + format_number(max->get<double>()) + suffix;
  if (max) return (verdict.value("magnitude", false) ? "|value| ≤ " : "≤ ") + format_number(max->get<double>()) + suffix;
  if (min) return "≥ " + format_number(min->get<double>()) + suffix;
  return "";
}

std::string verdict_cell(bool pass, const Labels& labels) {
  return pass ? fmt::format("<td class=\"verdict-cell pass\">{}</td>", html(labels("ui.pass")))
              : fmt::format("<td class=\"verdict-cell fail\">{}</td>", html(labels("ui.fail")));
}

class ReportWriter {
 public:
  ReportWriter(const json& results, const ReportOptions& options)
      : results_(results), options_(options), labels_(options.language) {}

  std::string render() {
    check_shape();
    index_verdicts();
    const json& plan = results_.at("plan");
    const std::string title = plan.contains("title") && plan.at("title").is_string()
                                  ? plan.at("title").get<std::string>()
                                  : labels_("ui.test_report") + " — " + instrument_id();
    out_ += fmt::format(
        "<!DOCTYPE html>\n<html lang=\"{}\">\n<head>\n<meta charset=\"utf-8\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
        "<title>{}</title>\n<style>\n{}</style>\n</head>\n<body>\n",
        options_.language == Language::chinese ? "zh-CN" : "en", html(title), report_css());
    write_cover(title);
    write_contents();
    write_summary();
    write_compliance();
    const json& procedures = results_.at("procedures");
    for (std::size_t i = 0; i < procedures.size(); ++i) write_procedure(procedures[i], i);
    write_truth_check();
    out_ += fmt::format("<footer>{}{}</footer>\n</body>\n</html>\n",
                        html(fmt::format(fmt::runtime(labels_("ui.generated")), results_.value("inertest_version", ""))),
                        options_.run_date.empty() ? "" : " · " + html(options_.run_date));
    return std::move(out_);
  }

  // The same figures as plain text: the instrument, each procedure's figure rows (value ± 1-sigma
  // uncertainty and unit), the specification limits and the overall verdict.
  std::string render_text() {
    check_shape();
    std::string text = fmt::format("{}: {} {}\n", labels_("ui.test_report"), labels_("ui.instrument"), instrument_id());
    for (const json& procedure : results_.at("procedures")) {
      const std::string kind = procedure.value("kind", "");
      text += fmt::format("\n{} ({})\n", labels_.title_of(kind), procedure.value("name", kind));
      for (const FigureRow& row : figures_of(procedure)) {
        if (row.in_table) continue;  // in its table (row_tables_text)
        text += fmt::format("  {:<56} {}\n", row.name, figure_text(row.figure, labels_));
      }
      text += row_tables_text(procedure);
    }
    if (!verdicts().empty()) {
      text += "\nSpecification limits\n";
      for (const json& v : verdicts()) {
        text += fmt::format("  {:<5} {} / {} = {} ({})\n", v.value("pass", false) ? "PASS" : "FAIL",
                            v.value("procedure", ""), verdict_figure_name(v), verdict_measured_text(v, labels_),
                            limit_text(v, labels_));
      }
    }
    return text + fmt::format("\nVerdict: {}\n", overall_verdict());
  }

 private:
  void check_shape() const {
    if (!results_.is_object()) throw Error("report: the results are not a JSON object");
    for (const char* key : {"instrument", "procedures"}) {
      if (!results_.contains(key)) throw Error(fmt::format("report: the results lack '{}'", key));
    }
    if (!results_.at("procedures").is_array()) throw Error("report: 'procedures' is not an array");
    if (!results_.at("instrument").is_object()) throw Error("report: 'instrument' is not an object");
  }

  std::string instrument_id() const {
    const auto* id = member(results_.at("instrument"), "id");
    return id != nullptr && id->is_string() ? id->get<std::string>() : "";
  }

  const json& verdicts() const {
    static const json kNone = json::array();
    const auto* v = member(results_, "verdicts");
    return v != nullptr && v->is_array() ? *v : kNone;
  }

  void index_verdicts() {
    for (const auto& v : verdicts()) {
      verdicts_by_figure_[verdict_key(v.value("procedure", ""), normalised_pointer(v.value("figure", "")))].push_back(&v);
    }
  }

  // The verdicts of one figure, one per limit the plan set on it (two limits on one figure: the
  // row showed the last one's, PASS beside a failed specification); null for none.
  const std::vector<const json*>* verdicts_of(const std::string& procedure, const std::string& pointer) const {
    const auto found = verdicts_by_figure_.find(verdict_key(procedure, pointer));
    return found == verdicts_by_figure_.end() ? nullptr : &found->second;
  }

  static bool all_pass(const std::vector<const json*>& figure_verdicts) {
    return std::all_of(figure_verdicts.begin(), figure_verdicts.end(),
                       [](const json* v) { return v->value("pass", false); });
  }

  std::string overall_verdict() const {
    const auto* v = member(results_, "verdict");
    return v != nullptr && v->is_string() ? v->get<std::string>() : "NONE";
  }

  void fact_row(const std::string& key, const json* value, const std::string& unit = "") {
    if (value == nullptr || value->is_null()) return;
    std::string text;
    if (value->is_string()) {
      text = value->get<std::string>();
    } else if (value->is_number()) {
      text = format_number(value->get<double>());
    } else {
      return;
    }
    if (text.empty()) return;
    if (!unit.empty()) text += " " + unit;
    out_ += fmt::format("<tr><th>{}</th><td>{}</td></tr>\n", html(labels_(key)), html(text));
  }

  void write_cover(const std::string& title) {
    const std::string verdict = overall_verdict();
    const std::string verdict_class = verdict == "PASS" ? "pass" : verdict == "FAIL" ? "fail" : "none";
    const std::string verdict_label = verdict == "PASS"   ? labels_("ui.pass")
                                      : verdict == "FAIL" ? labels_("ui.fail")
                                                          : labels_("ui.no_limits");
    out_ += "<header class=\"cover\">\n";
    out_ += fmt::format("<p class=\"kicker\">{}</p>\n<h1>{}</h1>\n", html(labels_("ui.test_report")), html(title));
    out_ +=
        fmt::format("<div class=\"overall verdict-{}\" data-verdict=\"{}\"><span>{}</span> <strong>{}</strong></div>\n",
                    verdict_class, html(verdict), html(labels_("ui.overall_verdict")), html(verdict_label));

    const json& instrument = results_.at("instrument");
    const json& plan = results_.contains("plan") ? results_.at("plan") : json::object();
    const json& site = results_.contains("site") ? results_.at("site") : json::object();
    out_ += "<div class=\"facts\">\n";
    out_ += fmt::format("<table><caption>{}</caption>\n", html(labels_("ui.instrument")));
    fact_row("ui.id", member(instrument, "id"));
    if (const auto* type = member(instrument, "type"); type != nullptr && type->is_string()) {
      const json readable = labels_("ui." + type->get<std::string>());
      fact_row("ui.type", &readable);
    }
    // K divides a rate: a counter's pulses per sample interval are read as pulse/s (output_unit_as_rate).
    const std::string output_unit = pretty_unit(output_unit_as_rate(instrument.value("output_unit", "")));
    fact_row("ui.output_unit", member(instrument, "output_unit"));
    const bool gyro = instrument.value("type", "gyro") == "gyro";
    fact_row("ui.nominal_scale_factor", member(instrument, "nominal_scale_factor"),
             (output_unit.empty() ? "1" : output_unit) + (gyro ? "/(°/s)" : "/g"));
    fact_row("ui.sample_rate_hz", member(instrument, "sample_rate_hz"), "Hz");
    out_ += "</table>\n";

    out_ += fmt::format("<table><caption>{}</caption>\n", html(labels_("ui.site")));
    fact_row("ui.name", member(site, "name"));
    fact_row("ui.latitude_deg", member(site, "latitude_deg"), "°");
    fact_row("ui.gravity_m_s2", member(site, "gravity_m_s2"), "m/s²");
    fact_row("ui.heading_deg", member(site, "heading_deg"), "°");
    out_ += "</table>\n";

    out_ += fmt::format("<table><caption>{}</caption>\n", html(labels_("ui.plan")));
    fact_row("ui.title", member(plan, "title"));
    const auto* plan_date = member(plan, "date");
    const json run_date = options_.run_date;
    fact_row("ui.date", plan_date != nullptr && plan_date->is_string() ? plan_date : &run_date);
    fact_row("ui.operator", member(plan, "operator"));
    fact_row("ui.laboratory", member(plan, "laboratory"));
    fact_row("ui.standard", member(plan, "standard"));
    fact_row("ui.version", member(results_, "inertest_version"));
    out_ += "</table>\n</div>\n</header>\n";
  }

  // The heading of a procedure's section: its kind's title, with the plan's name for the step
  // when it has one of its own ("Bias (bias_static)").
  std::string procedure_title(const json& procedure) const {
    const std::string name = procedure.value("name", "");
    const std::string kind_label = labels_.title_of(procedure.value("kind", ""));
    return name == procedure.value("kind", "") || name.empty() ? kind_label : kind_label + " (" + name + ")";
  }

  void write_contents() {
    out_ += fmt::format("<nav class=\"contents\"><h2>{}</h2><ol>\n", html(labels_("ui.contents")));
    out_ += fmt::format("<li><a href=\"#summary\">{}</a></li>\n", html(labels_("ui.summary")));
    if (!verdicts().empty()) {
      out_ += fmt::format("<li><a href=\"#compliance\">{}</a></li>\n", html(labels_("ui.compliance")));
    }
    const json& procedures = results_.at("procedures");
    for (std::size_t i = 0; i < procedures.size(); ++i) {
      out_ += fmt::format("<li><a href=\"#procedure-{}\">{}</a></li>\n", i + 1, html(procedure_title(procedures[i])));
    }
    if (const auto* checks = member(results_, "truth_check");
        checks != nullptr && checks->is_array() && !checks->empty()) {
      out_ += fmt::format("<li><a href=\"#truth-check\">{}</a></li>\n", html(labels_("ui.truth_check")));
    }
    out_ += "</ol></nav>\n";
  }

  // Whether a declared field is shown as a table (RowTable): a table field that is an array, or any
  // array too long to list figure by figure.
  static bool shown_as_table(const FieldSpec& field, const json& value) {
    return value.is_array() && (field.role == FieldRole::table || is_long_array(value));
  }

  // The tables of a declared procedure's result (its table fields, RowTable), in their declared order.
  std::vector<RowTable> tables_of(const json& procedure) const {
    std::vector<RowTable> tables;
    const auto* result = member(procedure, "result");
    const std::string kind = procedure.value("kind", "");
    const ProcedureSpec* spec = find_procedure_spec(kind);
    if (result == nullptr || spec == nullptr) return tables;
    for (const FieldSpec& field : spec->fields) {
      const auto* value = member(*result, field.name);
      if (value == nullptr || field.role == FieldRole::hidden || field.role == FieldRole::curve) continue;
      if (!shown_as_table(field, *value)) continue;
      collect_tables(*value, fmt::format("/{}", escape_pointer_token(field.name)), labels_.field_of(kind, field.name),
                     labels_, 1, tables);
    }
    return tables;
  }

  // A verdict's figure as its procedure's figures name it ("Bias stability (100 s)"), or its key
  // when no row shows it.
  std::string verdict_figure_name(const json& verdict) const {
    const std::string figure = verdict.value("figure", "");
    const std::string pointer = normalised_pointer(figure);
    for (const auto& procedure : results_.at("procedures")) {
      if (procedure.value("name", "") != verdict.value("procedure", "")) continue;
      for (const auto& row : figures_of(procedure)) {
        if (row.pointer == pointer) return row.name;
      }
    }
    return figure;
  }

  // The figures of a procedure's result: for a declared procedure its headline, detail and table
  // fields in their declared order, under the spec's labels (a plain number, text or yes/no field as
  // a figure without a unit, in the words the spec gives its values), a table's figures marked
  // in_table; otherwise every member that holds figures, in the label table's order.
  std::vector<FigureRow> figures_of(const json& procedure) const {
    std::vector<FigureRow> rows;
    const auto* result = member(procedure, "result");
    if (result == nullptr) return rows;
    const std::string kind = procedure.value("kind", "");
    const ProcedureSpec* spec = find_procedure_spec(kind);
    if (spec == nullptr) {
      collect_figures(*result, "", "", labels_, 0, true, rows);
      return rows;
    }
    for (const FieldSpec& field : spec->fields) {
      const auto* value = member(*result, field.name);
      if (value == nullptr || field.role == FieldRole::hidden || field.role == FieldRole::curve) continue;
      const std::string pointer = fmt::format("/{}", escape_pointer_token(field.name));
      if (shown_as_table(field, *value)) {
        std::vector<RowTable> tables;
        collect_tables(*value, pointer, labels_.field_of(kind, field.name), labels_, 1, tables);
        collect_table_figures(tables, rows);
        continue;
      }
      if (value->is_string() || value->is_boolean() || value->is_number()) {
        const auto words = field.value_words.find(value->dump());
        const json shown = words != field.value_words.end() ? json(words->second) : *value;
        rows.push_back({pointer, labels_.field_of(kind, field.name), json{{"value", shown}, {"unit", ""}}, 1,
                        field.role == FieldRole::headline});
        continue;
      }
      if (field.name == "channels" && value->is_object()) {
        collect_channels(*value, pointer, "", labels_, 0, field.role == FieldRole::headline, rows);
        continue;
      }
      collect_figures(*value, pointer, labels_.field_of(kind, field.name), labels_, 1, field.role == FieldRole::headline,
                      rows);
    }
    return rows;
  }

  // The declared tables of a procedure's section, each under its title: a column per member, a row
  // per element (its pointer in data-row, each cell's in data-figure, a limit's verdict on a cell in
  // data-verdict), at most kMaxTableRows rows and then the count of the others.
  void write_row_tables(const json& procedure) {
    const std::string name = procedure.value("name", "");
    for (const RowTable& table : tables_of(procedure)) {
      const std::size_t columns = std::max<std::size_t>(table.columns.size(), 1);
      out_ += fmt::format("<h3>{}</h3>\n<table class=\"rows\" data-table=\"{}\">\n<thead><tr>", html(table.title),
                          html(table.pointer));
      for (const std::string& heading : table.headings) out_ += fmt::format("<th>{}</th>", html(heading));
      out_ += "</tr></thead>\n<tbody>\n";
      if (table.rows.empty()) {
        out_ += fmt::format("<tr><td colspan=\"{}\">{}</td></tr>\n", columns, html(labels_("ui.no_rows")));
      }
      for (std::size_t i = 0; i < table.rows.size() && i < kMaxTableRows; ++i) {
        const RowTable::Row& row = table.rows[i];
        out_ += fmt::format("<tr data-row=\"{}\">", html(row.pointer));
        for (std::size_t c = 0; c < table.columns.size(); ++c) {
          const json* cell = row.cells[c];
          if (cell == nullptr) {
            out_ += "<td></td>";
            continue;
          }
          const std::string pointer = cell_pointer(row, table.columns[c]);
          const auto* figure_verdicts = verdicts_of(name, pointer);
          std::string classes = cell->is_number() || is_figure_node(*cell) ? "num" : "";
          std::string verdict;
          if (figure_verdicts != nullptr) {
            const bool pass = all_pass(*figure_verdicts);
            classes += classes.empty() ? "" : " ";
            classes += pass ? "pass" : "fail";
            verdict = fmt::format(" data-verdict=\"{}\"", pass ? "pass" : "fail");
          }
          out_ += fmt::format("<td{} data-figure=\"{}\"{}>{}</td>",
                              classes.empty() ? "" : fmt::format(" class=\"{}\"", classes), html(pointer), verdict,
                              html(cell_text(cell, labels_)));
        }
        out_ += "</tr>\n";
      }
      if (table.rows.size() > kMaxTableRows) {
        out_ += fmt::format("<tr class=\"more\"><td colspan=\"{}\">{}</td></tr>\n", columns,
                            html(fmt::format(fmt::runtime(labels_("ui.more_rows")), table.rows.size() - kMaxTableRows)));
      }
      out_ += "</tbody></table>\n";
    }
  }

  // The declared tables as text, columns aligned: the title, the headings, at most kMaxTableRows
  // rows and the count of the others.
  std::string row_tables_text(const json& procedure) const {
    std::string text;
    for (const RowTable& table : tables_of(procedure)) {
      text += fmt::format("  {}\n", table.title);
      std::vector<std::vector<std::string>> lines = {table.headings};
      for (std::size_t i = 0; i < table.rows.size() && i < kMaxTableRows; ++i) {
        std::vector<std::string> line;
        for (const json* cell : table.rows[i].cells) line.push_back(cell_text(cell, labels_));
        lines.push_back(std::move(line));
      }
      // Widths in characters (UTF-8 code points), not bytes: "±" and "°" are one column each.
      const auto width = [](const std::string& s) {
        return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
      };
      std::vector<std::size_t> widths(table.headings.size(), 0);
      for (const auto& line : lines) {
        for (std::size_t c = 0; c < line.size(); ++c) widths[c] = std::max(widths[c], width(line[c]));
      }
      for (const auto& line : lines) {
        std::string out = "   ";
        for (std::size_t c = 0; c < line.size(); ++c) {
          out += " " + line[c] + (c + 1 < line.size() ? std::string(widths[c] - width(line[c]) + 1, ' ') : "");
        }
        text += out + "\n";
      }
      if (table.rows.empty()) text += "    " + labels_("ui.no_rows") + "\n";
      if (table.rows.size() > kMaxTableRows) {
        text += "    " + fmt::format(fmt::runtime(labels_("ui.more_rows")), table.rows.size() - kMaxTableRows) + "\n";
      }
    }
    return text;
  }

  // The figure table: one procedure's rows, or every procedure's under group headings.
  void write_figure_rows(const json& procedure, bool with_limits, std::size_t columns, bool group_heading) {
    const std::string name = procedure.value("name", "");
    const auto rows = figures_of(procedure);
    const auto shown = [&](const FigureRow& row) {
      const bool limited = verdicts_of(name, row.pointer) != nullptr;
      return (!group_heading || row.headline || limited) && (!row.in_table || limited);  // else in its table
    };
    // A procedure of no headline figure and no limit (a calibration of triads) has no group: its
    // heading stood over no row.
    if (group_heading && std::any_of(rows.begin(), rows.end(), shown)) {
      out_ += fmt::format("<tr class=\"group\"><th colspan=\"{}\">{}</th></tr>\n", columns,
                          html(procedure_title(procedure)));
    }
    for (const auto& row : rows) {
      if (!shown(row)) continue;
      const auto [value, uncertainty] = format_figure(row.figure, labels_);
      const auto* figure_verdicts = verdicts_of(name, row.pointer);
      out_ += fmt::format(
          "<tr data-procedure=\"{}\" data-figure=\"{}\"{}>", html(name), html(row.pointer),
          figure_verdicts ? fmt::format(" data-verdict=\"{}\"", all_pass(*figure_verdicts) ? "pass" : "fail") : "");
      const std::string note = significance_note(row.figure, labels_);
      // A text figure (a criterion, a convention) wraps like text: kept on one line as a number, it
      // pushed the unit, the limit and the verdict off the printed page.
      out_ += fmt::format("<td>{}</td><td{}>{}</td><td class=\"num\">{}</td><td>{}</td>", html(row.name),
                          row.figure.at("value").is_string() ? "" : " class=\"num\"", html(value),
                          uncertainty.empty() ? "—" : "± " + html(uncertainty),
                          html(pretty_unit(row.figure.at("unit").get<std::string>()) + (note.empty() ? "" : ", " + note)));
      if (with_limits) {
        if (figure_verdicts) {
          std::vector<std::string> limits;
          for (const json* v : *figure_verdicts) limits.push_back(limit_text(*v, labels_));
          out_ += fmt::format("<td>{}</td>{}", html(fmt::format("{}", fmt::join(limits, "; "))),
                              verdict_cell(all_pass(*figure_verdicts), labels_));
        } else {
          out_ += "<td></td><td></td>";
        }
      }
      out_ += "</tr>\n";
    }
  }

  void figure_table_head(bool with_limits) {
    out_ += fmt::format("<thead><tr><th>{}</th><th class=\"num\">{}</th><th class=\"num\">{}</th><th>{}</th>",
                        html(labels_("ui.figure")), html(labels_("ui.value")), html(labels_("ui.uncertainty")),
                        html(labels_("ui.unit")));
    if (with_limits) {
      out_ += fmt::format("<th>{}</th><th>{}</th>", html(labels_("ui.specification")), html(labels_("ui.verdict")));
    }
    out_ += "</tr></thead>\n";
  }

  void write_summary() {
    const bool with_limits = !verdicts().empty();
    out_ += fmt::format("<section class=\"summary\" id=\"summary\">\n<h2>{} {}</h2>\n", ++section_,
                        html(labels_("ui.summary")));
    out_ += "<table class=\"figures\">\n";
    figure_table_head(with_limits);
    out_ += "<tbody>\n";
    for (const auto& procedure : results_.at("procedures")) {
      write_figure_rows(procedure, with_limits, with_limits ? 6 : 4, true);
    }
    out_ += "</tbody></table>\n</section>\n";
  }

  void write_compliance() {
    if (verdicts().empty()) return;
    out_ += fmt::format("<section class=\"compliance\" id=\"compliance\">\n<h2>{} {}</h2>\n", ++section_,
                        html(labels_("ui.compliance")));
    out_ += fmt::format(
        "<table class=\"limits\">\n<thead><tr><th>{}</th><th>{}</th><th>{}</th>"
        "<th class=\"num\">{}</th><th>{}</th></tr></thead>\n<tbody>\n",
        html(labels_("ui.procedure")), html(labels_("ui.figure")), html(labels_("ui.specification")),
        html(labels_("ui.measured")), html(labels_("ui.verdict")));
    for (const auto& v : verdicts()) {
      const std::string pointer = normalised_pointer(v.value("figure", ""));
      const std::string name = verdict_figure_name(v);
      const bool pass = v.value("pass", false);
      out_ += fmt::format(
          "<tr data-procedure=\"{}\" data-figure=\"{}\" data-verdict=\"{}\"><td>{}</td><td>{}</td>"
          "<td>{}</td><td class=\"num\">{}</td>{}</tr>\n",
          html(v.value("procedure", "")), html(pointer), pass ? "pass" : "fail", html(v.value("procedure", "")),
          html(name), html(limit_text(v, labels_)),
          html(verdict_measured_text(v, labels_) +
               (v.contains("reason") ? " (" + v.value("reason", "") + ")" : "")),
          verdict_cell(pass, labels_));
    }
    const std::string overall = overall_verdict();
    out_ += fmt::format("</tbody>\n<tfoot><tr><th colspan=\"4\">{}</th>{}</tr></tfoot>\n</table>\n</section>\n",
                        html(labels_("ui.overall_verdict")), verdict_cell(overall == "PASS", labels_));
  }

  // Arrays of named pass/fail items (e.g. the examination and electrical checks) as a table.
  void write_checklists(const json& result) {
    if (!result.is_object()) return;
    for (const auto& [key, items] : result.items()) {
      if (!items.is_array() || items.empty()) continue;
      const bool checklist = std::all_of(items.begin(), items.end(), [](const json& item) {
        return item.is_object() && item.contains("name") && item.contains("pass") && item.at("pass").is_boolean();
      });
      if (!checklist) continue;
      out_ += fmt::format(
          "<h3>{}</h3>\n<table class=\"checks\">\n<thead><tr><th>{}</th><th class=\"num\">{}</th>"
          "<th>{}</th><th>{}</th></tr></thead>\n<tbody>\n",
          html(labels_(key)), html(labels_("ui.name")), html(labels_("ui.measured")), html(labels_("ui.specification")),
          html(labels_("ui.verdict")));
      for (const auto& item : items) {
        std::string measured;
        if (const auto* v = member(item, "value"); v != nullptr) {
          measured = v->is_string()   ? labels_("ui." + v->get<std::string>())
                     : v->is_number() ? format_number(v->get<double>())
                                      : "";
        }
        const std::string unit = pretty_unit(item.value("unit", ""));
        if (!unit.empty() && !measured.empty()) measured += " " + unit;
        json limit = {{"unit", item.value("unit", "")}};
        if (item.contains("min")) limit["min"] = item.at("min");
        if (item.contains("max")) limit["max"] = item.at("max");
        out_ +=
            fmt::format("<tr><td>{}</td><td class=\"num\">{}</td><td>{}</td>{}</tr>\n", html(item.value("name", "")),
                        html(measured), html(limit_text(limit, labels_)), verdict_cell(item.at("pass").get<bool>(), labels_));
      }
      out_ += "</tbody></table>\n";
    }
  }

  // The demo's comparison of each measured figure with the simulated truth (results "truth_check").
  void write_truth_check() {
    const auto* checks = member(results_, "truth_check");
    if (checks == nullptr || !checks->is_array() || checks->empty()) return;
    out_ += fmt::format("<section class=\"truth\" id=\"truth-check\">\n<h2>{} {}</h2>\n", ++section_,
                        html(labels_("ui.truth_check")));
    out_ += fmt::format(
        "<table class=\"truth\">\n<thead><tr><th>{}</th><th>{}</th><th class=\"num\">{}</th>"
        "<th class=\"num\">{}</th><th class=\"num\">{}</th><th>{}</th><th>{}</th></tr></thead>\n"
        "<tbody>\n",
        html(labels_("ui.procedure")), html(labels_("ui.figure")), html(labels_("ui.true_value")),
        html(labels_("ui.measured")), html(labels_("ui.tolerance")), html(labels_("ui.unit")),
        html(labels_("ui.verdict")));
    for (const auto& c : *checks) {
      auto number = [&](const char* key) {
        const auto* v = member(c, key);
        return v != nullptr && v->is_number() ? format_number(v->get<double>()) : "";
      };
      const bool within = c.value("within", false);
      out_ += fmt::format(
          "<tr><td>{}</td><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
          "<td class=\"num\">± {}</td><td>{}</td>{}</tr>\n",
          html(c.value("procedure", "")), html(c.value("quantity", "")), html(number("true")),
          html(number("measured").empty() && !number("upper_bound").empty() ? "< " + number("upper_bound")
                                                                             : number("measured")),
          html(number("tolerance")), html(pretty_unit(c.value("unit", ""))), verdict_cell(within, labels_));
    }
    out_ += "</tbody></table>\n</section>\n";
  }

  // The records the step read, as results.json names them (campaign.cc records_of): what the
  // figures below were computed from, each with the SHA-256 a lab checks with `sha256sum`.
  void write_records(const json& procedure) {
    const auto* records = member(procedure, "records");
    if (records == nullptr || !records->is_array() || records->empty()) return;
    out_ += fmt::format("<h3>{}</h3>\n<table class=\"records\">\n<thead><tr><th>{}</th><th class=\"num\">{}</th>"
                        "<th>SHA-256</th></tr></thead>\n<tbody>\n",
                        html(labels_("ui.records")), html(labels_("ui.file")), html(labels_("ui.bytes")));
    for (const auto& record : *records) {
      if (!record.is_object()) continue;
      const auto bytes = record.value("bytes", json());
      out_ += fmt::format("<tr><td><code>{}</code></td><td class=\"num\">{}</td><td><code class=\"digest\">{}</code></td></tr>\n",
                          html(record.value("file", "")), bytes.is_number() ? bytes.dump() : "",
                          html(record.value("sha256", "")));
    }
    out_ += "</tbody></table>\n";
  }

  void write_procedure(const json& procedure, std::size_t index) {
    const int number = ++section_;
    const std::string kind = procedure.value("kind", "");
    const json& result = procedure.contains("result") ? procedure.at("result") : json::object();
    out_ += fmt::format("<section class=\"procedure\" id=\"procedure-{}\" data-kind=\"{}\">\n", index + 1, html(kind));
    out_ += fmt::format("<h2>{} {}</h2>\n<p class=\"kind\">{} · <code>{}</code></p>\n", number,
                        html(procedure_title(procedure)), html(labels_.title_of(kind)), html(kind));

    out_ += fmt::format("<div class=\"method\"><h3>{}</h3>\n", html(labels_("ui.method")));
    // Procedures cite their source as "clause" (standards), "standard" or "source" (papers).
    for (const char* citation : {"clause", "standard", "source"}) {
      if (const auto* text = member(result, citation); text != nullptr && text->is_string()) {
        out_ += fmt::format("<p class=\"clause\">{}</p>\n", html(text->get<std::string>()));
        break;
      }
    }
    if (const std::string method = labels_.method_of(kind); !method.empty()) {
      out_ += fmt::format("<p>{}</p>\n", html(method));
    }
    out_ += "</div>\n";
    write_records(procedure);

    out_ += fmt::format("<h3>{}</h3>\n<table class=\"figures\">\n", html(labels_("ui.results")));
    bool with_limits = false;
    for (const auto& v : verdicts())
      with_limits = with_limits || v.value("procedure", "") == procedure.value("name", "");
    figure_table_head(with_limits);
    out_ += "<tbody>\n";
    write_figure_rows(procedure, with_limits, with_limits ? 6 : 4, false);
    out_ += "</tbody></table>\n";
    write_row_tables(procedure);

    if (const auto* warnings = member(result, "warnings");
        warnings != nullptr && warnings->is_array() && !warnings->empty()) {
      out_ += fmt::format("<div class=\"warnings\"><h3>{}</h3><ul>\n", html(labels_("ui.warnings")));
      for (const auto& w : *warnings) {
        if (w.is_string()) out_ += fmt::format("<li>{}</li>\n", html(w.get<std::string>()));
      }
      out_ += "</ul></div>\n";
    }

    write_checklists(result);

    json procedure_verdicts = json::array();
    for (const auto& v : verdicts()) {
      if (v.value("procedure", "") == procedure.value("name", "")) procedure_verdicts.push_back(v);
    }
    const PlotContext context{result, labels_, procedure_verdicts, find_procedure_spec(kind)};
    for (auto& plot : procedure_plots(kind, context)) {
      if (plot.plot.panels.empty()) continue;
      plot.plot.embed_data = options_.embed_plot_data;
      plot.plot.description = plot.caption;
      ++figure_number_;
      out_ += fmt::format("<figure{}>\n{}<figcaption>{} {}. {}</figcaption>\n</figure>\n",
                          plot.field.empty() ? "" : fmt::format(" data-curve=\"{}\"", html(plot.field)),
                          render_svg(plot.plot), html(labels_("ui.plot")), figure_number_, html(plot.caption));
    }
    out_ += "</section>\n";
  }

  const json& results_;
  const ReportOptions& options_;
  Labels labels_;
  std::map<std::string, std::vector<const json*>> verdicts_by_figure_;
  std::string out_;
  int figure_number_ = 0;
  int section_ = 0;
};

}  // namespace

Language parse_language(const std::string& code) {
  if (code == "en") return Language::english;
  if (code == "zh") return Language::chinese;
  throw Error("report language '" + code + "' is not known (use \"en\" or \"zh\")");
}

std::string render_report(const json& results, const ReportOptions& options) {
  return ReportWriter(results, options).render();
}

std::string render_text_report(const json& results, const ReportOptions& options) {
  return ReportWriter(results, options).render_text();
}

std::string write_report(const json& results, const std::string& out_dir, const ReportOptions& options) {
  const std::string page = render_report(results, options);
  std::filesystem::create_directories(out_dir);
  const std::string path = (std::filesystem::path(out_dir) / "report.html").string();
  write_file_atomically(path, page);
  return path;
}

std::string current_date() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm local{};
  localtime_r(&now, &local);
  return fmt::format("{:04}-{:02}-{:02}", local.tm_year + 1900, local.tm_mon + 1, local.tm_mday);
}

}  // namespace inertest::report
