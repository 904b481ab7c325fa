#include "inertest/campaign/campaign.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "test_util/demo_campaign.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;

constexpr const char* kPoints = "rate,output\n0,1\n-2,-2.1\n-1,0\n1,4.1\n2,6\n0,3\n";

std::string plan_text(const std::string& procedure_extra, const std::string& limits = "") {
  return "[instrument]\nid = \"FOG-7\"\noutput_unit = \"pulse/s\"\n\n[site]\nlatitude_deg = 45.75\n\n"
         "[[procedure]]\nkind = \"scale_factor\"\nfile = \"points.csv\"\n" +
         procedure_extra + limits;
}

std::string error_of(const std::string& plan_path, const std::string& out) {
  try {
    run_campaign(plan_path, out);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(Campaign, RunsThePlanAndWritesResults) {
  testing::ScratchDirectory dir;
  dir.write("points.csv", kPoints);
  const std::string plan = dir.write("plan.toml", plan_text("name = \"SF\"\n",
                                                            "[procedure.limits]\n"
                                                            "nonlinearity = { max = 20000, unit = \"ppm\" }\n"
                                                            "\"/scale_factor_positive\" = { min = 1.95 }\n"));
  const auto summary = run_campaign(plan, dir.path() + "/out");
  ASSERT_TRUE(std::filesystem::exists(dir.path() + "/out/results.json"));
  const auto& results = summary.results;
  EXPECT_EQ(results["instrument"]["id"], "FOG-7");
  EXPECT_EQ(results["procedures"][0]["name"], "SF");
  EXPECT_NEAR_RELATIVE(results["procedures"][0]["result"]["scale_factor"]["value"].get<double>(), 2.03, 1e-14);
  ASSERT_EQ(results["verdicts"].size(), 2u);
  EXPECT_TRUE(results["verdicts"][0]["pass"].get<bool>());    // 17073 ppm <= 20000 ppm
  EXPECT_FALSE(results["verdicts"][1]["pass"].get<bool>());   // K(+) = 1.9 < 1.95
  EXPECT_EQ(results["verdict"], "FAIL");
  std::ifstream written(dir.path() + "/out/results.json");
  EXPECT_EQ(nlohmann::json::parse(written), results);
}

// When the test was done and when processed (the archive's ordering and its display): the plan's
// date, operator and station; processed_at in UTC ISO 8601, pinned by SOURCE_DATE_EPOCH.
TEST(Campaign, ResultsCarryTestDateAndProcessingTime) {
  testing::ScratchDirectory dir;
  dir.write("points.csv", kPoints);
  const std::string plan = dir.write(
      "plan.toml", "[plan]\ndate = \"2026-03-04\"\noperator = \"Li Wei\"\nstation = \"rate table 2\"\n\n" + plan_text(""));
  ::setenv("SOURCE_DATE_EPOCH", "1700000000", 1);  // 2023-11-14 22:13:20 UTC
  const auto summary = run_campaign(plan, dir.path() + "/out");
  ::unsetenv("SOURCE_DATE_EPOCH");
  EXPECT_EQ(summary.results["tested_on"], "2026-03-04");
  EXPECT_EQ(summary.results["processed_at"], "2023-11-14T22:13:20Z");
  EXPECT_EQ(summary.results["plan"]["operator"], "Li Wei");
  EXPECT_EQ(summary.results["plan"]["station"], "rate table 2");
  EXPECT_EQ(summary.results["results_schema_version"], 1);

  // Without a plan date the test date is the day of processing.
  const std::string undated = dir.write("undated.toml", plan_text(""));
  ::setenv("SOURCE_DATE_EPOCH", "0", 1);
  const auto undated_summary = run_campaign(undated, dir.path() + "/undated");
  ::unsetenv("SOURCE_DATE_EPOCH");
  EXPECT_EQ(undated_summary.results["tested_on"], "1970-01-01");
  EXPECT_EQ(undated_summary.results["processed_at"], "1970-01-01T00:00:00Z");

  // A TOML date is a date as well as the string.
  const std::string toml_date = dir.write("toml_date.toml", "[plan]\ndate = 2024-05-01\n\n" + plan_text(""));
  EXPECT_EQ(run_campaign(toml_date, dir.path() + "/toml_date").results["tested_on"], "2024-05-01");
}

TEST(Campaign, LimitsConvertUnits) {
  testing::ScratchDirectory dir;
  dir.write("points.csv", kPoints);
  // 17073 ppm = 1.7073 %: passes at 2 %, fails at 1.5 %.
  const std::string pass = dir.write("pass.toml", plan_text("", "[procedure.limits]\nnonlinearity = { max = 2, unit = \"%\" }\n"));
  EXPECT_EQ(run_campaign(pass, dir.path() + "/a").results["verdict"], "PASS");
  const std::string fail = dir.write("fail.toml", plan_text("", "[procedure.limits]\nnonlinearity = { max = 1.5, unit = \"%\" }\n"));
  EXPECT_EQ(run_campaign(fail, dir.path() + "/b").results["verdict"], "FAIL");
}

// A max alone bounds the magnitude: K = -2.03 (reversed polarity) fails max 2 and passes max 2.1;
// min with max bound the signed value (GJB/IEEE specifications "bias <= X" are magnitudes).
TEST(Campaign, AMaximumAloneBoundsTheMagnitude) {
  testing::ScratchDirectory dir;
  dir.write("points.csv", "rate,output\n0,-1\n-2,2.1\n-1,0\n1,-4.1\n2,-6\n0,-3\n");
  const auto verdict_of = [&](const std::string& name, const std::string& limit) {
    const std::string plan = dir.write(name + ".toml", plan_text("", "[procedure.limits]\nscale_factor = " + limit + "\n"));
    return run_campaign(plan, dir.path() + "/" + name).results["verdicts"][0];
  };
  const auto over = verdict_of("over", "{ max = 2.0 }");
  EXPECT_FALSE(over["pass"].get<bool>());
  EXPECT_NEAR(over["value"].get<double>(), -2.03, 1e-12);  // reported signed
  EXPECT_TRUE(over["magnitude"].get<bool>());
  EXPECT_TRUE(verdict_of("within", "{ max = 2.1 }")["pass"].get<bool>());
  EXPECT_TRUE(verdict_of("range", "{ min = -2.1, max = 2.0 }")["pass"].get<bool>());
  EXPECT_FALSE(verdict_of("range", "{ min = -2.1, max = 2.0 }").contains("magnitude"));
  EXPECT_FALSE(verdict_of("below", "{ min = -2.0 }")["pass"].get<bool>());
}

struct BadPlan {
  const char* name;
  std::string plan;
  const char* message;  // after "plan.toml"
};

class CampaignPlanErrors : public ::testing::TestWithParam<BadPlan> {};

TEST_P(CampaignPlanErrors, RejectedBeforeAnythingRuns) {
  testing::ScratchDirectory dir;
  dir.write("points.csv", kPoints);
  const std::string plan = dir.write("plan.toml", GetParam().plan);
  EXPECT_THAT(error_of(plan, dir.path() + "/out"), HasSubstr(plan + GetParam().message));
  EXPECT_FALSE(std::filesystem::exists(dir.path() + "/out"));
}

INSTANTIATE_TEST_SUITE_P(
    Campaign, CampaignPlanErrors,
    ::testing::Values(
        BadPlan{"unknown_key", plan_text("rate_units = \"deg/s\"\n"), ":11:1: plan.procedure[1]: unknown key 'rate_units'"},
        BadPlan{"missing_file", plan_text("").replace(plan_text("").find("points.csv"), 10, "nothere.csv"),
                ":10:8: plan.procedure[1]: data file 'nothere.csv' not found"},
        BadPlan{"unknown_kind", "[instrument]\nid = \"x\"\n[[procedure]]\nkind = \"teleport\"\n",
                ":4:8: plan.procedure[1]: 'kind' 'teleport' is not a known procedure"},
        BadPlan{"wrong_type", plan_text("rate_unit = 5\n"), ":11:13: plan.procedure[1]: 'rate_unit' must be a string"},
        BadPlan{"toml_syntax", "[instrument\nid = 1\n", ":1:"},
        // Ids the archive refuses, or that print as another instrument's.
        BadPlan{"dots_id", "[instrument]\nid = \"..\"\n[[procedure]]\nkind = \"scale_factor\"\nfile = \"points.csv\"\n",
                ":2:6: plan.instrument: 'id' '..' is only dots"},
        BadPlan{"blank_id", "[instrument]\nid = \"FOG-7 \"\n[[procedure]]\nkind = \"scale_factor\"\nfile = \"points.csv\"\n",
                ":2:6: plan.instrument: 'id' 'FOG-7 ' has blanks around it"},
        BadPlan{"no_break_id", "[instrument]\nid = \"FOG-7\u00a0\"\n[[procedure]]\nkind = \"scale_factor\"\nfile = \"points.csv\"\n",
                ":2:6: plan.instrument: 'id' 'FOG-7\u00a0' has blanks around it"},
        BadPlan{"zero_width_id", "[instrument]\nid = \"FOG\u200b-7\"\n[[procedure]]\nkind = \"scale_factor\"\nfile = \"points.csv\"\n",
                ":2:6: plan.instrument: 'id' 'FOG\u200b-7' holds an invisible character"},
        BadPlan{"no_instrument", "[[procedure]]\nkind = \"scale_factor\"\n", ":1:1: plan: missing [instrument] table"},
        BadPlan{"no_procedures", "[instrument]\nid = \"x\"\n", ":1:1: plan: no [[procedure]] tables"},
        BadPlan{"bad_latitude", "[instrument]\nid = \"x\"\n[site]\nlatitude_deg = 95\n", ":4:16: plan.site: 'latitude_deg' must lie in [-90, 90]"},
        BadPlan{"bad_limit", plan_text("", "[procedure.limits]\nnonlinearity = { unit = \"ppm\" }\n"), ":12:16: plan.procedure[1].limits.nonlinearity: a limit needs 'min', 'max' or both"},
        // Two unnamed steps of one kind share the name: the report gave both one verdict and the
        // archive refused the results (UNIQUE constraint); the second is refused, naming the first.
        BadPlan{"duplicate_step_name", plan_text("") + "[[procedure]]\nkind = \"scale_factor\"\nfile = \"points.csv\"\n",
                ":12:8: plan.procedure[2]: a procedure named 'scale_factor' is already at "},
        BadPlan{"duplicate_given_name",
                plan_text("name = \"SF\"\n") + "[[procedure]]\nkind = \"scale_factor\"\nname = \"SF\"\nfile = \"points.csv\"\n",
                ":14:8: plan.procedure[2]: a procedure named 'SF' is already at "},
        // Limits no figure can meet, or any meets: max = nan failed every figure (results.json "max":
        // null, the report "<= NaN"), inf passed every one, min 100 above max 5 failed every one.
        BadPlan{"nan_limit", plan_text("", "[procedure.limits]\nnonlinearity = { max = nan, unit = \"ppm\" }\n"),
                ":12:24: plan.procedure[1].limits.nonlinearity: 'max' must be a finite number (not nan or inf)"},
        BadPlan{"infinite_limit", plan_text("", "[procedure.limits]\nnonlinearity = { min = -inf, max = 5 }\n"),
                ":12:24: plan.procedure[1].limits.nonlinearity: 'min' must be a finite number"},
        BadPlan{"empty_range", plan_text("", "[procedure.limits]\nnonlinearity = { min = 100, max = 5, unit = \"ppm\" }\n"),
                ":12:24: plan.procedure[1].limits.nonlinearity: 'min' (100) is above 'max' (5): no value meets the limit"},
        BadPlan{"negative_magnitude", plan_text("", "[procedure.limits]\nnonlinearity = { max = -1 }\n"),
                ":12:24: plan.procedure[1].limits.nonlinearity: 'max' (-1) alone bounds the magnitude"},
        // An unknown unit in a limit named no file or line.
        BadPlan{"unknown_limit_unit", plan_text("", "[procedure.limits]\nnonlinearity = { max = 1, unit = \"ppmm\" }\n"),
                ":12:34: plan.procedure[1].limits.nonlinearity: 'unit' unknown unit 'ppmm'"},
        // "last tuesday" was written as tested_on, and the archive refused it later.
        BadPlan{"date_not_a_date", "[plan]\ndate = \"last tuesday\"\n" + plan_text(""),
                ":2:8: plan.plan: 'date' must be a day of the calendar written YYYY-MM-DD (e.g. 2026-03-04), not "
                "'last tuesday'"},
        BadPlan{"date_not_a_day", "[plan]\ndate = \"2026-02-30\"\n" + plan_text(""), ":2:8: plan.plan: 'date' must be a day"},
        BadPlan{"date_with_time", "[plan]\ndate = 2026-03-04T10:00:00\n" + plan_text(""), ":2:8: plan.plan: 'date' must be a date"},
        // A limit's unit is checked against the figure's declared unit before anything runs (ppm
        // against Hz failed after the step had run); a bare temperature is never converted.
        BadPlan{"incompatible_limit_unit", plan_text("", "[procedure.limits]\nnonlinearity = { max = 100, unit = \"Hz\" }\n"),
                ":12:16: limit on 'nonlinearity': procedure 'scale_factor' reports it in 'ppm': cannot convert 'ppm' "
                "(dimensionless) to 'Hz' (time^-1)"},
        // worst_temperature -40 degC was compared with a limit in K as -40 K.
        BadPlan{"absolute_temperature_in_another_unit",
                "[instrument]\nid = \"x\"\n[[procedure]]\nkind = \"scale_factor_temperature\"\n[procedure.limits]\n"
                "worst_temperature = { max = 200, unit = \"K\" }\n",
                ":6:21: limit on 'worst_temperature': procedure 'scale_factor_temperature' reports it in 'degC': cannot "
                "convert the temperature 'degC' to 'K'"},
        BadPlan{"unknown_top_level", "[instrument]\nid = \"x\"\n[sight]\n", ":3:2: plan: unknown key 'sight'"},
        // The archive names a figure PROCEDURE/FIGURE: "A/B" made "A/B/bias" ambiguous, "" printed as
        // "Bias ()", and "SF " and "SF" were two steps that print alike.
        BadPlan{"empty_name", plan_text("name = \"\"\n"),
                ":11:8: plan.procedure[1]: 'name' must be a non-empty name without '/' and without blanks around it"},
        BadPlan{"slash_in_name", plan_text("name = \"A/B\"\n"), ":11:8: plan.procedure[1]: 'name' must be a non-empty"},
        BadPlan{"blank_after_name", plan_text("name = \"SF \"\n"), ":11:8: plan.procedure[1]: 'name' must be a non-empty"}),
    testing::NameOfParam());

// A run that fails (here on a cell of its data, found only when the step runs) removes what it made
// of the output directory's path and nothing else: "staging/../reports" once removed the existing
// reports/ with an earlier report in it, having taken it for a directory the run had made.
TEST(Campaign, AFailedRunRemovesOnlyWhatItMade) {
  testing::ScratchDirectory dir;
  dir.write("points.csv", "rate,output\n0,1\n-2,-2.1\n-1,abc\n1,4.1\n2,6\n0,3\n");
  const std::string plan = dir.write("plan.toml", plan_text(""));
  const std::string kept = dir.write("reports/report_2024.html", "an earlier report");
  EXPECT_THAT(error_of(plan, dir.path() + "/staging/../reports"), HasSubstr("points.csv:4:"));
  EXPECT_EQ(testing::read_file(kept), "an earlier report");
  EXPECT_FALSE(std::filesystem::exists(dir.path() + "/staging"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() + "/reports/.inertest-exports"));
  EXPECT_THAT(error_of(plan, dir.path() + "/fresh/a/b"), HasSubstr("points.csv:4:"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() + "/fresh"));
  // An output "directory" that is a file is an error naming it (it was an internal error, exit 3).
  EXPECT_THAT(error_of(plan, dir.path() + "/plan.toml"), HasSubstr("plan.toml: the output directory is a file"));
}

// results.json and the report are written together: a report that cannot be written leaves no
// results without it (a directory where report.html goes: results.json had been written already).
TEST(Campaign, TheReportIsWrittenWithTheResultsOrNeither) {
  testing::ScratchDirectory dir;
  dir.write("points.csv", kPoints);
  const std::string plan = dir.write("plan.toml", plan_text(""));
  CampaignOptions options;
  options.report_page = [](const nlohmann::json& results) { return "<p>" + results.at("verdict").get<std::string>(); };
  const CampaignSummary summary = run_campaign(plan, dir.path() + "/out", options);
  ASSERT_EQ(summary.written_files.size(), 2u);
  EXPECT_EQ(summary.written_files.front(), dir.path() + "/out/results.json");
  EXPECT_EQ(testing::read_file(dir.path() + "/out/report.html"), "<p>NONE");
  std::filesystem::create_directories(dir.path() + "/blocked/report.html");
  try {
    run_campaign(plan, dir.path() + "/blocked", options);
    ADD_FAILURE() << "a directory in the way of report.html was not an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("report.html: a directory is where a file is to be written"));
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path() + "/blocked/results.json"));
}

TEST(Campaign, LimitOnAFigureThatDoesNotExist) {
  testing::ScratchDirectory dir;
  dir.write("points.csv", kPoints);
  const std::string plan = dir.write("plan.toml", plan_text("", "[procedure.limits]\nwobble = { max = 1 }\n"));
  EXPECT_THAT(error_of(plan, dir.path() + "/out"), HasSubstr("limit on 'wobble'"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() + "/out/results.json"));
}

// Every figure (or figure of a list) of a result whose field declares a unit (FieldSpec::unit) comes
// in that unit, made of the parameters it ran with; returns how many were compared.
std::size_t expect_declared_units(const ProcedureSpec& spec, const nlohmann::json& parameters,
                                  const nlohmann::json& result, const std::string& who) {
  std::size_t checked = 0;
  for (const FieldSpec& field : spec.fields) {
    const std::optional<std::string> unit = declared_unit(field, parameters);
    if (!unit || !result.contains(field.name)) continue;
    const auto& value = result.at(field.name);
    for (const auto& figure : value.is_array() ? value : nlohmann::json::array({value})) {
      EXPECT_EQ(figure.at("unit"), *unit) << who << " " << field.name;
      ++checked;
    }
  }
  return checked;
}

// The declared units are the units the figures come in. The demo campaign runs every plan kind;
// each step's units are made of the parameters validate_plan says it runs with ([instrument]
// output_unit "pulse/s", the accelerometer's "mA"...). The worked examples cover the kinds the demo
// lacks, with their defaults and the example's options, and a command's golden output the rest.
TEST(Campaign, DeclaredUnitsAreTheFiguresUnits) {
  const std::string demo = testing::demo_campaign_directory();
  const nlohmann::json plan = validate_plan(demo + "/lab/plan.toml");
  const auto results = nlohmann::json::parse(testing::read_file(demo + "/results.json"));
  std::size_t checked = 0;
  std::set<std::string> kinds;
  for (std::size_t i = 0; i < results.at("procedures").size(); ++i) {
    const auto& procedure = results.at("procedures").at(i);
    ASSERT_EQ(plan.at("procedures").at(i).at("name"), procedure.at("name"));
    const ProcedureSpec* spec = find_procedure_spec(procedure.at("kind").get<std::string>());
    if (spec == nullptr) continue;
    kinds.insert(spec->kind);
    checked += expect_declared_units(*spec, plan.at("procedures").at(i).at("parameters"), procedure.at("result"),
                                     procedure.at("name").get<std::string>());
  }
  for (const ProcedureSpec& spec : procedure_specs()) {
    if (spec.example.empty() || kinds.contains(spec.kind)) continue;
    nlohmann::json parameters = nlohmann::json::object();
    for (const auto& [name, value] : spec.defaults) parameters[name] = value;
    for (std::size_t a = 0; a + 1 < spec.example.size(); ++a) {
      for (const ParameterSpec& parameter : spec.parameters) {
        if (parameter.command_line_option() == spec.example[a]) parameters[parameter.name] = spec.example[a + 1];
      }
    }
    const testing::CliRun run = testing::run_example(spec);
    ASSERT_EQ(run.exit_code, 0) << spec.kind << ": " << run.err;
    checked += expect_declared_units(spec, parameters, nlohmann::json::parse(run.out), spec.kind + " example");
    kinds.insert(spec.kind);
  }
  // A kind in neither (warm_up_time): its command's golden output, the fixed units only.
  for (const ProcedureSpec& spec : procedure_specs()) {
    const std::string golden = testing::source_path("tests/golden/" + spec.kind + ".json");
    if (kinds.contains(spec.kind) || !std::filesystem::exists(golden)) continue;
    checked += expect_declared_units(spec, nlohmann::json::object(), nlohmann::json::parse(testing::read_file(golden)),
                                     spec.kind + " golden");
    kinds.insert(spec.kind);
  }
  EXPECT_EQ(kinds.size(), procedure_specs().size());
  EXPECT_GE(checked, 100u);
}

// A limit in a unit the figure's does not convert to is a plan error at the limit before anything
// runs, also where the figure's unit follows the parameters: a scale factor, in [instrument]
// output_unit per the step's rate_unit, limited in deg/s.
TEST(Campaign, LimitInAUnitTheFigureIsNotInIsAPlanError) {
  testing::ScratchDirectory dir;
  dir.write("points.csv", "not even csv");  // never read
  const auto error_at = [&](const std::string& limits) {
    return error_of(dir.write("plan.toml", plan_text("", "[procedure.limits]\n" + limits)), dir.path() + "/out");
  };
  const std::string wrong = error_at("scale_factor = { min = 1, max = 2, unit = \"deg/s\" }\n");
  EXPECT_THAT(wrong, HasSubstr("plan.toml:12:"));
  EXPECT_THAT(wrong, HasSubstr("limit on 'scale_factor': procedure 'scale_factor' reports it in 'pulse/s/(deg/s)'"));
  EXPECT_THAT(error_at("zero_offset = { max = 2, unit = \"V\" }\n"),
              HasSubstr("limit on 'zero_offset': procedure 'scale_factor' reports it in 'pulse/s'"));
  // Units that convert are judged after the run, as before.
  EXPECT_THAT(error_at("scale_factor = { min = 1, max = 2, unit = \"pulse/s/(rad/s)\" }\n"),
              HasSubstr("points.csv"));
}

TEST(Campaign, ValidatePlanDoesNotRun) {
  testing::ScratchDirectory dir;
  dir.write("points.csv", "not even csv");
  const auto plan = validate_plan(dir.write("plan.toml", plan_text("")));
  EXPECT_EQ(plan["procedures"][0]["kind"], "scale_factor");
}

}  // namespace
}  // namespace inertest
