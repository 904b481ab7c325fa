#include "inertest/campaign/campaign.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "inertest/core/error.h"
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
        BadPlan{"no_instrument", "[[procedure]]\nkind = \"scale_factor\"\n", ":1:1: plan: missing [instrument] table"},
        BadPlan{"no_procedures", "[instrument]\nid = \"x\"\n", ":1:1: plan: no [[procedure]] tables"},
        BadPlan{"bad_latitude", "[instrument]\nid = \"x\"\n[site]\nlatitude_deg = 95\n", ":4:16: plan.site: 'latitude_deg' must lie in [-90, 90]"},
        BadPlan{"bad_limit", plan_text("", "[procedure.limits]\nnonlinearity = { unit = \"ppm\" }\n"), ":12:16: plan.procedure[1].limits.nonlinearity: a limit needs 'min', 'max' or both"},
        BadPlan{"unknown_top_level", "[instrument]\nid = \"x\"\n[sight]\n", ":3:2: plan: unknown key 'sight'"}),
    testing::NameOfParam());

TEST(Campaign, LimitOnAFigureThatDoesNotExist) {
  testing::ScratchDirectory dir;
  dir.write("points.csv", kPoints);
  const std::string plan = dir.write("plan.toml", plan_text("", "[procedure.limits]\nwobble = { max = 1 }\n"));
  EXPECT_THAT(error_of(plan, dir.path() + "/out"), HasSubstr("limit on 'wobble'"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() + "/out/results.json"));
}

TEST(Campaign, ValidatePlanDoesNotRun) {
  testing::ScratchDirectory dir;
  dir.write("points.csv", "not even csv");
  const auto plan = validate_plan(dir.write("plan.toml", plan_text("")));
  EXPECT_EQ(plan["procedures"][0]["kind"], "scale_factor");
}

}  // namespace
}  // namespace inertest
