// The command made from a procedure's spec (issue 22): exactly one source per input, parameters
// checked before any file is read, and a procedure's complaint about a file's data naming the file.
#include <gmock/gmock.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;
using testing::run_cli;

TEST(ProcedureCommand, EachInputFromExactlyOneSource) {
  auto run = run_cli({"polarity", "--positive-output", "3"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("polarity: missing the output at the negative rate (--negative-file or "
                                 "--negative-output)"));
  run = run_cli({"polarity", "--positive-output", "3", "--positive-file", "x.csv", "--negative-output", "1"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("polarity: give a positive file or a positive output, not both"));
}

TEST(ProcedureCommand, ParametersAreCheckedAndErrorsNameTheFile) {
  testing::ScratchDirectory scratch;
  // Forward increments only: the reverse direction has no step (an error of the data, not a line).
  const std::string steps = scratch.write("steps.csv", "base_rate,base_output,rate,output\n100,0,110,10\n");
  auto run = run_cli({"resolution", steps, "--scale-factor", "0"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("the scale factor K must be a nonzero number"));
  run = run_cli({"resolution", steps, "--scale-factor", "1", "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_TRUE(run.out.empty());
  EXPECT_THAT(run.err, HasSubstr("inertest: error: " + steps + ": resolution:"));
}

// A unit parameter is a unit inertest reads, in every command (it was checked by some: bias printed
// "banana" as the output unit).
TEST(ProcedureCommand, AUnitParameterMustBeAUnit) {
  testing::ScratchDirectory scratch;
  const std::string record = scratch.write("rest.txt", "0.1\n0.2\n0.1\n0.2\n");
  for (const std::vector<std::string>& arguments :
       {std::vector<std::string>{"bias", record, "--scale-factor", "1", "--rate", "1", "--output-unit", "banana"},
        std::vector<std::string>{"polarity", "--positive-output", "3", "--negative-output", "-3", "--output-unit",
                                 "banana"},
        // each unit of a list too ("ch=banana" passed as a unit)
        std::vector<std::string>{"polarity", "--positive-output", "3", "--negative-output", "-3", "--output-unit",
                                 "ch=banana"}}) {
    const auto run = run_cli(arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments[0];
    EXPECT_TRUE(run.out.empty()) << arguments[0];
    EXPECT_THAT(run.err, HasSubstr("--output-unit")) << arguments[0];
    EXPECT_THAT(run.err, HasSubstr("banana")) << arguments[0];
  }
  // A list of units is its procedure's to read, with its own message.
  const std::string two = scratch.write("two.csv", "a,b\n0.1,0.2\n0.2,0.1\n0.1,0.2\n0.2,0.1\n");
  const auto unnamed = run_cli({"allan", two, "--rate", "1", "--columns", "a,b", "--input-unit", "deg/s,deg/h"});
  EXPECT_EQ(unnamed.exit_code, 2);
  EXPECT_THAT(unnamed.err, Not(HasSubstr("unknown unit")));
  const auto named = run_cli({"allan", two, "--rate", "1", "--columns", "a,b", "--input-unit", "a=deg/s,b=banana"});
  EXPECT_EQ(named.exit_code, 2);
  EXPECT_THAT(named.err, HasSubstr("--input-unit: unknown unit 'banana'"));
}

TEST(ProcedureCommand, RepeatedRunsAndAFlagThatGivesAParameter) {
  testing::ScratchDirectory scratch;
  const std::string first = scratch.write("run1.txt", "0.1\n0.1\n");
  const std::string second = scratch.write("run2.txt", "0.4\n0.4\n");
  // Records in deg/h already (--input-deg-h gives input = "deg/h"): biases 0.1 and 0.4, Br = 0.3/sqrt(2).
  auto run = run_cli({"bias-repeatability", first, second, "--input-deg-h", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_NEAR(json.at("bias_repeatability").at("value").get<double>(), 0.3 / std::sqrt(2.0), 1e-15);
  EXPECT_EQ(json.at("runs"), 2);
  run = run_cli({"bias-repeatability", first, second});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("missing the scale factor K"));
  // One record given twice (also by another path to it) would weigh one run as two.
  run = run_cli({"bias-repeatability", first, second, scratch.path() + "/./run1.txt", "--input-deg-h"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("inertest: error: " + scratch.path() + "/./run1.txt: the 1st and 3rd runs name one "
                                 "file: each run is a record of its own"));
  // K with records in deg/h would go unused: said, not ignored.
  run = run_cli({"bias-repeatability", first, second, "--input-deg-h", "--scale-factor", "36000"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("--scale-factor"));
  EXPECT_THAT(run.err, HasSubstr("exclude each other: records in deg/h are not divided by K"));
  // A record that stores its sample rate (HDF5, 200 Hz): a --rate that contradicts it is an error
  // naming both (the bias stability was computed at the rate given).
  const std::string stored = testing::source_path("data/lab_formats/record.h5");
  run = run_cli({"bias", stored, "--column", "imu/gyro_x", "--rate", "100", "--input-deg-h"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr(stored + ": the sample rate given, 100 Hz, contradicts the 200 Hz stored"));
  run = run_cli({"bias", stored, "--column", "imu/gyro_x", "--rate", "200", "--input-deg-h", "--json"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  // Without --rate the stored one is taken (the same figures); a record storing none needs it.
  const auto given_json = nlohmann::json::parse(run.out);
  run = run_cli({"bias", stored, "--column", "imu/gyro_x", "--input-deg-h", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out), given_json);
  run = run_cli({"bias", first, "--input-deg-h"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr(first + ": --rate is needed: the record stores no sample rate"));
  // A record that stores its unit: its deg/s are rates, converted to deg/h for --input-deg-h (they
  // were an error), for each procedure of eq. (19): 0.2495 deg/s (the mean, make_records.py) is
  // 898.2 deg/h. They are no output for K to divide (K = 36000 gave 0.025 deg/h, and a PASS).
  const std::string deg_s = testing::source_path("data/lab_formats/rate_deg_s.h5");
  const std::string copy = scratch.path() + "/copy.h5";  // a second run (one file twice is an error)
  std::filesystem::copy_file(deg_s, copy);
  run = run_cli({"bias", deg_s, "--input-deg-h", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NEAR(nlohmann::json::parse(run.out)["bias"]["value"].get<double>(), 0.2495 * 3600.0, 1e-9);
  run = run_cli({"bias-temperature", "--run", "20:" + deg_s, "--run", "40:" + copy, "--input-deg-h", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NEAR(nlohmann::json::parse(run.out)["runs"][0]["bias"]["value"].get<double>(), 0.2495 * 3600.0, 1e-9);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"bias", deg_s, "--scale-factor", "36000"},
        std::vector<std::string>{"bias-repeatability", deg_s, copy, "--scale-factor", "1"},
        std::vector<std::string>{"bias-temperature", "--run", "20:" + deg_s, "--run", "40:" + copy, "--scale-factor", "1"},
        std::vector<std::string>{"turn-on-time", "--run", "0:" + deg_s, "--scale-factor", "1", "--rest-band", "1"},
        std::vector<std::string>{"threshold", deg_s, "--method", "3", "--scale-factor", "36000", "--latitude", "40",
                                 "--table-rate", "0.36"}}) {
    run = run_cli(args);
    EXPECT_EQ(run.exit_code, 2) << args[0];
    EXPECT_THAT(run.err, HasSubstr(deg_s + ": the record stores its samples in deg/s, not the instrument's raw output that "
                                           "the scale factor K divides"))
        << args[0];
  }
  // An instrument whose output is in deg/s (K near 1) stores its own output: read as such.
  run = run_cli({"bias", deg_s, "--scale-factor", "1.0003", "--output-unit", "deg/s", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NEAR(nlohmann::json::parse(run.out)["bias"]["value"].get<double>(), 0.2495 / 1.0003 * 3600.0, 1e-9);
  run = run_cli({"bias", deg_s, "--scale-factor", "1.0003", "--output-unit", "deg/h"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("stores its samples in deg/s, not the instrument's output in deg/h that the scale factor K"));
  const std::string bad = scratch.write("bad.txt", "0.1\nabc\n");
  run = run_cli({"bias-repeatability", first, bad, "--input-deg-h"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr(bad + ":2:1: expected a number"));
}

// The help of a parameter says what a plan calls it where that is not the option's name (--rate is
// sample_rate_hz; the latitude is [site]'s), what a flag sets before what its parameter means, and what
// needs a parameter whose 0 stands for "not given" instead of showing that 0 as a default.
TEST(ProcedureCommand, TheHelpNamesThePlanKeyWhatAFlagSetsAndWhatNeedsAParameter) {
  const testing::CliRun threshold = run_cli({"threshold", "--help"});
  EXPECT_THAT(threshold.out, HasSubstr("[plan: sample_rate_hz]"));
  EXPECT_THAT(threshold.out, HasSubstr("site latitude (methods 2, 3), deg [plan: [site] latitude_deg]"));
  EXPECT_THAT(threshold.out, HasSubstr("method 3: table rate, deg/s [plan: table_rate_deg_s] (needed for method 3)"));
  const testing::CliRun centrifuge = run_cli({"centrifuge", "--help"});
  EXPECT_THAT(centrifuge.out, HasSubstr("--no-compensation           sets compensation = false; compensation: "));
  const testing::CliRun turn_on = run_cli({"turn-on-time", "--help"});
  EXPECT_THAT(turn_on.out, HasSubstr("allowed rate error relative to the input rate (needed for runs at rate)"));
  EXPECT_THAT(turn_on.out, ::testing::Not(HasSubstr("--rate-band FLOAT           allowed rate error relative to the "
                                                    "input rate (default")));
}

// NUMBER:FILE with a number out of a double's range (1e400) was a run at 0 (a room temperature of
// 0 degC, a run at rest), and "inf" was taken as a number.
TEST(ProcedureCommand, ARunNumberMustBeFinite) {
  testing::ScratchDirectory scratch;
  const std::string record = scratch.write("run.csv", "output\n1\n2\n3\n");
  for (const std::string number : {"1e400", "-1e309", "inf", "nan"}) {
    const auto run = run_cli({"bias-temperature", "--run", number + ":" + record, "--run", "-40:" + record, "--column",
                              "output", "--input-deg-h", "--json"});
    EXPECT_EQ(run.exit_code, 2) << number;
    EXPECT_THAT(run.err, HasSubstr("--run '" + number + ":" + record + "': expected NUMBER:FILE with a finite NUMBER"));
    EXPECT_EQ(run.out, "");
  }
}

}  // namespace
}  // namespace inertest
