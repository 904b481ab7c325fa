#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using testing::ScratchDirectory;

std::string constant_record(double value, std::size_t count) {
  std::string text;
  for (std::size_t i = 0; i < count; ++i) text += nlohmann::json(value).dump() + "\n";
  return text;
}

const char* kHeader = R"([instrument]
id = "FOG-7"
output_unit = "pulse/s"
nominal_scale_factor = 3600.0
sample_rate_hz = 4

[site]
latitude_deg = 30.0
heading_deg = 0.0
)";

TEST(BiasStepTest, BiasRepeatabilityAndTemperatureFromAPlan) {
  ScratchDirectory scratch;
  // 4 Hz, 100 s alternating 1 s blocks of 1 ± 0.5: bias 1 deg/h, Bs(1 s) = 0.5·sqrt(100/99).
  std::string rest;
  for (int i = 0; i < 400; ++i) rest += (i / 4) % 2 == 0 ? "1.5\n" : "0.5\n";
  scratch.write("rest.txt", rest);
  for (int i = 1; i <= 6; ++i) scratch.write("run" + std::to_string(i) + ".txt", constant_record(0.1 * i, 8));
  scratch.write("t20.txt", constant_record(1.0, 8));
  scratch.write("t60.txt", constant_record(2.0, 8));
  const std::string plan = scratch.write("plan.toml", std::string(kHeader) + R"(
[[procedure]]
kind = "bias"
file = "rest.txt"
smoothing_s = [1, 2]

[procedure.limits]
bias = { max = 2.0 }
"/bias_stability/0" = { max = 0.1, unit = "deg/h" }

[[procedure]]
kind = "bias"
name = "bias, Earth rate removed"
file = "rest.txt"
smoothing_s = [1]
remove_earth_rate = true

[[procedure]]
kind = "bias_repeatability"
files = ["run1.txt", "run2.txt", "run3.txt", "run4.txt", "run5.txt", "run6.txt"]

[[procedure]]
kind = "bias_temperature"
[[procedure.run]]
temperature_degC = 20
file = "t20.txt"
[[procedure.run]]
temperature_degC = 60
file = "t60.txt"
)");
  const CampaignSummary summary = run_campaign(plan, scratch.path() + "/out");
  const auto& procedures = summary.results.at("procedures");
  const auto& bias = procedures.at(0).at("result");
  EXPECT_NEAR(bias.at("bias").at("value").get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(bias.at("bias_stability").at(0).at("value").get<double>(), 0.5 * std::sqrt(100.0 / 99.0), 1e-12);
  EXPECT_NEAR(bias.at("bias_stability").at(1).at("value").get<double>(), 0.0, 1e-12);
  EXPECT_TRUE(bias.contains("random_walk_coefficient"));
  // IRA north at 30 deg N: Ωe cos 30° removed.
  const double earth = 7.2921150e-5 / (3.14159265358979323846 / 180.0) * 3600.0 * std::sqrt(3.0) / 2.0;
  EXPECT_NEAR(procedures.at(1).at("result").at("bias").at("value").get<double>(), 1.0 - earth, 1e-9);
  EXPECT_NEAR(procedures.at(2).at("result").at("bias_repeatability").at("value").get<double>(), 0.1 * std::sqrt(3.5),
              1e-12);
  EXPECT_NEAR(procedures.at(3).at("result").at("bias_temperature_sensitivity").at("value").get<double>(), 1.0 / 40.0,
              1e-12);
  // bias passes (1 <= 2), the 1 s stability fails (0.5 > 0.1).
  for (const auto& verdict : summary.results.at("verdicts")) {
    EXPECT_EQ(verdict.at("pass").get<bool>(), verdict.at("figure") == "bias") << verdict.dump();
  }
  EXPECT_EQ(summary.results.at("verdict"), "FAIL");
}

// [instrument] output_unit = "pulse": every bias step's records hold counts per sample interval (4 Hz),
// read as pulse/s, so counts a quarter of the rates give the rates' figures; records in deg/h are
// no counts and are read as they are.
TEST(BiasStepTest, PulseCountsOfTheInstrumentInEveryBiasStep) {
  ScratchDirectory scratch;
  for (int i = 1; i <= 6; ++i) {
    scratch.write("rates" + std::to_string(i) + ".txt", constant_record(0.1 * i + 0.01 * (i % 2), 8));
    scratch.write("counts" + std::to_string(i) + ".txt", constant_record((0.1 * i + 0.01 * (i % 2)) / 4.0, 8));
  }
  const auto figures = [&](const std::string& unit, const std::string& prefix) {
    std::string header = kHeader;
    header.replace(header.find("pulse/s"), 7, unit);
    const std::string plan = scratch.write(prefix + ".toml", header + fmt::format(R"(
[[procedure]]
kind = "bias"
file = "{0}1.txt"
smoothing_s = [1]

[[procedure]]
kind = "bias_repeatability"
files = ["{0}1.txt", "{0}2.txt", "{0}3.txt", "{0}4.txt", "{0}5.txt", "{0}6.txt"]

[[procedure]]
kind = "bias_temperature"
[[procedure.run]]
temperature_degC = 20
file = "{0}1.txt"
[[procedure.run]]
temperature_degC = 60
file = "{0}2.txt"

[[procedure]]
kind = "bias"
name = "rates in deg per h"
file = "rates1.txt"
input = "deg/h"
smoothing_s = [1]
)", prefix));
    const CampaignSummary summary = run_campaign(plan, scratch.path() + "/" + prefix);
    nlohmann::json results = nlohmann::json::array();
    for (const auto& procedure : summary.results.at("procedures")) results.push_back(procedure.at("result"));
    return results;
  };
  const nlohmann::json of_rates = figures("pulse/s", "rates");
  const nlohmann::json of_counts = figures("pulse", "counts");
  for (std::size_t step = 0; step < 4; ++step) {
    for (const char* figure : {"bias", "bias_repeatability", "bias_temperature_sensitivity"}) {
      if (!of_rates.at(step).contains(figure)) continue;
      EXPECT_NEAR(of_counts.at(step).at(figure).at("value").get<double>(),
                  of_rates.at(step).at(figure).at("value").get<double>(), 1e-12)
          << step << " " << figure;
    }
  }
  EXPECT_NEAR(of_counts.at(3).at("bias").at("value").get<double>(), 0.11, 1e-12);  // deg/h as read
}

void expect_plan_error(const std::string& body, const std::string& message) {
  ScratchDirectory scratch;
  scratch.write("rest.txt", constant_record(1.0, 8));
  const std::string plan = scratch.write("plan.toml", body);
  try {
    run_campaign(plan, scratch.path() + "/out");
    FAIL() << "expected a plan error: " << message;
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("plan.toml:"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr(message));
  }
}

TEST(BiasStepTest, PlanErrorsNameTheLine) {
  const std::string no_rate = R"([instrument]
id = "x"
nominal_scale_factor = 1.0
[[procedure]]
kind = "bias"
file = "rest.txt"
)";
  expect_plan_error(no_rate, "sample_rate_hz");
  const std::string no_k = R"([instrument]
id = "x"
[[procedure]]
kind = "bias"
file = "rest.txt"
sample_rate_hz = 1
)";
  expect_plan_error(no_k, "scale_factor");
  expect_plan_error(std::string(kHeader) + "[[procedure]]\nkind = \"bias\"\nfile = \"missing.txt\"\n", "not found");
  expect_plan_error(std::string(kHeader) + "[[procedure]]\nkind = \"bias\"\nfile = \"rest.txt\"\nsmoothing_s = [-1]\n",
                    "smoothing time must be positive");
  expect_plan_error(std::string(kHeader) + "[[procedure]]\nkind = \"bias\"\nfile = \"rest.txt\"\ninput = \"V\"\n",
                    "input");
  expect_plan_error(std::string(kHeader) + "[[procedure]]\nkind = \"bias_repeatability\"\nfiles = [\"rest.txt\"]\n",
                    "at least 2 runs");
  // One record as two runs: at the key of the array, or at the later run's table, naming the first.
  const std::string twice = std::string(kHeader) + "[[procedure]]\nkind = \"bias_repeatability\"\nfiles = [\"rest.txt\", "
                                                   "\"./rest.txt\"]\n";
  expect_plan_error(twice, "plan.toml:12:9: the 1st and 2nd runs name one file, '");
  expect_plan_error(twice, "rest.txt': each run is a record of its own");
  const std::string tables = std::string(kHeader) +
                             "[[procedure]]\nkind = \"bias_temperature\"\n[[procedure.run]]\ntemperature_degC = 20\n"
                             "file = \"rest.txt\"\n[[procedure.run]]\ntemperature_degC = 60\nfile = \"rest.txt\"\n";
  expect_plan_error(tables, "plan.toml:16:20: the 1st and 2nd runs name one file, '");
  expect_plan_error(tables, "rest.txt' (the first at ");
  expect_plan_error(tables, "plan.toml:13:20): each run is a record of its own");
  expect_plan_error(std::string(kHeader) +
                        "[[procedure]]\nkind = \"bias_temperature\"\n[[procedure.run]]\ntemperature_degC = 20\n"
                        "file = \"rest.txt\"\ncolour = 1\n",
                    "unknown key 'colour'");
  // A limit on a row of bias stability names one of the smoothing times asked for (rows from 0),
  // checked before anything runs.
  const std::string stability = std::string(kHeader) + "[[procedure]]\nkind = \"bias\"\nfile = \"rest.txt\"\n"
                                                       "smoothing_s = [1, 10, 100]\n[procedure.limits]\n";
  expect_plan_error(stability + "\"/bias_stability/3\" = { max = 1 }\n",
                    "plan.toml:15:23: limit on '/bias_stability/3': procedure 'bias' reports 3 rows of 'bias_stability', "
                    "one per smoothing_s ([1.0,10.0,100.0]), numbered from 0: '3' is none of them");
  expect_plan_error(stability + "\"/bias_stability/one\" = { max = 1 }\n", "'one' is none of them");
  expect_plan_error(stability + "\"/bias_stability/01\" = { max = 1 }\n", "'01' is none of them");
}

// smoothing_s = [1, 3000, 10] on a 100 s record: 3000 s is left out, and the limit on
// "/bias_stability/1" (the 3000 s figure) was judged on the 10 s value, which had moved up. The row
// stays at its place, not measured, and a limit on it fails with the reason.
TEST(BiasStepTest, ALimitOnALeftOutSmoothingTimeIsNotMeasured) {
  ScratchDirectory scratch;
  std::string record;
  for (int i = 0; i < 400; ++i) record += (i % 2 == 0 ? "1\n" : "3\n");
  scratch.write("rest.txt", record);
  const std::string plan = scratch.write(
      "plan.toml", std::string(kHeader) +
                       "[[procedure]]\nkind = \"bias\"\nfile = \"rest.txt\"\nsmoothing_s = [1, 3000, 10]\n"
                       "[procedure.limits]\n\"/bias_stability/1\" = { max = 0.05, unit = \"deg/h\" }\n"
                       "\"/bias_stability/2\" = { max = 0.05, unit = \"deg/h\" }\n");
  const CampaignSummary summary = run_campaign(plan, scratch.path() + "/out");
  const auto& rows = summary.results.at("procedures").at(0).at("result").at("bias_stability");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1].at("smoothing_s"), 3000.0);
  EXPECT_TRUE(rows[1].at("value").is_null());
  EXPECT_FALSE(rows[1].at("measured").get<bool>());
  EXPECT_THAT(rows[1].at("reason").get<std::string>(), ::testing::HasSubstr("3000 s"));
  EXPECT_EQ(rows[2].at("smoothing_s"), 10.0);
  EXPECT_NEAR(rows[2].at("value").get<double>(), 0.0, 1e-12);  // whole periods of 1, 3: every mean 2

  const auto& verdicts = summary.results.at("verdicts");
  EXPECT_FALSE(verdicts[0].at("pass").get<bool>());
  EXPECT_TRUE(verdicts[0].at("value").is_null());
  EXPECT_FALSE(verdicts[0].at("measured").get<bool>());
  EXPECT_THAT(verdicts[0].at("reason").get<std::string>(), ::testing::HasSubstr("longer than the record"));
  EXPECT_TRUE(verdicts[1].at("pass").get<bool>());
  EXPECT_EQ(summary.results.at("verdict"), "FAIL");
}

// A declared figure the record cannot give (a random walk coefficient of a 2 s record) is left out
// of the result: a limit on it is not measured, FAIL, rather than an error after processing.
TEST(BiasStepTest, ALimitOnAFigureLeftOutIsNotMeasured) {
  ScratchDirectory scratch;
  scratch.write("rest.txt", constant_record(1.0, 6));
  const std::string plan = scratch.write(
      "plan.toml", std::string(kHeader) + "[[procedure]]\nkind = \"bias\"\nfile = \"rest.txt\"\nsmoothing_s = [0.5]\n"
                                          "[procedure.limits]\nrandom_walk_coefficient = { max = 0.01 }\n");
  const CampaignSummary summary = run_campaign(plan, scratch.path() + "/out");
  ASSERT_FALSE(summary.results.at("procedures").at(0).at("result").contains("random_walk_coefficient"));
  const auto& verdict = summary.results.at("verdicts").at(0);
  EXPECT_FALSE(verdict.at("pass").get<bool>());
  EXPECT_FALSE(verdict.at("measured").get<bool>());
}

// A dead gyro (a constant output) measures no bias stability or random walk: limits on them FAIL as
// not measured (its spreads of 0 passed them, and the campaign with them).
TEST(BiasStepTest, AConstantRecordFailsItsStabilityLimitsAsNotMeasured) {
  ScratchDirectory scratch;
  scratch.write("stuck.txt", constant_record(0.0, 3600));
  const std::string plan = scratch.write(
      "plan.toml", std::string(kHeader) + "[[procedure]]\nkind = \"bias\"\nfile = \"stuck.txt\"\nsmoothing_s = [1, 10]\n"
                                          "[procedure.limits]\nbias = { max = 0.05, unit = \"deg/h\" }\n"
                                          "\"/bias_stability/1\" = { max = 0.05, unit = \"deg/h\" }\n"
                                          "random_walk_coefficient = { max = 0.005, unit = \"deg/sqrt(h)\" }\n");
  const CampaignSummary summary = run_campaign(plan, scratch.path() + "/out");
  const auto& verdicts = summary.results.at("verdicts");
  ASSERT_EQ(verdicts.size(), 3u);
  EXPECT_TRUE(verdicts[0].at("pass").get<bool>());  // the bias, 0, is a measurement
  for (const std::size_t i : {1u, 2u}) {
    EXPECT_FALSE(verdicts[i].at("pass").get<bool>()) << i;
    EXPECT_FALSE(verdicts[i].at("measured").get<bool>()) << i;
  }
  EXPECT_EQ(summary.results.at("verdict"), "FAIL");
}

TEST(BiasStepTest, WindowLongerThanTheRecordIsAWarning) {
  ScratchDirectory scratch;
  scratch.write("rest.txt", constant_record(1.0, 8));
  const std::string plan =
      scratch.write("plan.toml", std::string(kHeader) + "[[procedure]]\nkind = \"bias\"\nfile = \"rest.txt\"\n");
  const CampaignSummary summary = run_campaign(plan, scratch.path() + "/out");
  const auto& result = summary.results.at("procedures").at(0).at("result");
  EXPECT_TRUE(result.contains("bias"));
  EXPECT_THAT(result.at("warnings").dump(), ::testing::HasSubstr("longer than the record"));
}

}  // namespace
}  // namespace inertest
