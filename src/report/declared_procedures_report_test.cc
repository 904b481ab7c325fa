// The report of every declared procedure is made from its declaration (issue 22): the test walks
// the registry (procedure_specs()) over the golden campaign's results (tests/golden/
// demo_results.json, every plan kind; a procedure it does not run by its worked example) and checks, per declared kind, its section's title in both
// languages, a row for every headline and detail figure it reports, and a plot of every curve it
// reports (and of every table its plot builder draws).
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/report/report.h"
#include "report/procedure_plots.h"
#include "report/result_access.h"
#include "test_util/test_util.h"

namespace inertest::report {
namespace {

using ::testing::HasSubstr;

// The golden campaign's results, with the worked example's result (ProcedureSpec::example) of every
// declared procedure that the campaign does not run.
nlohmann::json golden_results() {
  std::ifstream in(testing::source_path("tests/golden/demo_results.json"));
  nlohmann::json results = nlohmann::json::parse(in);
  for (const ProcedureSpec& spec : procedure_specs()) {
    bool in_campaign = false;
    for (const auto& p : results.at("procedures")) in_campaign = in_campaign || p.at("kind") == spec.kind;
    if (in_campaign || spec.example.empty()) continue;
    const testing::CliRun run = testing::run_example(spec);
    if (run.exit_code != 0) throw Error(spec.kind + " example: " + run.err);
    results["procedures"].push_back({{"kind", spec.kind}, {"name", spec.kind}, {"result", nlohmann::json::parse(run.out)}});
  }
  return results;
}

// The HTML of the section of the procedure with this kind.
std::string section_of(const std::string& page, const std::string& kind) {
  const std::size_t begin = page.find("data-kind=\"" + kind + "\"");
  if (begin == std::string::npos) return "";
  return page.substr(begin, page.find("</section>", begin) - begin);
}

// A figure, an unidentified term, or a declared text or yes/no (polarity's "positive" and "as
// specified", which the report left out).
bool is_reported_figure(const nlohmann::json& value) {
  return value.is_string() || value.is_boolean() || is_figure(value) || value.contains("upper_bound");
}

TEST(DeclaredProceduresReport, EverySectionShowsItsTitleFiguresAndCurves) {
  const nlohmann::json results = golden_results();
  const std::string english = render_report(results, ReportOptions{});
  ReportOptions chinese_options;
  chinese_options.language = Language::chinese;
  const std::string chinese = render_report(results, chinese_options);
  std::size_t curves = 0;
  for (const ProcedureSpec& spec : procedure_specs()) {
    const nlohmann::json* procedure = nullptr;
    for (const auto& p : results.at("procedures")) {
      if (p.at("kind") == spec.kind) procedure = &p;
    }
    ASSERT_NE(procedure, nullptr) << spec.kind << " is missing from tests/golden/simulation.toml and has no example";
    const nlohmann::json& result = procedure->at("result");
    const std::string section = section_of(english, spec.kind);
    ASSERT_FALSE(section.empty()) << spec.kind;
    EXPECT_THAT(section, HasSubstr(spec.title)) << spec.kind;
    ASSERT_FALSE(spec.title_zh.empty()) << spec.kind << " has no Chinese title";
    EXPECT_THAT(section_of(chinese, spec.kind), HasSubstr(spec.title_zh)) << spec.kind;
    for (const FieldSpec& field : spec.fields) {
      if (!result.contains(field.name)) continue;
      const nlohmann::json& value = result.at(field.name);
      const bool listed = field.role == FieldRole::headline || field.role == FieldRole::detail;
      if (listed && is_reported_figure(value)) {
        EXPECT_THAT(section, HasSubstr("data-figure=\"/" + field.name + "\"")) << spec.kind << " " << field.name;
        EXPECT_THAT(section, HasSubstr(Labels(Language::english).field_of(spec.kind, field.name))) << spec.kind << " " << field.name;
      }
      if (field.role == FieldRole::curve) {
        ++curves;
        EXPECT_THAT(section, HasSubstr("data-curve=\"" + field.name + "\"")) << spec.kind << " " << field.name;
      }
      if (field.role == FieldRole::table && find_plots(spec.kind) != nullptr &&
          section.find("data-curve=\"" + field.name + "\"") != std::string::npos) {
        ++curves;
      }
    }
  }
  RecordProperty("declared_curves_plotted", static_cast<int>(curves));
}

// Every declared headline, detail and table field that a result holds is in its procedure's section,
// by its pointer: a figure row (data-figure="/field" or a figure inside it, "/field/..."), or a table
// (data-table="/field"). A renamed key, or a value the report cannot render (a number, a member of
// no name, a figure too deep), fails here instead of vanishing from the report.
TEST(DeclaredProceduresReport, EveryDeclaredFieldOfAResultIsInItsSection) {
  const nlohmann::json results = golden_results();
  for (const Language language : {Language::english, Language::chinese}) {
    ReportOptions options;
    options.language = language;
    const std::string page = render_report(results, options);
    std::size_t checked = 0;
    for (const ProcedureSpec& spec : procedure_specs()) {
      const nlohmann::json& procedures = results.at("procedures");
      for (std::size_t index = 0; index < procedures.size(); ++index) {
        const nlohmann::json& procedure = procedures[index];
        if (procedure.at("kind") != spec.kind) continue;
        // The section of this step (a kind may run in several: allan_long_static, imu_noise).
        const std::size_t begin = page.find("id=\"procedure-" + std::to_string(index + 1) + "\"");
        ASSERT_NE(begin, std::string::npos) << procedure.at("name");
        const std::string section = page.substr(begin, page.find("</section>", begin) - begin);
        const nlohmann::json& result = procedure.at("result");
        for (const FieldSpec& field : spec.fields) {
          if (field.role == FieldRole::hidden || field.role == FieldRole::curve) continue;
          if (!result.contains(field.name) || result.at(field.name).is_null()) continue;
          const std::string pointer = "/" + field.name;
          const bool shown = section.find("data-figure=\"" + pointer + "\"") != std::string::npos ||
                             section.find("data-figure=\"" + pointer + "/") != std::string::npos ||
                             section.find("data-table=\"" + pointer + "\"") != std::string::npos;
          EXPECT_TRUE(shown) << spec.kind << " (" << procedure.at("name") << ") " << field.name
                             << " is declared and in the result but not in the report";
          if (field.role == FieldRole::table && result.at(field.name).is_array()) {
            EXPECT_NE(section.find("data-table=\"" + pointer + "\""), std::string::npos)
                << spec.kind << " " << field.name << " is a table field but no table";
          }
          ++checked;
        }
      }
    }
    EXPECT_GT(checked, 100U);
    RecordProperty("declared_fields_shown", static_cast<int>(checked));
  }
}

// The smoothed records of a bias run start at its start: padding the time axis below it drew a
// fifth of the plot as negative seconds.
TEST(DeclaredProceduresReport, TheBiasRecordPlotStartsAtTimeZero) {
  const nlohmann::json results = golden_results();
  const Labels labels(Language::english);
  const nlohmann::json verdicts = nlohmann::json::array();
  std::size_t checked = 0;
  for (const auto& procedure : results.at("procedures")) {
    if (procedure.at("kind") != "bias") continue;
    const PlotContext context{procedure.at("result"), labels, verdicts, find_procedure_spec("bias")};
    for (const ReportPlot& plot : procedure_plots("bias", context)) {
      if (plot.field != "smoothed_record") continue;
      ASSERT_TRUE(plot.plot.panels.at(0).x.min.has_value());
      EXPECT_EQ(*plot.plot.panels.at(0).x.min, 0.0);
      ++checked;
    }
  }
  EXPECT_GT(checked, 0U);
}

TEST(DeclaredProceduresReport, APlotOfAnUndeclaredCurveIsAnError) {
  const ProcedureSpec* spec = find_procedure_spec("polarity");
  ASSERT_NE(spec, nullptr);
  const nlohmann::json result = {{"renamed_curve", nlohmann::json::array()}};
  const Labels labels(Language::english);
  const nlohmann::json verdicts = nlohmann::json::array();
  const PlotContext context{result, labels, verdicts, spec};
  EXPECT_THROW(curve_of(context, "renamed_curve"), Error);
}

}  // namespace
}  // namespace inertest::report
