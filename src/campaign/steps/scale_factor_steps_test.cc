// Plan steps scale_factor (raw records), scale_factor_repeatability, scale_factor_temperature and
// maximum_input_rate, run through inertest::run_campaign.
#include <fmt/format.h>
#include <cmath>
#include <nlohmann/json.hpp>

#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using testing::ScratchDirectory;
using ::testing::HasSubstr;

const std::vector<double> kRates = {0, 1, -1, 2, -2, 5, -5, 10, -10, 0};

std::string points_csv(double k) {
  std::string text = "rate,output\n";
  for (double r : kRates) text += fmt::format("{},{:.17g}\n", r, k * r + 0.5);
  return text;
}

const char* kHeader = R"([instrument]
id = "FOG-1"
output_unit = "pulse/s"
sample_rate_hz = 10.0
)";

nlohmann::json run_plan(const ScratchDirectory& scratch, const std::string& procedures) {
  const auto plan = scratch.write("plan.toml", std::string(kHeader) + procedures);
  const auto summary = run_campaign(plan, scratch.path() + "/out");
  return summary.results.at("procedures").at(0).at("result");
}

TEST(ScaleFactorStep, OneLongRecord) {
  ScratchDirectory scratch;
  std::string record = "rate,output\n";
  for (double r : kRates) {
    for (int k = 0; k < 30; ++k) record += fmt::format("{},{:.17g}\n", r, 3.0 * r + 0.5 + (k < 5 ? 50.0 : 0.0));
  }
  scratch.write("record.csv", record);
  const auto result = run_plan(scratch, R"(
[[procedure]]
kind = "scale_factor"
record = "record.csv"
settling_time_s = 0.5
minimum_segment_s = 2.0
)");
  EXPECT_NEAR(result.at("scale_factor").at("value").get<double>(), 3.0, 3e-12);
}

TEST(ScaleFactorStep, ARecordPerPoint) {
  ScratchDirectory scratch;
  std::string runs;
  for (std::size_t j = 0; j < kRates.size(); ++j) {
    std::string record = "output\n";
    for (int k = 0; k < 20; ++k) record += fmt::format("{:.17g}\n", 3.0 * kRates[j] + 0.5 + (k < 2 ? 9.0 : 0.0));
    scratch.write(fmt::format("p{}.csv", j), record);
    runs += fmt::format("[[procedure.run]]\nrate = {}\nfile = \"p{}.csv\"\n", kRates[j], j);
  }
  const auto result = run_plan(scratch, "[[procedure]]\nkind = \"scale_factor\"\nsettling_time_s = 0.2\n" + runs);
  EXPECT_NEAR(result.at("scale_factor").at("value").get<double>(), 3.0, 3e-12);
}

// [instrument] output_unit = "pulse": a record per point holds counts per sample interval (10 Hz),
// whose K is that of the counts times 10, pulse/s per deg/s; a table of mean outputs is taken per
// second, as the same plan in pulse/s takes it.
TEST(ScaleFactorStep, PulseCountsOfTheInstrument) {
  ScratchDirectory scratch;
  std::string runs;
  for (std::size_t j = 0; j < kRates.size(); ++j) {
    std::string record = "output\n";
    for (int k = 0; k < 20; ++k) record += fmt::format("{:.17g}\n", (3.0 * kRates[j] + 0.5) / 10.0);
    scratch.write(fmt::format("p{}.csv", j), record);
    runs += fmt::format("[[procedure.run]]\nrate = {}\nfile = \"p{}.csv\"\n", kRates[j], j);
  }
  std::string header = kHeader;
  header.replace(header.find("pulse/s"), 7, "pulse");
  const auto plan = scratch.write("plan.toml", header + "[[procedure]]\nkind = \"scale_factor\"\n" + runs);
  const auto result = run_campaign(plan, scratch.path() + "/out").results.at("procedures").at(0).at("result");
  EXPECT_NEAR(result.at("scale_factor").at("value").get<double>(), 3.0, 3e-12);
  EXPECT_EQ(result.at("scale_factor").at("unit"), "pulse/s/(deg/s)");

  scratch.write("points.csv", points_csv(3.0));
  const auto table =
      scratch.write("table.toml", header + "[[procedure]]\nkind = \"scale_factor\"\nfile = \"points.csv\"\n");
  const auto of_table = run_campaign(table, scratch.path() + "/table").results.at("procedures").at(0).at("result");
  EXPECT_EQ(of_table, run_plan(scratch, "[[procedure]]\nkind = \"scale_factor\"\nfile = \"points.csv\"\n"));
  EXPECT_EQ(of_table.at("scale_factor").at("unit"), "pulse/s/(deg/s)");
}

TEST(ScaleFactorStep, FileAndRecordTogetherIsRejectedBeforeRunning) {
  ScratchDirectory scratch;
  scratch.write("points.csv", points_csv(3.0));
  const auto plan = scratch.write("plan.toml", std::string(kHeader) + R"(
[[procedure]]
kind = "scale_factor"
file = "points.csv"
record = "points.csv"
)");
  try {
    run_campaign(plan, scratch.path() + "/out");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("plan.toml:"));
    EXPECT_THAT(e.what(), HasSubstr("exactly one of"));
  }
}

TEST(ScaleFactorRepeatabilityStep, SixRunsAndTooFew) {
  ScratchDirectory scratch;
  const std::vector<double> k = {100, 101, 99, 100, 102, 98};
  std::string files;
  for (std::size_t i = 0; i < k.size(); ++i) {
    scratch.write(fmt::format("r{}.csv", i), points_csv(k[i]));
    files += fmt::format("{}\"r{}.csv\"", i ? ", " : "", i);
  }
  const auto result =
      run_plan(scratch, "[[procedure]]\nkind = \"scale_factor_repeatability\"\nfiles = [" + files + "]\n");
  EXPECT_NEAR(result.at("scale_factor_repeatability").at("value").get<double>(), std::sqrt(2.0) * 1e4, 1e-6);

  const auto plan = scratch.write("few.toml", std::string(kHeader) +
                                                  "[[procedure]]\nkind = \"scale_factor_repeatability\"\n"
                                                  "files = [\"r0.csv\", \"r1.csv\"]\n");
  try {
    run_campaign(plan, scratch.path() + "/out");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("few.toml:"));
    EXPECT_THAT(e.what(), HasSubstr("Q >= 6"));
  }
}

TEST(ScaleFactorTemperatureStep, RunsAtSeveralTemperatures) {
  ScratchDirectory scratch;
  scratch.write("t20.csv", points_csv(100.0));
  scratch.write("t40.csv", points_csv(100.1));
  scratch.write("tm20.csv", points_csv(99.7));
  const std::string step = R"(
[[procedure]]
kind = "scale_factor_temperature"
reference_temperature_degC = 20
[[procedure.run]]
temperature_degC = 40
file = "t40.csv"
[[procedure.run]]
temperature_degC = 20
file = "t20.csv"
[[procedure.run]]
temperature_degC = -20
file = "tm20.csv"
)";
  const auto result = run_plan(scratch, step);
  EXPECT_NEAR(result.at("scale_factor_temperature_sensitivity").at("value").get<double>(), 75.0, 1e-6);
  const auto plan = scratch.write("bad.toml", std::string(kHeader) + R"(
[[procedure]]
kind = "scale_factor_temperature"
reference_temperature_degC = 25
[[procedure.run]]
temperature_degC = 40
file = "t40.csv"
[[procedure.run]]
temperature_degC = 20
file = "t20.csv"
)");
  try {
    run_campaign(plan, scratch.path() + "/out");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.toml:8"));
    EXPECT_THAT(e.what(), HasSubstr("matches no run"));
  }
}

TEST(MaximumInputRateStep, SaturatingGyro) {
  ScratchDirectory scratch;
  std::string text = "rate,output\n0,0\n";
  for (double r : {1.0, 2.0, 5.0, 10.0, 20.0}) {
    const double loss = r == 20.0 ? 0.01 : 0.0;
    text += fmt::format("{},{}\n{},{}\n", r, 10 * r * (1 - loss), -r, -10 * r * (1 - loss));
  }
  text += "0,0\n";
  scratch.write("p.csv", text);
  const auto result = run_plan(scratch, R"(
[[procedure]]
kind = "maximum_input_rate"
file = "p.csv"
nonlinearity_limit_ppm = 100
)");
  EXPECT_EQ(result.at("maximum_input_rate").at("value").get<double>(), 10.0);
}

}  // namespace
}  // namespace inertest
