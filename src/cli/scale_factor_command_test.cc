// The scale-factor command's contract: `inertest scale-factor POINTS.csv --json`.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;
using testing::run_cli;

constexpr const char* kPoints = "rate,output\n0,1\n-2,-2.1\n-1,0\n1,4.1\n2,6\n0,3\n";

TEST(ScaleFactorCommand, JsonHoldsTheFiguresOfTheStandard) {
  testing::ScratchDirectory dir;
  const auto run = run_cli({"scale-factor", dir.write("points.csv", kPoints), "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);  // exactly one JSON object
  EXPECT_NEAR_RELATIVE(json["scale_factor"]["value"].get<double>(), 2.03, 1e-14);
  EXPECT_NEAR(json["zero_offset"]["value"].get<double>(), 0.0, 1e-14);
  EXPECT_NEAR_RELATIVE(json["nonlinearity"]["value"].get<double>(), 0.07 / 4.1 * 1e6, 1e-12);
  EXPECT_NEAR_RELATIVE(json["asymmetry"]["value"].get<double>(), 1e5, 1e-12);
  EXPECT_NEAR_RELATIVE(json["scale_factor_positive"]["value"].get<double>(), 1.9, 1e-14);
  EXPECT_NEAR_RELATIVE(json["scale_factor_negative"]["value"].get<double>(), 2.1, 1e-14);
  EXPECT_EQ(json["nonlinearity"]["unit"], "ppm");
  EXPECT_EQ(json["asymmetry"]["unit"], "ppm");
  EXPECT_EQ(json["nonlinearity_curve"].size(), 4u);
}

TEST(ScaleFactorCommand, ReadableReportWithoutJson) {
  testing::ScratchDirectory dir;
  const auto run = run_cli({"scale-factor", dir.write("points.csv", kPoints), "--output-unit", "pulse/s"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("scale factor K"));
  EXPECT_THAT(run.out, HasSubstr("pulse/s/(deg/s)"));
}

struct BadFile {
  const char* name;
  const char* content;
  const char* message;  // after "<path>"
};

class ScaleFactorCommandErrors : public ::testing::TestWithParam<BadFile> {};

TEST_P(ScaleFactorCommandErrors, ExitNonZeroWithLocatedMessageAndNoOutput) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("points.csv", GetParam().content);
  const auto run = run_cli({"scale-factor", path, "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  EXPECT_THAT(run.err, HasSubstr(path + GetParam().message));
}

INSTANTIATE_TEST_SUITE_P(
    Cli, ScaleFactorCommandErrors,
    ::testing::Values(
        BadFile{"malformed_number", "rate,output\n0,1\n-1,abc\n", ":3:4: expected a number in column 'output'"},
        BadFile{"wrong_column_count", "rate,output\n0,1\n-1\n", ":3:3: expected 2 columns, found 1"},
        BadFile{"nan", "rate,output\n0,1\nNaN,2\n", ":3:1: 'NaN' is not a finite number"},
        BadFile{"empty", "", ": no data"},
        BadFile{"unknown_column", "speed,output\n0,1\n", ":1:1: no column 'rate' in the header"},
        BadFile{"missing_static_run", "rate,output\n-1,-1\n-2,-2\n1,1\n2,2\n0,0\n", ": scale factor: missing the static run at the start"},
        BadFile{"too_few_points", "rate,output\n0,1\n-1,-1\n1,1\n0,1\n", ": scale factor: 1 positive rate(s)"}),
    testing::NameOfParam());

TEST(ScaleFactorCommand, MissingFileAndUnknownUnit) {
  auto run = run_cli({"scale-factor", "/nonexistent/points.csv", "--json"});
  EXPECT_NE(run.exit_code, 0);
  EXPECT_EQ(run.out, "");
  testing::ScratchDirectory dir;
  run = run_cli({"scale-factor", dir.write("p.csv", kPoints), "--rate-unit", "deg/fortnight", "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("unknown unit 'fortnight'"));
}

TEST(Cli, VersionAndHelp) {
  auto run = run_cli({"--version"});
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_THAT(run.out, HasSubstr("inertest 0."));
  run = run_cli({"scale-factor", "--help"});
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_THAT(run.out, HasSubstr("GJB 2426A-2004 5.8.1"));
}

}  // namespace
}  // namespace inertest
