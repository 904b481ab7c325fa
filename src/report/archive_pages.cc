#include "inertest/report/archive_pages.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/io/atomic_write.h"
#include "inertest/report/svg_plot.h"
#include "inertest/version.h"
#include "report/figure_format.h"
#include "report/labels.h"
#include "report/result_access.h"
#include "report/report_style.h"

namespace inertest::report {
namespace {

using nlohmann::json;

// The words of these two pages only (the campaign report's table, labels.cc, is shared with
// other pages and kept to the campaign's words).
struct PageWord {
  const char* key;
  const char* english;
  const char* chinese;
};
constexpr PageWord page_words[] = {
    {"history", "Instrument history", "仪表历史记录"},
    {"fleet", "Fleet", "批次统计"},
    {"tested_on", "Tested on", "测试日期"},
    {"days", "days since first test", "距首次测试天数"},
    {"campaign", "Campaign", "测试记录"},
    {"tests", "Tests", "测试次数"},
    {"not_measured", "not measured", "未测得"},
    {"control_chart", "Control chart (individuals, moving range)", "控制图（单值-移动极差）"},
    {"capability", "Process capability", "过程能力"},
    {"center", "center line", "中心线"},
    {"ucl", "UCL", "上控制限"},
    {"lcl", "LCL", "下控制限"},
    {"lower_limit", "lower specification limit", "指标下限"},
    {"upper_limit", "upper specification limit", "指标上限"},
    {"out_of_control", "Out of control", "失控点"},
    {"since", "Tests on or after", "统计起始日期（含）"},
    {"magnitude", "(−max: the max bounds |value|)", "（−max：上限约束 |值|）"},
    {"instrument_number", "instrument, in order of first test", "仪表（按首次测试顺序）"},
    {"not_comparable", "Not comparable: archived in units that do not convert", "无法比较：存档单位不能相互换算"},
    {"rule.beyond_3_sigma", "beyond 3σ (rule 1)", "超出 3σ 控制限（准则 1）"},
    {"rule.8_on_one_side", "8 on one side of the center (rule 4)", "连续 8 点位于中心线同侧（准则 4）"},
    {"method", "Shewhart individuals chart: limits x̄ ± 3·MR̄/1.128 (NIST/SEMATECH e-Handbook 6.3.2.2), Western Electric rules 1 and 4; Cp = (USL − LSL)/6σ, Cpk = min(USL − x̄, x̄ − LSL)/3σ with σ = MR̄/1.128 (6.1.6); each instrument's latest value.",
     "休哈特单值控制图：控制限 x̄ ± 3·MR̄/1.128（NIST/SEMATECH 统计方法手册 6.3.2.2），西方电气准则 1 与 4；Cp = (USL − LSL)/6σ，Cpk = min(USL − x̄, x̄ − LSL)/3σ，σ = MR̄/1.128（6.1.6）；每台仪表取最近一次测试值。"},
};

class Page {
 public:
  // The figures archived in units that do not convert ({"figure", "why"}), each said, if any.
  void not_comparable(const json& figures) {
    if (figures.empty()) return;
    out() += fmt::format("<section class=\"not-comparable\"><h2>{}</h2>\n<ul>\n", escape_xml(word("not_comparable")));
    for (const auto& f : figures) out() += fmt::format("<li>{}</li>\n", escape_xml(f.at("why").get<std::string>()));
    out() += "</ul>\n</section>\n";
  }

  // One panel's plot at the page's width, its data embedded where the page is interactive.
  Plot plot_of(Panel panel) const {
    Plot plot;
    plot.panels = {std::move(panel)};
    plot.embed_data = options_.embed_plot_data;
    return plot;
  }

  explicit Page(const ReportOptions& options) : options_(options), labels_(options.language) {}

  std::string word(const std::string& key) const {
    for (const auto& w : page_words) {
      if (key == w.key) return options_.language == Language::chinese ? w.chinese : w.english;
    }
    return labels_(key);
  }
  // The figure's last key in the report's words, e.g. "Scale factor".
  // "scale_factor/nonlinearity": the label of the figure in that procedure's declaration, else the table's.
  // A row of a table ("bias/bias_stability/1") is its table's with its place ("smoothing_s = 10"),
  // else its number from 1: the pages called it "1".
  std::string figure_label(const nlohmann::json& history) const {
    const std::string figure = history.at("figure").get<std::string>();
    const std::size_t slash = figure.rfind('/');
    if (slash == std::string::npos) return labels_(figure);
    const std::string key = figure.substr(slash + 1);
    const std::size_t before = figure.rfind('/', slash - 1);
    if (before != std::string::npos && !key.empty() && key.find_first_not_of("0123456789") == std::string::npos) {
      const std::string table = labels_.field_of(figure.substr(0, before), figure.substr(before + 1, slash - before - 1));
      const auto* place = history.contains("place") ? &history.at("place") : nullptr;
      return table + (place != nullptr && place->is_string() ? " (" + place->get<std::string>() + ")"
                                                            : fmt::format(" #{}", std::stoul(key) + 1));
    }
    return labels_.field_of(figure.substr(0, slash), key);
  }
  // A figure PROCEDURE/FIGURE as a heading: "Scale factor (scale_factor/scale_factor)".
  std::string figure_title(const nlohmann::json& history) const {
    return figure_label(history) + " (" + history.at("figure").get<std::string>() + ")";
  }
  const Labels& labels() const { return labels_; }

  void open(const std::string& kicker, const std::string& title) {
    out_ += fmt::format(
        "<!DOCTYPE html>\n<html lang=\"{}\">\n<head>\n<meta charset=\"utf-8\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
        "<title>{}</title>\n<style>\n{}</style>\n</head>\n<body class=\"archive\">\n<header class=\"cover\">\n"
        "<p class=\"kicker\">{}</p>\n<h1>{}</h1>\n</header>\n",
        options_.language == Language::chinese ? "zh-CN" : "en", escape_xml(title), report_css(), escape_xml(kicker),
        escape_xml(title));
  }

  std::string close() {
    out_ += fmt::format("<footer>{}{}</footer>\n</body>\n</html>\n",
                        escape_xml(fmt::format(fmt::runtime(labels_("ui.generated")), version())),
                        options_.run_date.empty() ? "" : " · " + escape_xml(options_.run_date));
    return std::move(out_);
  }
  std::string& out() { return out_; }

 private:
  const ReportOptions& options_;
  Labels labels_;
  std::string out_;
};

// A number as a table shows it: 6 significant digits ("{:.10g}" printed 20.55712319 for the campaign
// report's 20.56 ± 0.13, and pushed the fleet's Cp and Cpk off the page); a limit as the plan set it.
std::string number(const json& value, const char* format = "{:.6g}") {
  return value.is_number() ? fmt::format(fmt::runtime(format), value.get<double>()) : "—";
}
std::string limit(const json& value) { return number(value, "{:.10g}"); }

// A measured point of a history or a fleet as a figure {"value", "unit", "uncertainty" if known}.
json point_figure(const json& point, const std::string& unit) {
  json figure = {{"value", point.at("value")}, {"unit", unit}};
  if (point.at("uncertainty").is_number()) figure["uncertainty"] = point.at("uncertainty");
  return figure;
}

// A point as the campaign report gives a figure: "36000.25 ± 0.50 pulse/s/(°/s)"; null: the test
// did not measure it.
std::string point_text(const json& point, const std::string& unit, const Page& page) {
  if (!point.at("value").is_number()) return escape_xml(page.word("not_measured"));
  return escape_xml(figure_text(point_figure(point, unit), page.labels()));
}

// A point's value and uncertainty in two cells, as the campaign report gives them (to the
// uncertainty's second significant digit, GUM 7.2.6) with its readable unit.
std::pair<std::string, std::string> point_cells(const json& point, const std::string& unit, const Page& page) {
  if (!point.at("value").is_number()) return {escape_xml(page.word("not_measured")), "—"};
  const auto [value, uncertainty] = format_figure(point_figure(point, unit), page.labels());
  const std::string shown_unit = pretty_unit(unit).empty() ? "" : " " + pretty_unit(unit);
  return {escape_xml(value + shown_unit), uncertainty.empty() ? "—" : escape_xml(uncertainty + shown_unit)};
}

// Days from 1970-01-01 of a YYYY-MM-DD date (the archive checked the form).
double days(const std::string& date) {
  const int y = std::stoi(date.substr(0, 4));
  const unsigned m = static_cast<unsigned>(std::stoi(date.substr(5, 2)));
  const unsigned d = static_cast<unsigned>(std::stoi(date.substr(8, 2)));
  const std::chrono::sys_days day{std::chrono::year{y} / std::chrono::month{m} / std::chrono::day{d}};
  return static_cast<double>(day.time_since_epoch().count());
}

// The specification limits as lines. A limit on the magnitude (|value| <= max: "limit_on_magnitude")
// draws its -max only when a plotted value is negative: a figure that is never negative (a bias
// stability) keeps the scale of its values rather than stretching to a line below zero.
void add_limits(Panel& panel, const json& figure, const std::vector<double>& plotted, const Page& page) {
  const bool on_magnitude = figure.value("limit_on_magnitude", false);
  const bool any_negative = std::any_of(plotted.begin(), plotted.end(), [](double v) { return v < 0.0; });
  for (const char* key : {"lower_limit", "upper_limit"}) {
    if (on_magnitude && std::string(key) == "lower_limit" && !any_negative) continue;
    if (figure.contains(key) && figure.at(key).is_number()) {
      panel.references.push_back({ReferenceLine::Direction::horizontal, figure.at(key).get<double>(), page.word(key), "#b3261e"});
    }
  }
}

}  // namespace

std::string render_history_page(const json& history, const ReportOptions& options) {
  Page page(options);
  const std::string instrument = history.at("instrument").get<std::string>();
  page.open(page.word("history"), instrument);
  for (const auto& figure : history.at("figures")) {
    const auto& points = figure.at("points");
    if (points.empty()) continue;
    const std::string first = points.front().at("tested_on").get<std::string>().substr(0, 10);
    Series series;
    series.name = instrument;
    series.line = LineStyle::solid;
    series.marker = Marker::circle;
    for (const auto& p : points) {
      if (!p.at("value").is_number()) continue;  // not measured: in the table, not on the plot
      const double value = p.at("value").get<double>();
      const double u = p.at("uncertainty").is_number() ? p.at("uncertainty").get<double>() : 0.0;
      series.x.push_back(days(p.at("tested_on").get<std::string>()) - days(first));
      series.y.push_back(value);
      series.y_low.push_back(value - u);
      series.y_high.push_back(value + u);
    }
    Panel panel;
    panel.title = page.figure_title(figure);
    panel.x = make_axis(page.word("days") + " (" + first + ")", "");
    panel.y = make_axis(page.figure_label(figure),
                        figure.at("unit").get<std::string>());
    const std::vector<double> plotted = series.y;
    panel.series.push_back(std::move(series));
    add_limits(panel, figure, plotted, page);
    page.out() += fmt::format("<section class=\"procedure\">\n<h2>{}</h2>\n", escape_xml(panel.title));
    if (!plotted.empty()) {
      page.out() += fmt::format("<figure>\n{}</figure>\n", render_svg(page.plot_of(panel)));
    }
    page.out() += fmt::format("<table><tr><th>{}</th><th>{}</th><th>{}</th><th>{}</th></tr>\n",
                              escape_xml(page.word("tested_on")), escape_xml(page.labels()("ui.value")),
                              escape_xml(page.labels()("ui.uncertainty")), escape_xml(page.word("campaign")));
    for (const auto& p : points) {
      const auto [value, uncertainty] = point_cells(p, figure.at("unit").get<std::string>(), page);
      page.out() += fmt::format("<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td><code>{}</code></td></tr>\n",
                                escape_xml(p.at("tested_on").get<std::string>()), value, uncertainty,
                                escape_xml(p.at("campaign").get<std::string>()));
    }
    page.out() += "</table>\n</section>\n";
  }
  page.not_comparable(history.value("not_comparable", json::array()));
  return page.close();
}

std::string render_fleet_page(const json& fleet, const ReportOptions& options, const json& not_comparable) {
  Page page(options);
  page.open(page.word("fleet"), page.word("control_chart"));
  page.out() += fmt::format("<p>{}</p>\n", escape_xml(page.word("method")));
  // Counted from a date (archive fleet --since, /fleet?since=): said, or the page reads as the whole fleet.
  if (!fleet.empty() && fleet.front().value("since", json()).is_string()) {
    page.out() += fmt::format("<p class=\"since\">{}: {}</p>\n", escape_xml(page.word("since")),
                              escape_xml(fleet.front().at("since").get<std::string>()));
  }
  // The capability table first: one row per figure.
  page.out() += fmt::format(
      "<section><h2>{}</h2>\n<table><tr><th>{}</th><th>{}</th><th>n</th><th>x̄</th><th>σ</th><th>{}</th><th>{}</th>"
      "<th>{}</th><th>{}</th><th>Cp</th><th>Cpk</th><th>{}</th></tr>\n",
      escape_xml(page.word("capability")), escape_xml(page.labels()("ui.figure")), escape_xml(page.labels()("ui.unit")),
      escape_xml(page.word("lower_limit")), escape_xml(page.word("upper_limit")), escape_xml(page.word("lcl")),
      escape_xml(page.word("ucl")), escape_xml(page.word("out_of_control")));
  for (const auto& f : fleet) {
    const json& chart = f.at("control_chart");
    const json none = nullptr;
    page.out() += fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>"
        "<td>{}</td><td>{}</td><td>{}</td></tr>\n",
        escape_xml(f.at("figure").get<std::string>()), escape_xml(pretty_unit(f.at("unit").get<std::string>())),
        std::count_if(f.at("instruments").begin(), f.at("instruments").end(),
                      [](const json& i) { return i.at("value").is_number(); }),
        number(chart.is_null() ? none : chart.at("center")),
        number(chart.is_null() ? none : chart.at("sigma")),
        limit(f.at("lower_limit")) + (f.value("limit_on_magnitude", false) ? " " + escape_xml(page.word("magnitude")) : ""),
        limit(f.at("upper_limit")),
        number(chart.is_null() ? none : chart.at("lcl")), number(chart.is_null() ? none : chart.at("ucl")),
        number(f.at("capability").at("cp"), "{:.3g}"), number(f.at("capability").at("cpk"), "{:.3g}"),
        chart.is_null() ? 0 : chart.at("out_of_control").size());
  }
  page.out() += "</table>\n</section>\n";
  page.not_comparable(not_comparable);

  for (const auto& f : fleet) {
    const json& chart = f.at("control_chart");
    Series values;
    values.name = page.labels()("ui.value");
    values.line = LineStyle::solid;
    values.marker = Marker::circle;
    Series flagged;
    flagged.name = page.word("out_of_control");
    flagged.line = LineStyle::none;
    flagged.marker = Marker::diamond;
    flagged.color = "#b3261e";
    std::size_t index = 0;
    for (const auto& i : f.at("instruments")) {
      ++index;  // the instrument's number in the table, measured or not
      if (!i.at("value").is_number()) continue;
      values.x.push_back(static_cast<double>(index));
      values.y.push_back(i.at("value").get<double>());
      if (chart.is_null()) continue;
      for (const auto& o : chart.at("out_of_control")) {
        if (o.at("instrument") == i.at("instrument")) {
          flagged.x.push_back(static_cast<double>(index));
          flagged.y.push_back(i.at("value").get<double>());
        }
      }
    }
    Panel panel;
    panel.title = page.figure_title(f);
    panel.x = make_axis(page.word("instrument_number"), "");
    panel.y = make_axis(page.figure_label(f),
                        f.at("unit").get<std::string>());
    const std::vector<double> plotted = values.y;
    panel.series.push_back(std::move(values));
    if (!flagged.x.empty()) panel.series.push_back(std::move(flagged));
    if (!chart.is_null()) {
      panel.references.push_back({ReferenceLine::Direction::horizontal, chart.at("center").get<double>(), page.word("center"), "#555555"});
      panel.references.push_back({ReferenceLine::Direction::horizontal, chart.at("ucl").get<double>(), page.word("ucl"), "#1f6feb"});
      panel.references.push_back({ReferenceLine::Direction::horizontal, chart.at("lcl").get<double>(), page.word("lcl"), "#1f6feb"});
    }
    add_limits(panel, f, plotted, page);
    page.out() += fmt::format("<section class=\"procedure\">\n<h2>{}</h2>\n", escape_xml(panel.title));
    if (!plotted.empty()) {
      page.out() += fmt::format("<figure>\n{}</figure>\n", render_svg(page.plot_of(panel)));
    }
    page.out() += fmt::format("<table><tr><th>#</th><th>{}</th><th>{}</th><th>{}</th><th>{}</th><th>{}</th></tr>\n",
                              escape_xml(page.labels()("ui.instrument")), escape_xml(page.word("tested_on")),
                              escape_xml(page.labels()("ui.value")), escape_xml(page.word("tests")),
                              escape_xml(page.word("out_of_control")));
    index = 0;
    for (const auto& i : f.at("instruments")) {
      std::string rule;
      if (!chart.is_null()) {
        for (const auto& o : chart.at("out_of_control")) {
          if (o.at("instrument") == i.at("instrument")) rule = page.word("rule." + o.at("rule").get<std::string>());
        }
      }
      page.out() += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n", ++index,
                                escape_xml(i.at("instrument").get<std::string>()),
                                escape_xml(i.at("tested_on").get<std::string>()),
                                point_text(i, f.at("unit").get<std::string>(), page),
                                i.at("tests").get<std::size_t>(),
                                escape_xml(rule));
    }
    page.out() += "</table>\n</section>\n";
  }
  return page.close();
}

std::string history_page_file_name(const std::string& instrument) {
  std::string name = "history-";
  for (const char c : instrument) {
    const auto byte = static_cast<unsigned char>(c);
    if (std::isalnum(byte) != 0 || c == '-' || c == '.' || c == '_') {
      name += c;
    } else {
      name += fmt::format("%{:02X}", byte);
    }
  }
  return name + ".html";
}

std::vector<std::string> write_archive_pages(const json& data, const std::string& out_dir, const ReportOptions& options) {
  namespace fs = std::filesystem;
  // Every page is rendered before any is written.
  std::vector<std::pair<std::string, std::string>> pages = {
      {"fleet.html", render_fleet_page(data.at("fleet"), options, data.value("not_comparable", json::array()))}};
  for (const auto& history : data.at("histories")) {
    pages.emplace_back(history_page_file_name(history.at("instrument").get<std::string>()),
                       render_history_page(history, options));
  }
  require_output_directory(out_dir);
  fs::create_directories(out_dir);
  // Then written into a staging directory beside them, and moved into place only when all are
  // there: a full disk, or a directory where a page goes, leaves the pages as they were.
  const fs::path staging = fs::path(out_dir) / fmt::format(".archive-pages-{}", ::getpid());
  fs::remove_all(staging);
  fs::create_directory(staging);
  std::vector<fs::path> names;
  std::vector<std::string> written;
  for (const auto& [name, content] : pages) {
    names.emplace_back(name);
    written.push_back((fs::path(out_dir) / name).string());
  }
  try {
    for (const auto& [name, content] : pages) write_file_atomically((staging / name).string(), content);
    move_staged_files(staging, out_dir, names);
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(staging, ignored);
    throw;
  }
  fs::remove(staging);
  return written;
}

}  // namespace inertest::report
