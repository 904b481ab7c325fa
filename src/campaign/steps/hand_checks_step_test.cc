#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
#include "inertest/report/report.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using testing::ScratchDirectory;

const char* kHeader = R"([instrument]
id = "FOG-7"
nominal_scale_factor = 3600.0

[site]
latitude_deg = 60.0
)";

TEST(HandChecksStepTest, RunThatNeverSettlesFailsWhenRun) {
  ScratchDirectory scratch;
  scratch.write("drift.txt", "2.0\n1.5\n1.01\n1.0\n");
  const std::string plan = scratch.write("plan.toml", std::string(kHeader) + R"(
[[procedure]]
kind = "warm_up_time"
rest_band_deg_h = 0.1
sample_rate_hz = 2
[[procedure.run]]
file = "drift.txt"
)");
  try {
    run_campaign(plan, scratch.path() + "/out");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("never settles"));
  }
}

TEST(HandChecksStepTest, AllKindsRun) {
  ScratchDirectory scratch;
  scratch.write("th.csv", "rate,output\n0,10\n10,20\n2,11.5\n1,10.6\n-10,0\n-4,7\n-2,9.5\n");
  scratch.write("res.csv", "base_rate,base_output,rate,output\n100,0,110,10\n100,0,102,1.2\n100,0,101,0.4\n"
                           "-100,0,-110,-10\n-100,0,-104,-2.5\n-100,0,-103,-1\n");
  scratch.write("plus.txt", "5\n5\n");
  scratch.write("minus.txt", "-5\n-5\n");
  // Time column + output in deg/h (K = 3600): settles within 0.1 from t = 4 s.
  scratch.write("on.csv", "t,out\n1,1\n2,0.5\n3,0.2\n4,0.05\n5,0.01\n");
  // At 1 deg/h input (output 1 when settled): within 2 % from the sample at t = 3 s on.
  scratch.write("on_rate.csv", "t,out\n1,2.0\n2,1.5\n3,1.01\n4,1.0\n");
  const std::string plan = scratch.write("plan.toml", std::string(kHeader) + R"(
[[procedure]]
kind = "hand_checks"
[[procedure.check]]
name = "Appearance"
value = "pass"
[[procedure.check]]
name = "Insulation resistance"
value = 150.0
unit = "MOhm"
min = 20.0
[[procedure.check]]
name = "Power consumption"
value = 4.2
unit = "W"
max = 4.0

[[procedure]]
kind = "polarity"
positive_file = "plus.txt"
negative_file = "minus.txt"
expected = "positive"

[[procedure]]
kind = "threshold"
method = 1
file = "th.csv"
rate_unit = "deg/h"

[procedure.limits]
threshold = { max = 5.0, unit = "deg/h" }

[[procedure]]
kind = "resolution"
file = "res.csv"
rate_unit = "deg/h"

[[procedure]]
kind = "turn_on_time"
rest_band_deg_h = 0.1
rate_band = 0.02
[[procedure.run]]
file = "on.csv"
[[procedure.run]]
file = "on_rate.csv"
input_rate_deg_s = 0.0002777777777777778

[[procedure]]
kind = "warm_up_time"
rest_band_deg_h = 0.1
[[procedure.run]]
file = "on.csv"
)");
  const CampaignSummary summary = run_campaign(plan, scratch.path() + "/out");
  const auto& p = summary.results.at("procedures");
  const auto& checks = p.at(0).at("result");
  EXPECT_EQ(checks.at("appearance").at("value"), 1.0);
  EXPECT_EQ(checks.at("insulation_resistance").at("unit"), "MOhm");
  EXPECT_TRUE(checks.at("check_pass").at("insulation_resistance").get<bool>());
  EXPECT_FALSE(checks.at("check_pass").at("power_consumption").get<bool>());
  EXPECT_FALSE(checks.at("all_pass").get<bool>());
  EXPECT_EQ(p.at(1).at("result").at("polarity"), "positive");
  EXPECT_TRUE(p.at(1).at("result").at("pass").get<bool>());
  EXPECT_DOUBLE_EQ(p.at(2).at("result").at("threshold").at("value").get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(p.at(3).at("result").at("resolution").at("value").get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(p.at(4).at("result").at("turn_on_time").at("value").get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(p.at(4).at("result").at("runs").at(1).at("time").at("value").get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(p.at(5).at("result").at("warm_up_time").at("value").get<double>(), 4.0);
  EXPECT_TRUE(summary.results.at("verdicts").at(0).at("pass").get<bool>());
  // The checks' own bounds and pass/fail, and the polarity against `expected`, are verdicts of the
  // campaign with the plan's limits: the power consumption over its 4 W fails it (it read PASS).
  std::vector<std::string> judged;
  for (const auto& v : summary.results.at("verdicts")) {
    judged.push_back(fmt::format("{}/{} {} {}", v.at("procedure").get<std::string>(), v.at("figure").get<std::string>(),
                                 v.at("value").get<double>(), v.at("pass").get<bool>() ? "PASS" : "FAIL"));
  }
  EXPECT_EQ(judged, (std::vector<std::string>{"hand_checks/appearance 1 PASS", "hand_checks/insulation_resistance 150 PASS",
                                              "hand_checks/power_consumption 4.2 FAIL", "polarity/pass 1 PASS",
                                              "threshold/threshold 4 PASS"}));
  EXPECT_EQ(summary.results.at("verdict"), "FAIL");
  // The yes/no ones (a check by eye, the polarity as specified) say so, and read "yes" in the report,
  // not "1 (>= 1)".
  std::vector<bool> yes_no;
  for (const auto& v : summary.results.at("verdicts")) yes_no.push_back(v.value("yes_no", false));
  EXPECT_EQ(yes_no, (std::vector<bool>{true, false, false, true, false}));
  const std::string text = report::render_text_report(summary.results, {report::Language::english, ""});
  EXPECT_NE(text.find("  PASS  hand_checks / Appearance = yes (yes)\n"), std::string::npos) << text;
}

// A failed appearance check or a reversed polarity fails the campaign; a polarity without an
// expected one is no verdict.
TEST(HandChecksStepTest, AFailedCheckOrAReversedPolarityFailsTheCampaign) {
  ScratchDirectory scratch;
  scratch.write("plus.txt", "5\n5\n");
  scratch.write("minus.txt", "-5\n-5\n");
  const auto verdict_of = [&](const std::string& steps) {
    const std::string plan = scratch.write("plan.toml", std::string(kHeader) + steps);
    return run_campaign(plan, scratch.path() + "/out").results.at("verdict").get<std::string>();
  };
  const std::string polarity = "[[procedure]]\nkind = \"polarity\"\npositive_file = \"plus.txt\"\n"
                               "negative_file = \"minus.txt\"\n";
  EXPECT_EQ(verdict_of(polarity + "expected = \"negative\"\n"), "FAIL");
  EXPECT_EQ(verdict_of(polarity + "expected = \"positive\"\n"), "PASS");
  EXPECT_EQ(verdict_of(polarity), "NONE");
  EXPECT_EQ(verdict_of("[[procedure]]\nkind = \"hand_checks\"\n[[procedure.check]]\nname = \"Appearance\"\nvalue = \"fail\"\n"),
            "FAIL");
}

TEST(HandChecksStepTest, ThresholdCriterionDenominatorKey) {
  // Input 2 deg/h gives 60 % of its expected output: it passes the default criterion (relative to
  // the expected output) and fails eq. (15) as printed (relative to the measured output).
  ScratchDirectory scratch;
  scratch.write("th.csv", "rate,output\n0,0\n4,4\n2,1.2\n1,0.45\n-4,-4\n-2,-2\n-1,-0.45\n");
  const std::string plan = scratch.write("plan.toml", std::string(kHeader) + R"(
[[procedure]]
kind = "threshold"
method = 1
file = "th.csv"
rate_unit = "deg/h"

[[procedure]]
kind = "threshold"
name = "threshold, eq. 15 as printed"
method = 1
file = "th.csv"
rate_unit = "deg/h"
criterion_denominator = "measured"
)");
  const CampaignSummary summary = run_campaign(plan, scratch.path() + "/out");
  const auto& p = summary.results.at("procedures");
  EXPECT_EQ(p.at(0).at("result").at("criterion_denominator"), "expected");
  EXPECT_DOUBLE_EQ(p.at(0).at("result").at("threshold").at("value").get<double>(), 2.0);
  EXPECT_EQ(p.at(1).at("result").at("criterion_denominator"), "measured");
  EXPECT_DOUBLE_EQ(p.at(1).at("result").at("threshold").at("value").get<double>(), 4.0);
}

TEST(HandChecksStepTest, PlanErrors) {
  ScratchDirectory scratch;
  auto expect_error = [&](const std::string& body, const std::string& message) {
    const std::string plan = scratch.write("plan.toml", std::string(kHeader) + body);
    try {
      validate_plan(plan);
      FAIL() << "expected: " << message;
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr("plan.toml:"));
      EXPECT_THAT(e.what(), ::testing::HasSubstr(message));
    }
  };
  expect_error("[[procedure]]\nkind = \"hand_checks\"\n", "at least one [[procedure.check]]");
  expect_error("[[procedure]]\nkind = \"hand_checks\"\n[[procedure.check]]\nname = \"Appearance\"\nvalue = \"ok\"\n",
               "\"pass\" or \"fail\"");
  // An error of one check names its table (it named the [[procedure]] table of all of them).
  expect_error("[[procedure]]\nkind = \"hand_checks\"\n[[procedure.check]]\nname = \"A\"\nvalue = 1\nmin = 2\nmax = 1\n",
               "plan.toml:9:1: plan.procedure[1].check[1]: hand checks: 'A' has min 2 above max 1");
  expect_error("[[procedure]]\nkind = \"hand_checks\"\n[[procedure.check]]\nname = \"A\"\nvalue = 1\nunit = \"Mohms\"\n",
               "plan.toml:9:1: plan.procedure[1].check[1]: ");
  expect_error("[[procedure]]\nkind = \"hand_checks\"\n[[procedure.check]]\nname = \"Power, 15 V\"\nvalue = 1\n"
               "[[procedure.check]]\nname = \"power 15-V\"\nvalue = 2\n",
               "plan.toml:13:8: plan.procedure[1].check[2]: 'name' 'power 15-V' has the result key 'power_15_v' of the "
               "check at ");
  // A limit on a check the step does not have, or in a unit its value is not in, is found before
  // anything runs (it was found after every step had run).
  const std::string insulation =
      "[[procedure]]\nkind = \"hand_checks\"\n[[procedure.check]]\nname = \"Insulation resistance\"\nvalue = 150.0\n"
      "unit = \"MOhm\"\n[procedure.limits]\n";
  expect_error(insulation + "insulation = { min = 20 }\n",
               "plan.toml:14:14: limit on 'insulation': procedure 'hand_checks' reports no such figure (it reports: "
               "insulation_resistance, checks)");
  expect_error(insulation + "insulation_resistance = { min = 20, unit = \"V\" }\n",
               "limit on 'insulation_resistance': procedure 'hand_checks' reports it in 'MOhm'");
  EXPECT_NO_THROW(validate_plan(scratch.write("plan.toml", std::string(kHeader) + insulation +
                                                              "insulation_resistance = { min = 2e7, unit = \"ohm\" }\n")));
  expect_error("[[procedure]]\nkind = \"polarity\"\npositive_output = 1.0\n", "negative_file");
  expect_error("[[procedure]]\nkind = \"threshold\"\nmethod = 4\nfile = \"x\"\n", "must be 1, 2 or 3");
  scratch.write("x.csv", "rate,output\n");
  expect_error(
      "[[procedure]]\nkind = \"threshold\"\nmethod = 1\nfile = \"x.csv\"\ncriterion_denominator = \"theoretical\"\n",
      "criterion_denominator");
  expect_error("[[procedure]]\nkind = \"turn_on_time\"\n", "at least one [[procedure.run]]");
}

}  // namespace
}  // namespace inertest
