// The instrument list page of inertest serve (a table and a few lines of plain JavaScript), and the
// interactive plots and the history switcher the server adds to the report's pages.
#include "serve/pages.h"

#include <cctype>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/report/svg_plot.h"
#include "report/report_style.h"
#include "serve/plot_script.h"

namespace inertest::serve {
using report::escape_xml;

namespace {

// Filters the rows by the search box (case-insensitive substring of the id), keeps ?q= in step
// and says how many rows are shown.
constexpr std::string_view search_script = R"(
(function () {
  var box = document.getElementById('search');
  var rows = Array.prototype.slice.call(document.querySelectorAll('#instruments tbody tr'));
  var shown = document.getElementById('shown');
  function apply() {
    var text = box.value.trim().toLowerCase();
    var count = 0;
    rows.forEach(function (row) {
      var match = row.getAttribute('data-instrument').toLowerCase().indexOf(text) >= 0;
      row.hidden = !match;
      if (match) count += 1;
    });
    shown.textContent = count + ' / ' + rows.length;
  }
  box.value = new URLSearchParams(window.location.search).get('q') || '';
  box.addEventListener('input', apply);
  apply();
})();
)";

// Sends the chosen results.json with the token and shows the server's answer.
constexpr std::string_view add_script = R"(
(function () {
  var form = document.getElementById('add-form');
  if (!form) return;
  var answer = document.getElementById('add-answer');
  form.addEventListener('submit', function (event) {
    event.preventDefault();
    var file = document.getElementById('add-file').files[0];
    var token = document.getElementById('add-token').value.trim();
    if (!file) { answer.className = 'fail'; answer.textContent = form.getAttribute('data-no-file'); return; }
    answer.className = '';
    answer.textContent = '…';
    file.text().then(function (body) {
      return fetch('/api/campaigns', {method: 'POST', body: body,
                                      headers: {'Content-Type': 'application/json', 'Authorization': 'Bearer ' + token}});
    }).then(function (response) {
      return response.json().then(function (json) { return {status: response.status, json: json}; });
    }).then(function (reply) {
      answer.textContent = '';
      if (reply.status !== 200) {
        answer.className = 'fail';
        answer.textContent = reply.status + ': ' + reply.json.error;
        return;
      }
      answer.className = 'pass';
      reply.json.added.forEach(function (added) {
        var link = document.createElement('a');
        link.href = '/campaigns/' + added.id;
        link.textContent = added.id;
        answer.appendChild(document.createTextNode(form.getAttribute(added.added ? 'data-added' : 'data-already') + ' '));
        answer.appendChild(link);
        answer.appendChild(document.createTextNode(' (' + added.instrument + ')'));
      });
    }).catch(function (error) {
      answer.className = 'fail';
      answer.textContent = String(error);
    });
  });
})();
)";

struct Words {
  const char* title;
  const char* search;
  const char* instrument;
  const char* campaigns;
  const char* latest;
  const char* verdict;
  const char* report;
  const char* fleet;
  const char* add;          // the form's heading
  const char* add_file;     // the file input's label
  const char* add_token;    // the token input's label
  const char* add_send;     // the button
  const char* add_no_file;  // the answer when no file is chosen
  const char* added;        // before the new campaign's id
  const char* already;      // before the id of a campaign the archive already held
};

const Words english{"Instruments", "Search by id", "Instrument", "Campaigns", "Latest test", "Verdict",
                    "Latest report", "Fleet", "Add a campaign", "results.json", "Token (printed by inertest serve)",
                    "Add", "choose a results.json file", "added", "already in the archive:"};
// GJB 2426A's words, as the report uses them (report/labels.cc, archive_pages.cc): 测试 for a test
// (the standard's "5 测试项目与方法", the report's 测试报告; 试验 is its word for test conditions, as a
// test temperature), 被测仪表 for the instrument under test, 结论 with 合格 / 不合格 for the verdict.
const Words chinese{"被测仪表", "按编号搜索", "仪表编号", "测试次数", "最近测试", "结论", "最近测试报告", "批次统计",
                    "添加测试结果", "results.json 文件", "令牌（inertest serve 启动时显示）", "添加",
                    "请选择 results.json 文件", "已添加", "档案中已有："};

// The verdict as the report words it: 合格, 不合格, 无 in Chinese.
std::string verdict_word(const std::string& verdict, bool zh) {
  if (!zh) return verdict;
  return verdict == "PASS" ? "合格" : verdict == "FAIL" ? "不合格" : "无";
}

// The form of --allow-add and its script (add_script); not printed.
std::string add_form(const Words& w) {
  return fmt::format(
      "<section id=\"add\"><h2>{0}</h2>\n"
      "<form id=\"add-form\" data-no-file=\"{4}\" data-added=\"{5}\" data-already=\"{6}\">\n"
      "<p><label>{1} <input id=\"add-file\" type=\"file\" accept=\".json,application/json\"></label></p>\n"
      "<p><label>{2} <input id=\"add-token\" type=\"password\" autocomplete=\"off\" size=\"34\"></label> "
      "<button type=\"submit\">{3}</button></p>\n<p id=\"add-answer\" role=\"status\"></p>\n</form>\n</section>\n"
      "<script>{7}</script>\n",
      w.add, w.add_file, w.add_token, w.add_send, w.add_no_file, w.added, w.already, add_script);
}

// A path segment of a URL, or (kept "/") a query's value: every byte but the unreserved ones and
// `kept` percent-encoded (RFC 3986 2.3), so that an id with a space, a '/' or Chinese characters
// links to its page, and a figure of a step named "SF & NL #1+x" to its history (its '&' ended the
// value, its '#' the query, its '+' read as a space).
std::string percent_encoded(const std::string& text, std::string_view kept = "") {
  std::string encoded;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (std::isalnum(byte) != 0 || c == '-' || c == '.' || c == '_' || c == '~' || kept.find(c) != std::string_view::npos) {
      encoded += c;
    } else {
      encoded += fmt::format("%{:02X}", byte);
    }
  }
  return encoded;
}

}  // namespace

std::string render_instrument_list_page(const nlohmann::json& instruments, report::Language language, bool allow_add) {
  const bool zh = language == report::Language::chinese;
  const Words& w = zh ? chinese : english;
  const std::string lang_query = zh ? "?lang=zh" : "";
  std::string rows;
  for (const auto& i : instruments.at("instruments")) {
    const std::string& instrument = i.at("instrument").get_ref<const std::string&>();
    const std::string id = escape_xml(instrument);
    const auto& latest = i.at("latest");
    const std::string verdict = latest.at("verdict").get<std::string>();
    rows += fmt::format(
        "<tr data-instrument=\"{0}\"><td><a href=\"/instruments/{8}{1}\">{0}</a></td><td class=\"num\">{2}</td>"
        "<td>{3}</td><td class=\"verdict {4}\">{5}</td><td><a href=\"/campaigns/{6}{1}\">{7}</a></td></tr>\n",
        id, lang_query, i.at("campaigns").get<std::size_t>(), escape_xml(latest.at("tested_on").get<std::string>()),
        verdict == "PASS" ? "pass" : verdict == "FAIL" ? "fail" : "none", escape_xml(verdict_word(verdict, zh)),
        escape_xml(latest.at("id").get<std::string>()), escape_xml(latest.at("title").get<std::string>()),
        percent_encoded(instrument));
  }
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"{0}\">\n<head>\n<meta charset=\"utf-8\">\n<title>inertest · {1}</title>\n"
      "<style>{2}\n#search {{ font: inherit; padding: 0.3em; width: 20em; }} #add-answer.pass {{ color: var(--pass); }} #add-answer.fail {{ color: var(--fail); }}"
      " @media print {{ #search, #add {{ display: none; }} }}"
      "</style>\n</head>\n<body>\n<h1>{1}</h1>\n<p><a href=\"/fleet{3}\">{4}</a> · <a href=\"/{5}\">{6}</a></p>\n"
      "<p><input id=\"search\" type=\"search\" placeholder=\"{7}\" aria-label=\"{7}\"> <span id=\"shown\"></span></p>\n"
      "<table id=\"instruments\">\n<thead><tr><th>{8}</th><th>{9}</th><th>{10}</th><th>{11}</th><th>{12}</th></tr></thead>\n"
      "<tbody>\n{13}</tbody>\n</table>\n{15}<script>{14}</script>\n</body>\n</html>\n",
      zh ? "zh-CN" : "en", w.title, report::report_css(), lang_query, w.fleet, zh ? "" : "?lang=zh", zh ? "English" : "中文",
      w.search, w.instrument, w.campaigns, w.latest, w.verdict, w.report, rows, search_script,
      allow_add ? add_form(w) : std::string());
}

namespace {

// The plots' tool bar and tooltip; neither is printed.
constexpr std::string_view plot_style = R"(
.plot-box { position: relative; }
.plot-box svg { cursor: crosshair; user-select: none; }
.plot-tools { display: flex; gap: 0.3em; justify-content: flex-end; margin-bottom: 0.2em; }
.plot-tools button { font: inherit; font-size: 0.85em; padding: 0.1em 0.6em; border: 1px solid #999; border-radius: 3px;
  background: #f6f6f6; cursor: pointer; }
.plot-tools button[aria-pressed="true"] { background: #dde8f8; border-color: #1f6feb; }
.plot-tip { position: absolute; pointer-events: none; background: #fffff4; border: 1px solid #888; border-radius: 3px;
  padding: 0.25em 0.5em; font-size: 0.85em; white-space: nowrap; box-shadow: 0 1px 3px rgba(0, 0, 0, 0.2); }
.plot-tip .tip-series { font-weight: bold; }
nav.switch { margin: 0.5em 0 1em; }
nav.switch select { font: inherit; margin-right: 1em; max-width: 30em; }
@media print { .plot-tools, .plot-tip, nav.switch { display: none; } }
)";

void insert_before_body_end(std::string& page, const std::string& text) {
  const std::size_t at = page.rfind("</body>");
  page.insert(at == std::string::npos ? page.size() : at, text);
}

}  // namespace

std::string with_interactive_plots(std::string page) {
  insert_before_body_end(page, fmt::format("<style>{}</style>\n<script>{}</script>\n", plot_style, plot_script()));
  return page;
}

std::string with_history_switcher(std::string page, const std::vector<std::string>& instruments,
                                  const std::string& instrument, const std::vector<std::string>& figures,
                                  const std::string& figure, report::Language language) {
  const bool zh = language == report::Language::chinese;
  const std::string lang_query = zh ? "lang=zh" : "";
  auto href = [&](const std::string& id, const std::string& f) {
    std::string query = f.empty() ? "" : "figure=" + percent_encoded(f, "/");
    if (!lang_query.empty()) query += (query.empty() ? "" : "&") + lang_query;
    return escape_xml("/instruments/" + percent_encoded(id) + (query.empty() ? "" : "?" + query));
  };
  std::string instrument_options;
  for (const auto& id : instruments) {
    instrument_options += fmt::format("<option value=\"{}\"{}>{}</option>", href(id, figure),
                                      id == instrument ? " selected" : "", escape_xml(id));
  }
  std::string figure_options = fmt::format("<option value=\"{}\"{}>{}</option>", href(instrument, ""),
                                           figure.empty() ? " selected" : "", zh ? "全部指标" : "All figures");
  for (const auto& f : figures) {
    figure_options += fmt::format("<option value=\"{}\"{}>{}</option>", href(instrument, f),
                                  f == figure ? " selected" : "", escape_xml(f));
  }
  const std::string nav = fmt::format(
      "<nav class=\"switch\"><a href=\"/{0}\">{1}</a> · <label>{2} <select id=\"instrument-switch\" "
      "onchange=\"window.location.href = this.value\">{3}</select></label><label>{4} <select id=\"figure-switch\" "
      "onchange=\"window.location.href = this.value\">{5}</select></label></nav>\n",
      zh ? "?lang=zh" : "", zh ? "被测仪表" : "Instruments", zh ? "仪表编号" : "Instrument", instrument_options,
      zh ? "指标" : "Figure", figure_options);
  const std::string header_end = "</header>\n";
  const std::size_t at = page.find(header_end);
  page.insert(at == std::string::npos ? 0 : at + header_end.size(), nav);
  return page;
}

}  // namespace inertest::serve
