// Plan kinds gyro_misalignment and accelerometer_misalignment through the campaign runner.
#include <fmt/format.h>

#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

std::string plan_text(const std::string& instrument_type, const std::string& nominal, const std::string& steps) {
  return fmt::format(
      "[plan]\ntitle = \"misalignment\"\n\n[instrument]\nid = \"X-1\"\ntype = \"{}\"\n"
      "output_unit = \"V\"\n{}\n[site]\nname = \"hall\"\nlatitude_deg = 45.75\n\n{}",
      instrument_type, nominal, steps);
}

TEST(MisalignmentSteps, GyroStepTakesTheNominalScaleFactorByDefault) {
  testing::ScratchDirectory scratch;
  const std::string plan = scratch.write(
      "plan.toml", plan_text("gyro", "nominal_scale_factor = -2.9222",
                             fmt::format("[[procedure]]\nkind = \"gyro_misalignment\"\nfile = \"{}\"\n\n"
                                         "[procedure.limits]\nmisalignment = {{ max = 180, unit = \"arcsec\" }}\n",
                                         testing::source_path("data/misalignment/gyro_table1.csv"))));
  const CampaignSummary summary = run_campaign(plan, scratch.path() + "/out");
  const auto& result = summary.results["procedures"][0]["result"];
  EXPECT_EQ(result["procedure"], "gyro_misalignment");
  EXPECT_NEAR(result["by_rate"][0]["delta_theta_y2"]["value"].get<double>(), -162.2, 0.1);
  EXPECT_EQ(result["scale_factor"]["unit"], "V/(deg/s)");
}

TEST(MisalignmentSteps, AccelerometerStepWithItsOwnScaleFactor) {
  testing::ScratchDirectory scratch;
  const std::string plan = scratch.write(
      "plan.toml", plan_text("accelerometer", "",
                             fmt::format("[[procedure]]\nkind = \"accelerometer_misalignment\"\nfile = \"{}\"\n"
                                         "scale_factor = 1.299\n",
                                         testing::source_path("data/misalignment/accelerometer_table2.csv"))));
  const CampaignSummary summary = run_campaign(plan, scratch.path() + "/out");
  const auto& result = summary.results["procedures"][0]["result"];
  EXPECT_NEAR(result["delta_theta_z2"]["value"].get<double>(), 20.5, 0.1);
  EXPECT_EQ(result["by_run"].size(), 3u);
}

// run_count = { min = 3 } passed validation, then failed after processing ("reports no such
// figure"): a declared count is judged as a plain number; with a unit it is refused beforehand.
TEST(MisalignmentSteps, ALimitOnTheRunCountIsJudged) {
  testing::ScratchDirectory scratch;
  const auto step = [](const std::string& limit) {
    return plan_text("accelerometer", "",
                     fmt::format("[[procedure]]\nkind = \"accelerometer_misalignment\"\nfile = \"{}\"\n"
                                 "scale_factor = 1.299\n[procedure.limits]\nrun_count = {}\n",
                                 testing::source_path("data/misalignment/accelerometer_table2.csv"), limit));
  };
  const auto verdict = run_campaign(scratch.write("plan.toml", step("{ min = 3 }")), scratch.path() + "/out")
                           .results.at("verdicts").at(0);
  EXPECT_EQ(verdict.at("value"), 3.0);
  EXPECT_TRUE(verdict.at("pass").get<bool>());
  EXPECT_THROW(validate_plan(scratch.write("unit.toml", step("{ min = 3, unit = \"1\" }"))), Error);
}

TEST(MisalignmentSteps, ZeroOrMissingScaleFactorFailsAtValidation) {
  testing::ScratchDirectory scratch;
  const std::string data = testing::source_path("data/misalignment/accelerometer_table2.csv");
  const std::string zero = scratch.write(
      "zero.toml", plan_text("accelerometer", "",
                             fmt::format("[[procedure]]\nkind = \"accelerometer_misalignment\"\nfile = \"{}\"\n"
                                         "scale_factor = 0.0\n",
                                         data)));
  EXPECT_THAT([&] { validate_plan(zero); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("scale factor kI must be finite and nonzero")));
  const std::string missing = scratch.write(
      "missing.toml",
      plan_text("gyro", "", fmt::format("[[procedure]]\nkind = \"gyro_misalignment\"\nfile = \"{}\"\n", data)));
  EXPECT_THAT([&] { validate_plan(missing); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr(
                  "missing 'scale_factor' (give it here or as [instrument] nominal_scale_factor)")));
}

// An [instrument]'s nominal scale factor is per deg/s for a gyro and per g for an accelerometer, and
// its output unit is that sensor's: an accelerometer step takes them from an accelerometer only (a
// gyro's 36000 pulse/s per deg/s was taken for kI per g), and a gyro step from a gyro only.
TEST(MisalignmentSteps, TheInstrumentsScaleFactorAppliesToItsOwnSensorOnly) {
  testing::ScratchDirectory scratch;
  const std::string accelerometer_data = testing::source_path("data/misalignment/accelerometer_table2.csv");
  const std::string accelerometer_step =
      fmt::format("[[procedure]]\nkind = \"accelerometer_misalignment\"\nfile = \"{}\"\n", accelerometer_data);
  const std::string of_a_gyro = scratch.write("gyro.toml", plan_text("gyro", "nominal_scale_factor = 1.299", accelerometer_step));
  EXPECT_THAT([&] { validate_plan(of_a_gyro); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr(
                  "missing 'scale_factor' (the plan's [instrument] nominal_scale_factor is a gyro's, which does not "
                  "apply to this step: give it here)")));
  const std::string of_its_own = scratch.write("own.toml", plan_text("accelerometer", "nominal_scale_factor = 1.299", accelerometer_step));
  const CampaignSummary summary = run_campaign(of_its_own, scratch.path() + "/out");
  const auto& result = summary.results["procedures"][0]["result"];
  EXPECT_NEAR(result["delta_theta_z2"]["value"].get<double>(), 20.5, 0.1);  // as with scale_factor = 1.299 in the step
  EXPECT_EQ(result["scale_factor"]["unit"], "V/g");

  const std::string gyro_step = fmt::format("[[procedure]]\nkind = \"gyro_misalignment\"\nfile = \"{}\"\n",
                                            testing::source_path("data/misalignment/gyro_table1.csv"));
  const std::string of_an_accelerometer =
      scratch.write("accelerometer.toml", plan_text("accelerometer", "nominal_scale_factor = -2.9222", gyro_step));
  EXPECT_THAT([&] { validate_plan(of_an_accelerometer); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("nominal_scale_factor is an accelerometer's")));
}

}  // namespace
}  // namespace inertest
