// Power consumption (GJB 2426A-2004 5.4), through its declaration: hand-computed figures, the
// command, a plan with a limit, and the readings it refuses with their file, line and column.
#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "inertest/core/procedure_spec.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;

// Two readings each of +5 V (2.0 and 2.0582 W), +15 V (1.5 and 1.8 W) and -15 V (1.2 W twice).
constexpr const char* kReadings =
    "supply,voltage,current\n"
    "+5V,5.00,0.40\n"
    "+15V,15.0,0.10\n"
    "-15V,-15.0,-0.08\n"
    "+5V,5.02,0.41\n"
    "+15V,15.0,0.12\n"
    "-15V,-15.0,-0.08\n";

nlohmann::json run_on(const std::string& path) {
  const ProcedureSpec* spec = find_procedure_spec("power_consumption");
  EXPECT_NE(spec, nullptr);
  ProcedureCall call;
  call.files["supplies"] = path;
  spec->check(call);
  return spec->run(call).fields;
}

TEST(PowerConsumption, HandCase) {
  const testing::ScratchDirectory scratch;
  const nlohmann::json fields = run_on(scratch.write("supplies.csv", kReadings));
  // Per supply the mean of U I and its standard error (two readings: half their difference).
  const nlohmann::json& supplies = fields.at("supplies");
  ASSERT_EQ(supplies.size(), 3u);
  EXPECT_EQ(supplies[0].at("supply"), "+5V");
  EXPECT_EQ(supplies[0].at("readings"), 2);
  EXPECT_NEAR(supplies[0].at("power").at("value").get<double>(), 2.0291, 1e-12);
  EXPECT_NEAR(supplies[0].at("power").at("uncertainty").get<double>(), 0.0291, 1e-12);
  EXPECT_EQ(supplies[0].at("power").at("unit"), "W");
  EXPECT_NEAR(supplies[0].at("voltage").at("value").get<double>(), 5.01, 1e-12);
  EXPECT_EQ(supplies[0].at("voltage").at("unit"), "V");
  EXPECT_NEAR(supplies[0].at("current").at("value").get<double>(), 0.405, 1e-12);
  EXPECT_EQ(supplies[0].at("current").at("unit"), "A");
  EXPECT_NEAR(supplies[1].at("power").at("value").get<double>(), 1.65, 1e-12);
  EXPECT_NEAR(supplies[1].at("power").at("uncertainty").get<double>(), 0.15, 1e-12);
  // The negative rail: both negative, a positive power.
  EXPECT_NEAR(supplies[2].at("power").at("value").get<double>(), 1.2, 1e-12);
  EXPECT_EQ(supplies[2].at("power").at("uncertainty").get<double>(), 0.0);
  // The sum, with the root sum of squares of the supplies' uncertainties.
  const nlohmann::json& total = fields.at("power_consumption");
  EXPECT_NEAR(total.at("value").get<double>(), 4.8791, 1e-12);
  EXPECT_NEAR(total.at("uncertainty").get<double>(), std::sqrt(0.0291 * 0.0291 + 0.15 * 0.15), 1e-12);
  EXPECT_EQ(total.at("unit"), "W");
  // Two readings give a 1-sigma that holds the mean in half the tests (Student's t, 1 degree of
  // freedom), and it says so; equal readings make an uncertainty of 0 that the meters' resolution
  // makes, and it says so.
  ASSERT_EQ(fields.at("warnings").size(), 3u);
  EXPECT_THAT(fields.at("warnings")[0].get<std::string>(),
              HasSubstr("supply '+5V' has 2 readings: the 1-sigma of its power, estimated from so few, holds the true "
                        "mean in about 50 % of tests"));
  EXPECT_THAT(fields.at("warnings")[2].get<std::string>(), HasSubstr("'-15V' are all equal"));
}

// +5 V and -5 V readings under one name are two rails: said (their mean voltage of 0 is no rail's).
TEST(PowerConsumption, ReadingsOfBothSignsUnderOneNameAreWarnedAbout) {
  const testing::ScratchDirectory scratch;
  const nlohmann::json fields =
      run_on(scratch.write("rails.csv", "supply,voltage,current\n5V,5.01,0.4\n5V,-5.0,-0.4\n5V,5.0,0.41\n"));
  EXPECT_THAT(fields.at("warnings").dump(), HasSubstr("supply '5V' reads both positive and negative voltages (-5 V to "
                                                      "5.01 V): two rails under one name?"));
}

// Excel's "CSV UTF-8" starts with a byte order mark: the header's first name read as
// "\xEF\xBB\xBFsupply" and the file was refused with "'supply' is missing".
TEST(PowerConsumption, AByteOrderMarkIsNoPartOfTheHeader) {
  const testing::ScratchDirectory scratch;
  EXPECT_EQ(run_on(scratch.write("bom.csv", "\xEF\xBB\xBF" + std::string(kReadings))),
            run_on(scratch.write("plain.csv", kReadings)));
}

// A European Excel separates the cells with ';': the file was refused with "'supply' is missing".
TEST(PowerConsumption, SemicolonsOrTabsSeparateTheCells) {
  const testing::ScratchDirectory scratch;
  std::string semicolons = kReadings;
  std::replace(semicolons.begin(), semicolons.end(), ',', ';');
  std::string tabs = kReadings;
  std::replace(tabs.begin(), tabs.end(), ',', '\t');
  const nlohmann::json plain = run_on(scratch.write("plain.csv", kReadings));
  EXPECT_EQ(run_on(scratch.write("semicolons.csv", semicolons)), plain);
  EXPECT_EQ(run_on(scratch.write("tabs.csv", tabs)), plain);
}

TEST(PowerConsumption, OneReadingHasNoUncertainty) {
  const testing::ScratchDirectory scratch;
  const nlohmann::json fields =
      run_on(scratch.write("supplies.csv", "# one reading each\nsupply,current,voltage,time_s\n+5V,0.4,5,0\n+15V,0.1,15,0\n"));
  EXPECT_NEAR(fields.at("power_consumption").at("value").get<double>(), 3.5, 1e-12);
  EXPECT_FALSE(fields.at("power_consumption").contains("uncertainty"));
  EXPECT_EQ(fields.at("warnings").size(), 2u);
}

TEST(PowerConsumption, CommandAndPlan) {
  const testing::ScratchDirectory scratch;
  const std::string readings = scratch.write("supplies.csv", kReadings);
  const testing::CliRun command = testing::run_cli({"power-consumption", readings, "--json"});
  ASSERT_EQ(command.exit_code, 0) << command.err;
  const nlohmann::json json = nlohmann::json::parse(command.out);
  EXPECT_EQ(json.at("procedure"), "power_consumption");
  EXPECT_EQ(json.at("clause"), "GJB 2426A-2004 5.4");
  EXPECT_NEAR(json.at("power_consumption").at("value").get<double>(), 4.8791, 1e-12);
  const testing::CliRun text = testing::run_cli({"power-consumption", readings});
  EXPECT_THAT(text.out, HasSubstr("power consumption"));
  const std::string plan = scratch.write("plan.toml", R"([plan]
title = "FOG-001 power"

[instrument]
id = "FOG-001"
type = "gyro"
output_unit = "pulse/s"

[[procedure]]
kind = "power_consumption"
file = "supplies.csv"
[procedure.limits]
power_consumption = { max = 4.5, unit = "W" }
)");
  const testing::CliRun run = testing::run_cli({"run", plan, "--out", scratch.path() + "/out"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json results = nlohmann::json::parse(testing::read_file(scratch.path() + "/out/results.json"));
  ASSERT_EQ(results.at("verdicts").size(), 1u);
  EXPECT_EQ(results.at("verdicts")[0].at("figure"), "power_consumption");
  EXPECT_FALSE(results.at("verdicts")[0].at("pass").get<bool>());  // 4.88 W > 4.5 W
}

struct BadReadings {
  const char* name;
  const char* text;
  const char* where;    // file:line:column, after the file's path
  const char* message;  // part of it
};

class PowerConsumptionRefuses : public ::testing::TestWithParam<BadReadings> {};

TEST_P(PowerConsumptionRefuses, NamingFileLineAndColumn) {
  const testing::ScratchDirectory scratch;
  const std::string path = scratch.write("supplies.csv", GetParam().text);
  const testing::CliRun run = testing::run_cli({"power-consumption", path, "--json"});
  EXPECT_NE(run.exit_code, 0);
  EXPECT_TRUE(run.out.empty()) << run.out;
  EXPECT_THAT(run.err, HasSubstr(path + ":" + GetParam().where));
  EXPECT_THAT(run.err, HasSubstr(GetParam().message));
}

INSTANTIATE_TEST_SUITE_P(
    PowerConsumption, PowerConsumptionRefuses,
    ::testing::Values(
        BadReadings{"opposite_signs", "supply,voltage,current\n-15V,-15,0.08\n", "2:10", "opposite signs"},
        BadReadings{"not_a_number", "supply,voltage,current\n+5V,5.0,0.4A\n", "2:9", "current: '0.4A' is not a number"},
        BadReadings{"missing_column", "supply,voltage,amps\n+5V,5,0.4\n", "1:1", "'current' is missing"},
        BadReadings{"empty_name", "supply,voltage,current\n,5,0.4\n", "2:1", "supply: empty name"},
        BadReadings{"short_row", "supply,voltage,current\n+5V,5\n", "2:1", "2 columns, but the header has 3"},
        BadReadings{"no_readings", "supply,voltage,current\n", "1", "no readings"}),
    testing::NameOfParam());

}  // namespace
}  // namespace inertest
