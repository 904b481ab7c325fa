// CLI tests of scale-factor (points and raw records), scale-factor-repeatability,
// scale-factor-temperature, maximum-input-rate and input-axis-misalignment.
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "test_util/test_util.h"

namespace inertest {
namespace {

using testing::run_cli;
using testing::ScratchDirectory;
using ::testing::HasSubstr;

const std::vector<double> kRates = {0, 1, -1, 2, -2, 5, -5, 10, -10, 0};

std::string points_csv(double k, double bias = 0.5) {
  std::string text = "rate,output\n";
  for (double r : kRates) text += fmt::format("{},{:.17g}\n", r, k * r + bias);
  return text;
}

nlohmann::json run_json(const std::vector<std::string>& arguments) {
  const auto run = run_cli(arguments);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return run.exit_code == 0 ? nlohmann::json::parse(run.out) : nlohmann::json::object();
}

TEST(ScaleFactorCommand, PointsTableStillWorks) {
  ScratchDirectory scratch;
  const auto json = run_json({"scale-factor", scratch.write("points.csv", points_csv(3.0)), "--json"});
  EXPECT_NEAR(json.at("scale_factor").at("value").get<double>(), 3.0, 3e-12);
}

TEST(ScaleFactorCommand, OneLongRecordWithATableRateColumn) {
  // 10 Hz; each rate held 3 s; the first 0.5 s of each carries a transient of +50.
  ScratchDirectory scratch;
  std::string record = "time,table_rate,gyro\n";
  std::size_t i = 0;
  for (double r : kRates) {
    for (int k = 0; k < 30; ++k, ++i) {
      record += fmt::format("{},{},{:.17g}\n", i / 10.0, r, 3.0 * r + 0.5 + (k < 5 ? 50.0 : 0.0));
    }
  }
  const auto json = run_json({"scale-factor", "--record", scratch.write("record.csv", record), "--rate-column",
                              "table_rate", "--output-column", "gyro", "--sample-rate", "10", "--settling-time", "0.5",
                              "--json"});
  EXPECT_NEAR(json.at("scale_factor").at("value").get<double>(), 3.0, 3e-12);
  EXPECT_NEAR(json.at("static_output_start").at("value").get<double>(), 0.5, 1e-12);
}

TEST(ScaleFactorCommand, ARecordPerTestPoint) {
  ScratchDirectory scratch;
  std::string listing = "rate,file\n";
  for (std::size_t j = 0; j < kRates.size(); ++j) {
    std::string record = "output\n";
    for (int k = 0; k < 20; ++k) record += fmt::format("{:.17g}\n", 3.0 * kRates[j] + 0.5 + (k < 2 ? 9.0 : 0.0));
    const std::string name = fmt::format("p{}.csv", j);
    scratch.write(name, record);
    listing += fmt::format("{},{}\n", kRates[j], name);
  }
  const auto json = run_json({"scale-factor", "--records", scratch.write("list.csv", listing), "--sample-rate", "10",
                              "--settling-time", "0.2", "--json"});
  EXPECT_NEAR(json.at("scale_factor").at("value").get<double>(), 3.0, 3e-12);
}

TEST(ScaleFactorCommand, SettlingTimeLongerThanARecordNamesTheFile) {
  ScratchDirectory scratch;
  scratch.write("short.csv", "output\n1\n2\n");
  const auto listing = scratch.write("list.csv", "rate,file\n0,short.csv\n");
  const auto run = run_cli({"scale-factor", "--records", listing, "--sample-rate", "10", "--settling-time", "1"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("short.csv"));
  EXPECT_THAT(run.err, HasSubstr("not shorter than the record"));
}

TEST(ScaleFactorCommand, NoInputIsAnError) {
  const auto run = run_cli({"scale-factor", "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("exactly one of POINTS"));
}

TEST(ScaleFactorRepeatabilityCommand, SixRuns) {
  ScratchDirectory scratch;
  std::vector<std::string> arguments = {"scale-factor-repeatability"};
  const std::vector<double> k = {100, 101, 99, 100, 102, 98};
  for (std::size_t i = 0; i < k.size(); ++i) arguments.push_back(scratch.write(fmt::format("r{}.csv", i), points_csv(k[i])));
  arguments.push_back("--json");
  const auto json = run_json(arguments);
  EXPECT_NEAR(json.at("scale_factor_repeatability").at("value").get<double>(), std::sqrt(2.0) * 1e4, 1e-6);
  arguments.erase(arguments.begin() + 1);
  const auto five = run_cli(arguments);
  EXPECT_EQ(five.exit_code, 2);
  EXPECT_THAT(five.err, HasSubstr("Q >= 6"));
}

TEST(ScaleFactorTemperatureCommand, ListingOfTemperatures) {
  ScratchDirectory scratch;
  scratch.write("t20.csv", points_csv(100.0));
  scratch.write("t40.csv", points_csv(100.1));
  scratch.write("tm20.csv", points_csv(99.7));
  const auto listing = scratch.write("runs.csv", "temperature_degC,file\n20,t20.csv\n40,t40.csv\n-20,tm20.csv\n");
  const auto json = run_json({"scale-factor-temperature", listing, "--json"});
  EXPECT_NEAR(json.at("scale_factor_temperature_sensitivity").at("value").get<double>(), 75.0, 1e-6);
  EXPECT_EQ(json.at("scale_factor_temperature_sensitivity").at("unit"), "ppm/degC");
  const auto bad = run_cli({"scale-factor-temperature", listing, "--reference-temperature", "25"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("reference temperature"));
}

TEST(MaximumInputRateCommand, SaturatingGyro) {
  ScratchDirectory scratch;
  std::string text = "rate,output\n0,0\n";
  for (double r : {1.0, 2.0, 5.0, 10.0, 20.0}) {
    const double loss = r == 20.0 ? 0.01 : 0.0;
    text += fmt::format("{},{}\n{},{}\n", r, 10 * r * (1 - loss), -r, -10 * r * (1 - loss));
  }
  text += "0,0\n";
  const auto json =
      run_json({"maximum-input-rate", scratch.write("p.csv", text), "--nonlinearity-limit", "100", "--json"});
  EXPECT_EQ(json.at("maximum_input_rate").at("value").get<double>(), 10.0);
}

TEST(InputAxisMisalignmentCommand, TwoPositions) {
  ScratchDirectory scratch;
  // δ1 = 1e-4, δ2 = −2e-4 with K = 2, Ω = 100: F+ − F− = 2KΩδ = 0.04, −0.08.
  const auto path = scratch.write("pos.csv", "position,output_positive,output_negative\n1,5.02,4.98\n2,4.96,5.04\n");
  const auto json = run_json({"input-axis-misalignment", path, "--scale-factor", "2", "--rate", "100", "--json"});
  EXPECT_NEAR(json.at("misalignment").at("value").get<double>(), std::asin(std::sqrt(5e-8)) * 180 / 3.14159265358979323846 * 3600, 1e-6);
  EXPECT_EQ(json.at("misalignment").at("unit"), "arcsec");
  EXPECT_EQ(json.at("misalignment_deg").at("unit"), "deg");
  const auto bad = scratch.write("bad.csv", "position,output_positive,output_negative\n1,5.02,4.98\n3,4.96,5.04\n");
  const auto run = run_cli({"input-axis-misalignment", bad, "--scale-factor", "2", "--rate", "100"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr(bad + ":3"));
}

}  // namespace
}  // namespace inertest
