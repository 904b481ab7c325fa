#include <nlohmann/json.hpp>

#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest::testing {
namespace {

using ::testing::HasSubstr;

// The paper's Table 3 coefficients are per its g of 9.8 m/s^2, the results per standard g: a
// coefficient of order n is (9.80665 / 9.8)^n times the paper's.
constexpr double kPerStandardG = 9.80665 / 9.8;

std::string plan_text(const std::string& data_file, const std::string& extra) {
  return "[instrument]\nid = \"G1\"\n[site]\nlatitude_deg = 45.75\ngravity_m_s2 = 9.8\n"
         "[[procedure]]\nkind = \"centrifuge\"\nname = \"drift\"\nfile = \"" +
         data_file + "\"\n" + extra;
}

TEST(CentrifugeStep, RunsTheExamplePlanOnTable3) {
  ScratchDirectory scratch;
  const CampaignSummary summary = run_campaign(source_path("examples/centrifuge/plan.toml"), scratch.path());
  const auto& result = summary.results["procedures"][0]["result"];
  EXPECT_NEAR(result["coefficients"]["D_I"]["value"].get<double>(), 1.5366 * kPerStandardG, 0.5e-4);
  EXPECT_NEAR(result["coefficients"]["D_F"]["value"].get<double>(), 0.90605, 0.5e-5);
  EXPECT_EQ(summary.results["verdict"], "PASS");
}

TEST(CentrifugeStep, SiteGivesLatitudeAndGravityAndCompensationCanBeOff) {
  ScratchDirectory scratch;
  const std::string plan = scratch.write(
      "plan.toml", plan_text(source_path("data/centrifuge/table3_harmonics.csv"),
                             "k1_rad = -2e-5\nk2_rad = 2e-5\ndelta_omega_rad_s = 1e-5\ncompensation = false\n"));
  const CampaignSummary summary = run_campaign(plan, scratch.path() + "/out");
  const auto& result = summary.results["procedures"][0]["result"];
  EXPECT_NEAR(result["coefficients"]["D_I"]["value"].get<double>(), -1.5268 * kPerStandardG, 0.5e-4);
  EXPECT_NEAR(result["site"]["gravity"]["value"].get<double>(), 9.8, 0.0);
}

TEST(CentrifugeStep, EstimatesErrors) {
  ScratchDirectory scratch;
  const std::string plan = scratch.write(
      "plan.toml", plan_text(source_path("data/centrifuge/table3_harmonics.csv"), "k2_rad = 2e-5\nestimate_errors = true\n"));
  const CampaignSummary summary = run_campaign(plan, scratch.path() + "/out");
  const auto& errors = summary.results["procedures"][0]["result"]["centrifuge_errors"];
  EXPECT_EQ(errors["k1"]["source"], "estimated");
  EXPECT_EQ(errors["k2"]["source"], "measured");
}

TEST(CentrifugeStep, UnknownKeyAndBadOptionsAreErrorsBeforeRunning) {
  ScratchDirectory scratch;
  const std::string table = source_path("data/centrifuge/table3_harmonics.csv");
  const std::string unknown = scratch.write("unknown.toml", plan_text(table, "radius = 1.0\n"));
  EXPECT_THROW(validate_plan(unknown), Error);
  const std::string contradictory =
      scratch.write("bad.toml", plan_text(table, "compensation = false\nestimate_errors = true\n"));
  try {
    validate_plan(contradictory);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("needs compensation"));
  }
}

}  // namespace
}  // namespace inertest::testing
