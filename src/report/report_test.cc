#include "inertest/report/report.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>

#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
#include "inertest/core/sha256.h"
#include "test_util/test_util.h"

namespace inertest::report {
namespace {

using inertest::testing::read_file;
using inertest::testing::ScratchDirectory;
using inertest::testing::source_path;
using ::testing::HasSubstr;
using ::testing::Not;

// The scale-factor example's points give Kn = 16.99 ppm, Ka = 35.03 ppm, K = 5000.088 pulse/s/(deg/s).
std::string plan_with_limits(const std::string& limits, const std::string& header = "") {
  return header + R"(
[instrument]
id = "FOG-T"
output_unit = "pulse/s"

[site]
name = "Hall 2"

[[procedure]]
kind = "scale_factor"
name = "SF 20 degC"
file = ")" +
         source_path("examples/scale_factor/points.csv") + "\"\n\n[procedure.limits]\n" + limits;
}

nlohmann::json run_plan(const ScratchDirectory& scratch, const std::string& plan) {
  const std::string path = scratch.write("plan.toml", plan);
  return run_campaign(path, scratch.path() + "/out").results;
}

// Every table row of the report about this figure of the procedure, as its HTML text.
std::vector<std::string> rows_about(const std::string& page, const std::string& figure) {
  std::vector<std::string> rows;
  const std::regex row("<tr data-procedure=\"SF 20 degC\" data-figure=\"" + figure + "\"[^>]*>.*?</tr>");
  for (auto it = std::sregex_iterator(page.begin(), page.end(), row); it != std::sregex_iterator(); ++it) {
    rows.push_back(it->str());
  }
  return rows;
}

void expect_rows(const std::string& page, const std::string& figure, const std::string& verdict, std::size_t count) {
  const auto rows = rows_about(page, figure);
  EXPECT_EQ(rows.size(), count) << figure;
  const std::string other = verdict == "pass" ? "fail" : "pass";
  for (const auto& row : rows) {
    EXPECT_THAT(row, HasSubstr("data-verdict=\"" + verdict + "\"")) << figure;
    EXPECT_THAT(row, HasSubstr("verdict-cell " + verdict + "\">" + (verdict == "pass" ? "PASS" : "FAIL"))) << figure;
    EXPECT_THAT(row, Not(HasSubstr("verdict-cell " + other))) << figure;
  }
}

TEST(Report, PlantedFailuresShowFailAndTheRestPassInBothDirections) {
  ScratchDirectory scratch;
  const auto results = run_plan(scratch, plan_with_limits(R"(nonlinearity = { max = 100, unit = "ppm" }
asymmetry = { max = 10, unit = "ppm" }
scale_factor = { min = 5001 }
scale_factor_positive = { min = 4999, max = 5001 }
)"));
  ASSERT_EQ(results.at("verdict"), "FAIL");
  const std::string page = render_report(results, {Language::english, "2024-01-02"});

  // Each limited figure appears in the summary, the procedure's table and the compliance table.
  expect_rows(page, "/nonlinearity", "pass", 3);           // 16.99 ppm <= 100 ppm
  expect_rows(page, "/asymmetry", "fail", 3);              // 35.03 ppm > 10 ppm: fails its maximum
  expect_rows(page, "/scale_factor", "fail", 3);           // 5000.09 < 5001: fails its minimum
  expect_rows(page, "/scale_factor_positive", "pass", 3);  // inside [4999, 5001]
  EXPECT_THAT(page, HasSubstr("≤ 10 ppm"));
  EXPECT_THAT(page, HasSubstr("≥ 5001 pulse/s/(°/s)"));
  EXPECT_THAT(page, HasSubstr("4999 … 5001"));
  EXPECT_THAT(page, HasSubstr("class=\"overall verdict-fail\" data-verdict=\"FAIL\""));
  // Figures without a limit get no verdict.
  for (const auto& row : rows_about(page, "/zero_offset")) EXPECT_THAT(row, Not(HasSubstr("data-verdict")));
}

TEST(Report, AllLimitsMetShowsAnOverallPass) {
  ScratchDirectory scratch;
  const auto results = run_plan(scratch, plan_with_limits(R"(nonlinearity = { max = 100, unit = "ppm" }
scale_factor = { min = 4990, max = 5010 }
)"));
  const std::string page = render_report(results, {Language::english, "2024-01-02"});
  expect_rows(page, "/nonlinearity", "pass", 3);
  expect_rows(page, "/scale_factor", "pass", 3);
  EXPECT_THAT(page, HasSubstr("class=\"overall verdict-pass\" data-verdict=\"PASS\""));
  EXPECT_THAT(page, Not(HasSubstr("verdict-cell fail")));
  EXPECT_THAT(page, HasSubstr(">Specification Kn ≤ 100 ppm<"));  // the limit drawn on the nonlinearity curve
}

// Two limits on one figure (by key and by pointer, or a hand check's own and the plan's): its rows
// show both and FAIL when either fails (they showed the last one's, PASS beside a failed limit).
TEST(Report, AFigureOfTwoLimitsShowsBothAndFailsWhenEitherFails) {
  ScratchDirectory scratch;
  for (const char* limits : {"nonlinearity = { max = 1, unit = \"ppm\" }\n\"/nonlinearity\" = { max = 100, unit = \"ppm\" }\n",
                             "\"/nonlinearity\" = { max = 100, unit = \"ppm\" }\nnonlinearity = { max = 1, unit = \"ppm\" }\n"}) {
    const auto results = run_plan(scratch, plan_with_limits(limits));
    const std::string page = render_report(results, {Language::english, "2024-01-02"});
    // The compliance table: a row per limit; the summary and the results: a row of the figure.
    std::size_t figure_rows = 0;
    for (const auto& row : rows_about(page, "/nonlinearity")) {
      const bool both = row.find("≤ 1 ppm; ≤ 100 ppm") != std::string::npos || row.find("≤ 100 ppm; ≤ 1 ppm") != std::string::npos;
      figure_rows += both ? 1 : 0;
      const bool fails = both || row.find("≤ 1 ppm") != std::string::npos;
      EXPECT_THAT(row, HasSubstr(fails ? "verdict-cell fail\">FAIL" : "verdict-cell pass\">PASS")) << row;
    }
    EXPECT_EQ(figure_rows, 2u);
  }
}

// A negative figure judged by its magnitude (a max alone) says so beside the limit.
TEST(Report, AMagnitudeVerdictShowsTheAbsoluteValueAgainstTheLimit) {
  ScratchDirectory scratch;
  auto results = run_plan(scratch, plan_with_limits("zero_offset = { max = 100 }\n"));
  nlohmann::json& verdict = results["verdicts"][0];
  verdict["value"] = -250.0;
  verdict["magnitude"] = true;
  verdict["pass"] = false;
  const std::string text = render_text_report(results, {Language::english, ""});
  EXPECT_THAT(text, HasSubstr("FAIL  SF 20 degC / Zero offset F0 = -250 pulse/s (|value| ≤ 100 pulse/s)"));
}

TEST(Report, WithoutLimitsThereIsNoVerdictColumn) {
  ScratchDirectory scratch;
  auto results = run_plan(scratch, plan_with_limits("nonlinearity = { max = 100 }\n"));
  results["verdicts"] = nlohmann::json::array();
  results["verdict"] = "NONE";
  const std::string page = render_report(results, {Language::english, ""});
  EXPECT_THAT(page, HasSubstr("data-verdict=\"NONE\""));
  EXPECT_THAT(page, Not(HasSubstr("class=\"verdict-cell")));
  EXPECT_THAT(page, Not(HasSubstr("id=\"compliance\"")));
}

TEST(Report, IsSelfContained) {
  ScratchDirectory scratch;
  const auto results = run_plan(scratch, plan_with_limits("nonlinearity = { max = 100 }\n"));
  const std::string page = render_report(results, {Language::english, "2024-01-02"});
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  for (const char* outside :
       {"<script", "<link", "http://", "https://", "url(", "@import", " src=", "<iframe", "<object", "@font-face"}) {
    EXPECT_THAT(page, Not(HasSubstr(outside))) << outside;
  }
  EXPECT_THAT(page, HasSubstr("<style>"));
  EXPECT_THAT(page, HasSubstr("@media print"));
  EXPECT_THAT(page, HasSubstr("break-before: page"));
  EXPECT_THAT(page, HasSubstr("<svg class=\"plot\""));
}

TEST(Report, ShowsInstrumentSitePlanVersionMethodAndFigures) {
  ScratchDirectory scratch;
  const auto results = run_plan(scratch, plan_with_limits("nonlinearity = { max = 100 }\n",
                                                          "[plan]\ntitle = \"Acceptance of FOG-T\"\n"
                                                          "date = \"2024-03-05\"\noperator = \"Li Wei\"\n"));
  const std::string page = render_report(results, {Language::english, "2030-12-31"});
  EXPECT_THAT(page, HasSubstr("<title>Acceptance of FOG-T</title>"));
  EXPECT_THAT(page, HasSubstr("FOG-T"));
  EXPECT_THAT(page, HasSubstr("Hall 2"));
  EXPECT_THAT(page, HasSubstr("Li Wei"));
  EXPECT_THAT(page, HasSubstr("<td>2024-03-05</td>"));  // the plan's date wins over the run date
  EXPECT_THAT(page, Not(HasSubstr("<td>2030-12-31</td>")));
  EXPECT_THAT(page, HasSubstr(results.at("inertest_version").get<std::string>()));
  EXPECT_THAT(page, HasSubstr("GJB 2426A-2004 5.8.1-5.8.3, eqs. (1)-(11)"));
  // Value and uncertainty to the uncertainty's second significant digit.
  // (The example's points are a smooth shape to 4 decimals: its noise is their rounding.)
  EXPECT_THAT(page, HasSubstr(">5000.088365<"));
  EXPECT_THAT(page, HasSubstr(">± 0.000065<"));
  EXPECT_THAT(page, HasSubstr("Nonlinearity curve"));
  // A plot is named for a screen reader by its caption.
  EXPECT_THAT(page, HasSubstr("role=\"img\" font-family="));
  EXPECT_THAT(page, ::testing::ContainsRegex("<title>Nonlinearity curve — GJB 2426A-2004 5.8.2.4, eqs. \\(7\\)-\\(9\\)</title>"));
  EXPECT_THAT(page, HasSubstr("<footer>Generated by inertest " + results.at("inertest_version").get<std::string>()));
  // The record the figures were computed from, with its size and SHA-256 (as sha256sum prints it).
  const std::string points = read_file(source_path("examples/scale_factor/points.csv"));
  EXPECT_THAT(page, HasSubstr("<h3>Records</h3>"));
  EXPECT_THAT(page, HasSubstr(fmt::format("<td class=\"num\">{}</td><td><code class=\"digest\">{}</code>", points.size(),
                                          sha256_hex(points))));
}

TEST(Report, RunDateStandsInWhenThePlanHasNone) {
  ScratchDirectory scratch;
  const auto results = run_plan(scratch, plan_with_limits("nonlinearity = { max = 100 }\n"));
  EXPECT_FALSE(results.at("plan").contains("date"));
  EXPECT_THAT(render_report(results, {Language::english, "2030-12-31"}), HasSubstr("<td>2030-12-31</td>"));
}

TEST(Report, ChineseUsesGjbTerms) {
  ScratchDirectory scratch;
  const auto results = run_plan(scratch, plan_with_limits(R"(nonlinearity = { max = 100, unit = "ppm" }
asymmetry = { max = 10, unit = "ppm" }
)"));
  const std::string page = render_report(results, {Language::chinese, "2024-01-02"});
  EXPECT_THAT(page, HasSubstr("<html lang=\"zh-CN\">"));
  for (const char* term :
       {"标度因数", "标度因数非线性度", "标度因数不对称性", "测试报告", "合格", "不合格", "总结论"}) {
    EXPECT_THAT(page, HasSubstr(term)) << term;
  }
  EXPECT_THAT(page, Not(HasSubstr(">Overall verdict<")));
  // The version inside the sentence, where Chinese puts it (it followed 生成).
  EXPECT_THAT(page, HasSubstr("<footer>由 inertest " + results.at("inertest_version").get<std::string>() + " 生成 · 2024-01-02"));
}

// A white-noise rate record (deg/h) at 10 Hz from a fixed-seed generator, one sample a line.
std::string white_noise_record(std::size_t samples) {
  std::string text = "rate\n";
  inertest::testing::UniformSequence uniform;
  for (std::size_t i = 0; i < samples; ++i) {
    double sum = 0.0;  // Irwin-Hall: the sum of 12 uniforms (each in [-0.5, 0.5)) is near-Gaussian, unit variance
    for (int k = 0; k < 12; ++k) sum += uniform.next();
    text += std::to_string(0.5 + 0.05 * sum) + "\n";
  }
  return text;
}

// The sections of the page, by kind, each with the number of plots in it.
std::map<std::string, int> plots_by_kind(const std::string& page) {
  std::map<std::string, int> plots;
  const std::regex section("<section class=\"procedure\" id=\"procedure-[0-9]+\" data-kind=\"([a-z_]+)\">");
  auto it = std::sregex_iterator(page.begin(), page.end(), section);
  std::vector<std::pair<std::string, std::size_t>> starts;
  for (; it != std::sregex_iterator(); ++it)
    starts.emplace_back((*it)[1].str(), static_cast<std::size_t>(it->position()));
  for (std::size_t i = 0; i < starts.size(); ++i) {
    const std::size_t end = i + 1 < starts.size() ? starts[i + 1].second : page.size();
    const std::string body = page.substr(starts[i].second, end - starts[i].second);
    int count = 0;
    for (auto at = body.find("<svg class=\"plot\""); at != std::string::npos;
         at = body.find("<svg class=\"plot\"", at + 1)) {
      ++count;
    }
    plots[starts[i].first] += count;
  }
  return plots;
}

TEST(Report, EveryProcedureOfAMixedCampaignGetsItsPlots) {
  ScratchDirectory scratch;
  scratch.write("rate.csv", white_noise_record(20000));
  const std::string plan = R"([instrument]
id = "FOG-MIX"
output_unit = "pulse/s"
sample_rate_hz = 10

[site]
latitude_deg = 45.75

[[procedure]]
kind = "scale_factor"
file = ")" + source_path("examples/scale_factor/points.csv") +
                           R"("

[[procedure]]
kind = "bias"
file = "rate.csv"
input = "deg/h"

[[procedure]]
kind = "allan"
file = "rate.csv"
input_unit = "deg/h"

[[procedure]]
kind = "bandwidth"
file = ")" + source_path("examples/bandwidth/gains.csv") +
                           R"("

[[procedure]]
kind = "gyro_misalignment"
file = ")" + source_path("data/misalignment/gyro_table1.csv") +
                           R"("
scale_factor = -2.9222

[[procedure]]
kind = "accelerometer_misalignment"
file = ")" + source_path("data/misalignment/accelerometer_table2.csv") +
                           R"("
scale_factor = 1.299

[[procedure]]
kind = "centrifuge"
file = ")" + source_path("data/centrifuge/table3_harmonics.csv") +
                           R"("
radius_m = 1.0
)";
  const auto results = run_plan(scratch, plan);
  const std::string page = render_report(results, {Language::english, "2024-01-02"});
  const auto plots = plots_by_kind(page);
  EXPECT_EQ(plots.at("scale_factor"), 1);
  EXPECT_EQ(plots.at("bias"), 2);  // the smoothed records, and Bs(τ) of the normalisation method
  EXPECT_EQ(plots.at("allan"), 1);
  EXPECT_EQ(plots.at("bandwidth"), 1);  // magnitude over phase in one figure
  EXPECT_EQ(plots.at("gyro_misalignment"), 2);
  EXPECT_EQ(plots.at("accelerometer_misalignment"), 1);  // the angles of each run (no per-position data)
  EXPECT_EQ(plots.at("centrifuge"), 2);                  // harmonics, residuals
  EXPECT_THAT(page, HasSubstr("−3 dB"));
  EXPECT_THAT(page, HasSubstr("Bw = 300"));
  EXPECT_THAT(page, HasSubstr("(slope −1/2)"));  // an Allan noise term with its slope
  // White noise only: the fit's verdict and range, and B held at zero shown as not identified.
  EXPECT_THAT(page, HasSubstr("fit of eq. (30): consistent (reduced χ² "));
  EXPECT_THAT(page, ::testing::ContainsRegex("Bias instability</td><td class=\"num\">not identified \\(&lt; [0-9.e+-]+\\)"));
  EXPECT_THAT(page, HasSubstr("10 s smoothing"));
  EXPECT_THAT(page, HasSubstr("k1s, 10 g"));
  EXPECT_THAT(page, HasSubstr("α = 180°"));
  // Bias stability at each smoothing time: a table of the declared field, one row per time.
  EXPECT_THAT(page, HasSubstr("<table class=\"rows\" data-table=\"/bias_stability\">\n<thead><tr><th>Smoothing (s)</th>"
                              "<th>Value</th></tr></thead>"));
  EXPECT_THAT(page, HasSubstr("<td class=\"num\" data-figure=\"/bias_stability/1/smoothing_s\">10</td>"));
  EXPECT_NE(page.find("Drift coefficients · DI<"), std::string::npos);
}

// A limit on a row of a table the data could not give (a smoothing time longer than the record)
// is in the summary as FAIL, under the row's name, and the row reads "not measured": the summary
// left it out while the verdict was FAIL, and the table printed the row's JSON in a cell.
TEST(Report, ANotMeasuredRowUnderALimitIsSummarisedAndTabulated) {
  ScratchDirectory scratch;
  scratch.write("rate.csv", white_noise_record(2000));
  const std::string plan = R"([instrument]
id = "FOG-NM"
output_unit = "pulse/s"
sample_rate_hz = 10

[[procedure]]
kind = "bias"
file = "rate.csv"
input = "deg/h"
smoothing_s = [1, 10, 2000]
[procedure.limits]
"/bias_stability/2" = { max = 0.05, unit = "deg/h" }
)";
  const std::string page = render_report(run_plan(scratch, plan), {Language::english, "2024-01-02"});
  const std::string summary = page.substr(0, page.find("Compliance with the specification</h2>"));
  EXPECT_THAT(summary, ::testing::ContainsRegex("Bias stability \\(2000 s\\)</td>.*not measured.*FAIL"));
  EXPECT_THAT(page, Not(HasSubstr("{&quot;")));
  EXPECT_THAT(page, Not(HasSubstr("not measured °/h")));
}

TEST(Report, ChecklistsAndTheDemoTruthCheckAreTabulated) {
  const nlohmann::json results = {
      {"inertest_version", "1.0.0"},
      {"plan", nlohmann::json::object()},
      {"instrument", {{"id", "X"}}},
      {"procedures",
       {{{"name", "checks"},
         {"kind", "hand_checks"},
         {"result",
          {{"clause", "GJB 2426A-2004 5.2-5.4"},
           {"checks",
            {{{"key", "appearance"}, {"name", "Appearance"}, {"pass", true}, {"value", "pass"}},
             {{"key", "insulation"},
              {"name", "Insulation resistance"},
              {"pass", false},
              {"value", 5.0},
              {"unit", "MOhm"},
              {"min", 20.0}}}}}}}}},
      {"verdicts", nlohmann::json::array()},
      {"verdict", "NONE"},
      {"truth_check",
       {{{"procedure", "scale_factor"},
         {"quantity", "scale factor"},
         {"true", 36000.0},
         {"measured", 36000.2},
         {"unit", "pulse/s/(deg/s)"},
         {"tolerance", 0.1},
         {"within", false}}}}};
  const std::string page = render_report(results, {Language::english, ""});
  EXPECT_THAT(page,
              HasSubstr("<td>Appearance</td><td class=\"num\">PASS</td><td></td><td class=\"verdict-cell pass\">"));
  EXPECT_THAT(page, HasSubstr("<td>Insulation resistance</td><td class=\"num\">5 MOhm</td><td>≥ 20 MOhm</td>"
                              "<td class=\"verdict-cell fail\">"));
  EXPECT_THAT(page, HasSubstr("id=\"truth-check\""));
  EXPECT_THAT(page, HasSubstr("<td class=\"num\">36000.2</td><td class=\"num\">± 0.1</td>"));
}

// The text report (what `inertest run` prints, the demo's report.txt) lists the figures the HTML
// report lists: nested ones (the Allan noise terms), an IMU's channels and a triad's elements too,
// each with its uncertainty and unit, then every limit's verdict and the overall verdict.
TEST(Report, TextReportListsTheFiguresOfTheHtmlReport) {
  std::ifstream in(source_path("tests/golden/demo_results.json"));
  const nlohmann::json results = nlohmann::json::parse(in);
  const std::string text = render_text_report(results, {Language::english, ""});
  EXPECT_THAT(text, HasSubstr("Test report: Instrument FOG-SIM-NAV\n"));
  const std::regex sections[] = {
      std::regex(R"(\nScale factor \(scale_factor\)\n  Scale factor K +[0-9.]+ ± [0-9.]+ pulse/s/\(°/s\)\n)"),
      std::regex(R"(\nAllan variance and random walk coefficient \(allan_long_static\)\n  Noise terms · Random walk coefficient +[0-9.]+ ± [0-9.]+ °/√h\n)"),
      std::regex(R"(\n  ax · Noise terms · Velocity random walk +[0-9.]+ ± [0-9.]+ m/s/√h\n)"),
      // Measured, but its coefficient within 2 sigma of zero: said so, with its upper bound.
      std::regex(R"(\n  ax · Noise terms · Acceleration random walk +[0-9.]+ ± [0-9.]+ m/s/h/√h, not significant \(< [0-9.]+\)\n)"),
      std::regex(R"(\n  Gyro triad · Scale factor x +[0-9.]+ ± [0-9.]+ count/\(rad/s\)\n)"),
      std::regex(R"(\n  Gyro triad · Misalignment zy +-?[0-9.]+ ± [0-9.]+ rad\n)"),
  };
  for (const std::regex& section : sections) EXPECT_TRUE(std::regex_search(text, section)) << text;
  EXPECT_THAT(text, HasSubstr("\nSpecification limits\n  PASS  scale_factor / Nonlinearity Kn = "));
  std::size_t limits = 0;
  for (auto at = text.find("\n  PASS  "); at != std::string::npos; at = text.find("\n  PASS  ", at + 1)) ++limits;
  for (auto at = text.find("\n  FAIL  "); at != std::string::npos; at = text.find("\n  FAIL  ", at + 1)) ++limits;
  EXPECT_EQ(limits, results.at("verdicts").size());
  EXPECT_THAT(text, HasSubstr("\nVerdict: " + results.at("verdict").get<std::string>() + "\n"));
}

// A limit on a term the analysis could not identify is judged by its upper bound (check_limit): the
// verdict shows it as a bound in both reports, as the figure's own row does (it read "= 0.0035").
TEST(Report, AVerdictOnAnUnidentifiedTermShowsItsBound) {
  std::ifstream in(source_path("tests/golden/demo_results.json"));
  nlohmann::json results = nlohmann::json::parse(in);
  results["verdicts"] = {{{"procedure", "allan"}, {"figure", "/noise/rate_random_walk"}, {"value", 0.00347},
                          {"unit", "deg/h/sqrt(h)"}, {"pass", true}, {"identified", false}, {"max", 0.01}}};
  results["verdict"] = "PASS";
  EXPECT_THAT(render_text_report(results, {Language::english, ""}),
              HasSubstr("PASS  allan / /noise/rate_random_walk = not identified (< 0.00347) °/h/√h"));
  EXPECT_THAT(render_report(results, {Language::english, ""}), HasSubstr("not identified (&lt; 0.00347) °/h/√h"));
}

// The row of the figure with this pointer in the section of the procedure with this name.
std::string figure_row(const std::string& page, const std::string& procedure, const std::string& pointer) {
  const std::string start = "<tr data-procedure=\"" + procedure + "\" data-figure=\"" + pointer + "\"";
  std::size_t at = page.rfind(start);  // the section's row comes after the summary's
  if (at == std::string::npos) return "";
  return page.substr(at, page.find("</tr>", at) - at);
}

// Figures deeper than three levels were dropped: the centrifuge's influence of each error alone
// (/influence/<error>/shift/<coefficient>, .../sensitivity/...) and the Allan fit's coefficients
// with their uncertainties (/noise/fit/coefficients/<i>), each an element of no name of its own.
TEST(Report, DeclaredFiguresAreListedWhateverTheirDepth) {
  std::ifstream in(source_path("tests/golden/demo_results.json"));
  const nlohmann::json results = nlohmann::json::parse(in);
  const std::string page = render_report(results, {Language::english, ""});
  for (const char* pointer : {"/influence/delta_omega/shift/D_I", "/influence/delta_omega/sensitivity/D_I",
                              "/influence/k1/shift/D_O", "/influence/k2/sensitivity/D_SS"}) {
    EXPECT_THAT(figure_row(page, "centrifuge", pointer), HasSubstr("Influence of each error alone")) << pointer;
  }
  const std::string coefficient = figure_row(page, "allan_long_static", "/noise/fit/coefficients/0");
  EXPECT_THAT(coefficient, HasSubstr("Noise terms · Fit · Coefficients (power -2)"));  // A_p, no drift coefficient
  EXPECT_THAT(coefficient, ::testing::ContainsRegex("<td class=\"num\">± [0-9.]+</td>"));
  // The PSD's periodic components of an IMU channel, six levels down.
  EXPECT_THAT(figure_row(page, "imu_noise", "/channels/gz/psd/peaks/0/frequency"), HasSubstr("± 0.000020"));
  // Every group of the summary heads a row (the IMU calibration's heading stood over none).
  const std::string summary = page.substr(page.find("<section class=\"summary\""),
                                          page.find("</section>", page.find("<section class=\"summary\"")) -
                                              page.find("<section class=\"summary\""));
  for (std::size_t at = summary.find("<tr class=\"group\">"); at != std::string::npos;
       at = summary.find("<tr class=\"group\">", at + 1)) {
    const std::size_t next = summary.find("<tr", summary.find("</tr>", at));
    ASSERT_NE(next, std::string::npos) << summary.substr(at, 200);
    EXPECT_NE(summary.compare(next, 18, "<tr class=\"group\">"), 0) << summary.substr(at, 200);
  }
  // A text wraps as text: set as a number on one line, threshold's criterion pushed the unit, the
  // limit and the verdict off the printed page.
  EXPECT_THAT(figure_row(page, "threshold", "/criterion"), HasSubstr("<td>Criterion</td><td>|(F_expected"));
  EXPECT_THAT(figure_row(page, "centrifuge", "/coefficients_g"), HasSubstr("</td><td>per standard g"));
}

// The bound against runaway nesting says what it leaves out instead of dropping it.
TEST(Report, NestingBeyondTheBoundIsNamedNotDropped) {
  nlohmann::json deep = {{"inner", {{"value", 1.0}, {"unit", "s"}}}};
  for (int level = 0; level < 40; ++level) deep = {{"level", deep}};
  const nlohmann::json results = {{"plan", nlohmann::json::object()},
                                  {"instrument", {{"id", "X"}}},
                                  {"procedures", {{{"name", "deep"}, {"kind", "future_kind"}, {"result", {{"a", deep}}}}}}};
  const std::string page = render_report(results, {Language::english, ""});
  EXPECT_THAT(page, HasSubstr("nested too deep to list: see results.json"));
}

// The rows of the table with this pointer in the section of the procedure with this kind.
std::size_t table_rows(const std::string& page, const std::string& kind, const std::string& pointer) {
  const std::size_t section = page.find("data-kind=\"" + kind + "\"");
  const std::size_t table = page.find("data-table=\"" + pointer + "\"", section);
  if (section == std::string::npos || table == std::string::npos) return 0;
  const std::string body = page.substr(table, page.find("</table>", table) - table);
  std::size_t rows = 0;
  for (auto at = body.find("<tr data-row="); at != std::string::npos; at = body.find("<tr data-row=", at + 1)) ++rows;
  return rows;
}

// Declared table fields whose elements do not name themselves were left out without notice: the
// temperature model's fit with each sensor and its cross-validation by order, the bandwidth's sine
// fits, the IMU calibration's static intervals. Each is a table: a column per member, numbers with
// their uncertainties and units, in the HTML and in the text report.
TEST(Report, DeclaredTablesAreTabulatedWhateverTheirElements) {
  std::ifstream in(source_path("tests/golden/demo_results.json"));
  const nlohmann::json results = nlohmann::json::parse(in);
  const std::string page = render_report(results, {Language::english, ""});
  const auto rows_in_results = [&](const std::string& kind, const std::string& field) {
    for (const auto& procedure : results.at("procedures")) {
      if (procedure.at("kind") == kind) return procedure.at("result").at(field).size();
    }
    return std::size_t{0};
  };
  for (const auto& [kind, field] : {std::pair{"temperature_model", "sensors"}, {"temperature_model", "order_selection"},
                                    {"bandwidth", "vibration_fits"}, {"imu_calibration", "static_intervals"}}) {
    const std::size_t rows = rows_in_results(kind, field);
    EXPECT_GT(rows, 1U) << kind << " " << field;
    EXPECT_EQ(table_rows(page, kind, std::string("/") + field), rows) << kind << " " << field;
  }
  EXPECT_THAT(page, HasSubstr("<thead><tr><th>Sensor</th><th>Order</th><th>RMS residual</th></tr></thead>"));
  EXPECT_THAT(page, HasSubstr("<tr data-row=\"/sensors/0\"><td data-figure=\"/sensors/0/sensor\">coil</td>"
                              "<td class=\"num\" data-figure=\"/sensors/0/order\">2</td>"
                              "<td class=\"num\" data-figure=\"/sensors/0/residual_rms\">0.00934 ± 0.00024 °/h</td></tr>"));
  EXPECT_THAT(page, HasSubstr("<td class=\"num\" data-figure=\"/vibration_fits/0/output_amplitude\">359949 ± 20 pulse/s</td>"));
  // An array of objects inside a row is a table of its own, its cell pointing to it.
  EXPECT_THAT(page, HasSubstr("data-table=\"/branches/0/points\""));
  EXPECT_THAT(page, HasSubstr(">7 rows (table below)</td>"));
  const std::string text = render_text_report(results, {Language::english, ""});
  EXPECT_THAT(text, HasSubstr("\n  Fit with each sensor\n    Sensor   Order  RMS residual\n"
                              "    coil     2      0.00934 ± 0.00024 °/h\n"));
}

// A long table is cut to its first 40 rows and says how many more results.json holds; a limit on a
// cell of a table still shows in the procedure's figures with its verdict.
TEST(Report, ALongTableSaysHowManyRowsItLeavesOut) {
  nlohmann::json biases = nlohmann::json::array();
  for (int i = 0; i < 55; ++i) biases.push_back({{"value", 0.01 * i}, {"unit", "deg/h"}});
  const nlohmann::json results = {
      {"plan", nlohmann::json::object()},
      {"instrument", {{"id", "X"}}},
      {"procedures",
       {{{"name", "repeat"},
         {"kind", "bias_repeatability"},
         {"result", {{"run_biases", biases}, {"bias_repeatability", {{"value", 0.2}, {"unit", "deg/h"}}}}}}}},
      {"verdicts",
       {{{"procedure", "repeat"}, {"figure", "/run_biases/50"}, {"value", 0.5}, {"unit", "deg/h"}, {"max", 0.4},
         {"pass", false}}}},
      {"verdict", "FAIL"}};
  const std::string page = render_report(results, {Language::english, ""});
  EXPECT_EQ(table_rows(page, "bias_repeatability", "/run_biases"), 40U);
  EXPECT_THAT(page, HasSubstr("<tr class=\"more\"><td colspan=\"1\">15 more rows in results.json</td></tr>"));
  EXPECT_THAT(figure_row(page, "repeat", "/run_biases/50"), HasSubstr("data-verdict=\"fail\""));
  EXPECT_THAT(render_text_report(results, {Language::english, ""}), HasSubstr("\n    15 more rows in results.json\n"));
}

// A periodic component of the PSD (the golden IMU's gz sinusoid) is captioned with the uncertainties
// of its frequency and amplitude, formatted as the tables format figures (GUM 7.2.6): the caption
// gave "1.25 Hz, 0.0101 °/s" while the JSON holds ± 2.0e-5 Hz and ± 9.9e-5 deg/s.
TEST(Report, PeriodicComponentsShowValueUncertaintyAndUnit) {
  std::ifstream in(source_path("tests/golden/demo_results.json"));
  const nlohmann::json results = nlohmann::json::parse(in);
  const std::string page = render_report(results, {Language::english, ""});
  EXPECT_THAT(page, HasSubstr("gz: periodic component 1.249999 ± 0.000020 Hz, 0.010080 ± 0.000099 °/s"));
}

TEST(Report, LanguageCodes) {
  EXPECT_EQ(parse_language("en"), Language::english);
  EXPECT_EQ(parse_language("zh"), Language::chinese);
  EXPECT_THROW(parse_language("fr"), Error);
}

TEST(Report, RejectsResultsThatAreNotACampaign) {
  EXPECT_THROW(render_report(nlohmann::json::array(), {}), Error);
  EXPECT_THROW(render_report(nlohmann::json{{"instrument", nlohmann::json::object()}}, {}), Error);
  EXPECT_THROW(render_report(nlohmann::json{{"instrument", nlohmann::json::object()}, {"procedures", 3}}, {}), Error);
}

TEST(Report, UnknownProceduresAreListedAndTheirCurvesPlotted) {
  const nlohmann::json results = {
      {"inertest_version", "9.9.9"},
      {"plan", nlohmann::json::object()},
      {"instrument", {{"id", "X"}}},
      {"procedures",
       {{{"name", "future"},
         {"kind", "future_kind"},
         {"result",
          {{"clause", "IEEE Std 952-1997 clause 99"},
           {"gain", {{"value", 1.5}, {"unit", "1"}, {"uncertainty", 0.25}}},
           {"nested", {{"inner", {{"value", 2.0}, {"unit", "s"}}}}},
           {"sweep_curve",
            {{{"frequency", {{"value", 1.0}, {"unit", "Hz"}}}, {"gain", {{"value", 1.0}, {"unit", "1"}}}},
             {{"frequency", {{"value", 10.0}, {"unit", "Hz"}}}, {"gain", {{"value", 0.9}, {"unit", "1"}}}},
             {{"frequency", {{"value", 1000.0}, {"unit", "Hz"}}}, {"gain", {{"value", 0.1}, {"unit", "1"}}}}}}}}}}},
      {"verdicts", nlohmann::json::array()},
      {"verdict", "NONE"}};
  const std::string page = render_report(results, {Language::english, ""});
  EXPECT_THAT(page, HasSubstr("data-figure=\"/gain\""));
  EXPECT_THAT(page, HasSubstr("data-figure=\"/nested/inner\""));
  EXPECT_THAT(page, HasSubstr(">1.50<"));
  EXPECT_THAT(page, HasSubstr(">± 0.25<"));
  EXPECT_THAT(page, Not(HasSubstr("data-figure=\"/sweep_curve")));  // a curve is plotted, not listed
  EXPECT_THAT(page, HasSubstr("<svg class=\"plot\""));
  EXPECT_THAT(page, HasSubstr("IEEE Std 952-1997 clause 99"));
}

TEST(Report, WriteReportWritesReportHtmlInTheDirectory) {
  ScratchDirectory scratch;
  const auto results = run_plan(scratch, plan_with_limits("nonlinearity = { max = 100 }\n"));
  const std::string path = write_report(results, scratch.path() + "/new/dir", {Language::english, "2024-01-02"});
  EXPECT_EQ(path, scratch.path() + "/new/dir/report.html");
  std::ifstream file(path);
  const std::string content((std::istreambuf_iterator<char>(file)), {});
  EXPECT_EQ(content, render_report(results, {Language::english, "2024-01-02"}));
}

TEST(Report, RunCommandWritesTheReportInTheChosenLanguage) {
  ScratchDirectory scratch;
  const std::string plan = scratch.write("plan.toml", plan_with_limits("nonlinearity = { max = 100 }\n"));
  const auto run = inertest::testing::run_cli({"run", plan, "--out", scratch.path() + "/out", "--lang", "zh"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::ifstream file(scratch.path() + "/out/report.html");
  const std::string content((std::istreambuf_iterator<char>(file)), {});
  EXPECT_THAT(content, HasSubstr("标度因数非线性度"));
  EXPECT_THAT(run.err, HasSubstr("report.html"));
  const auto bad = inertest::testing::run_cli({"run", plan, "--out", scratch.path() + "/out", "--lang", "fr"});
  EXPECT_NE(bad.exit_code, 0);
}

}  // namespace
}  // namespace inertest::report
