// The plan step made from a procedure's spec (issue 22), on the declared polarity procedure.
#include "campaign/procedure_step.h"

#include <filesystem>

#include <nlohmann/json.hpp>

#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using testing::ScratchDirectory;

const char* kHeader = R"([instrument]
id = "FOG-7"
output_unit = "pulse/s"

)";

// Loads the plan (nothing runs) and expects an Error located in it that says `message`.
void expect_plan_error(const std::string& body, const std::string& message) {
  ScratchDirectory scratch;
  const std::string plan = scratch.write("plan.toml", std::string(kHeader) + body);
  try {
    validate_plan(plan);
    FAIL() << "expected: " << message;
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("plan.toml:"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr(message));
  }
}

TEST(ProcedureStep, KeysAreTheParameterNamesAndTheOutputUnitComesFromTheInstrument) {
  ScratchDirectory scratch;
  scratch.write("minus.csv", "output\n-4\n-6\n");  // mean -5
  const std::string plan = scratch.write("plan.toml", std::string(kHeader) + R"([[procedure]]
kind = "polarity"
positive_output = 5
negative_file = "minus.csv"
expected = "negative"
)");
  run_campaign(plan, scratch.path() + "/out");
  const auto result = nlohmann::json::parse(testing::read_file(scratch.path() + "/out/results.json"))
                          .at("procedures")
                          .at(0)
                          .at("result");
  EXPECT_EQ(result.at("polarity"), "positive");
  EXPECT_EQ(result.at("output_negative_rate").at("value"), -5.0);
  EXPECT_EQ(result.at("output_negative_rate").at("unit"), "pulse/s");
  EXPECT_FALSE(result.at("pass").get<bool>());
  EXPECT_EQ(result.at("clause"), "GJB 2426A-2004 5.7");
}

TEST(ProcedureStep, ARunIsNamedAsThePlanWritesItWhereverThePlanIsRunFrom) {
  // The run's file is read resolved against the plan's directory, but named in the results as the
  // plan writes it: run from another directory (the plan's path relative to it), the campaign's
  // results are the same, and the archive, which identifies a campaign by them, holds it once.
  ScratchDirectory scratch;
  scratch.write("lab/runs/power_on.csv", "time_s,output\n1,5\n2,0.1\n3,0\n4,0\n");
  const std::string plan = scratch.write("lab/plan.toml", std::string(kHeader) + R"([[procedure]]
kind = "turn_on_time"
scale_factor = 1
rest_band_deg_h = 1
[[procedure.run]]
file = "runs/../runs/power_on.csv"
)");
  const std::string plan_from_here = std::filesystem::relative(plan).string();
  ASSERT_TRUE(std::filesystem::path(plan_from_here).is_relative());
  run_campaign(plan, scratch.path() + "/a");
  run_campaign(plan_from_here, scratch.path() + "/b");
  const auto results = [&](const std::string& out) {
    auto json = nlohmann::json::parse(testing::read_file(scratch.path() + out + "/results.json"));
    json.erase("processed_at");
    return json;
  };
  EXPECT_EQ(results("/a").at("procedures").at(0).at("result").at("runs").at(0).at("name"), "runs/power_on.csv");
  EXPECT_EQ(results("/a"), results("/b"));
}

// A binary record has no time column: where the step gives no sample rate, the instrument's does (it was
// an error naming the record). A text record keeps its own stamps (1 s apart here, against 2 Hz).
TEST(ProcedureStep, ABinaryRecordTakesTheInstrumentsSampleRate) {
  ScratchDirectory scratch;
  scratch.write("power_on.f64", testing::f64_bytes({5.0, 0.1, 0.0, 0.0, 0.0}));
  scratch.write("power_on.csv", "time_s,output\n1,5\n2,0.1\n3,0\n4,0\n5,0\n");
  const auto turn_on = [&](const std::string& name, const std::string& instrument_rate, const std::string& step) {
    const std::string plan = scratch.write(name + ".toml", std::string(kHeader) + instrument_rate + R"(
[[procedure]]
kind = "turn_on_time"
scale_factor = 1
rest_band_deg_h = 1
)" + step);
    run_campaign(plan, scratch.path() + "/" + name);
    return nlohmann::json::parse(testing::read_file(scratch.path() + "/" + name + "/results.json"))
        .at("procedures")
        .at(0)
        .at("result")
        .at("turn_on_time");
  };
  const std::string binary = "format = \"f64\"\n[[procedure.run]]\nfile = \"power_on.f64\"\n";
  const nlohmann::json of_instrument = turn_on("instrument", "sample_rate_hz = 2\n", binary);
  EXPECT_EQ(of_instrument, turn_on("step", "", "sample_rate_hz = 2\n" + binary));
  EXPECT_EQ(of_instrument.at("value"), 1.5);  // the third sample is the first at rest: t = (i + 1) / 2 Hz
  EXPECT_EQ(turn_on("text", "", "[[procedure.run]]\nfile = \"power_on.csv\"\n").at("value"), 3.0);
  EXPECT_EQ(
      turn_on("text_with_rate", "sample_rate_hz = 2\n", "[[procedure.run]]\nfile = \"power_on.csv\"\n").at("value"),
      3.0);
}

TEST(ProcedureStep, EachInputFromExactlyOneSource) {
  expect_plan_error("[[procedure]]\nkind = \"polarity\"\nnegative_output = 1.0\n",
                    "needs exactly one of 'positive_file' and 'positive_output'");
  expect_plan_error("[[procedure]]\nkind = \"polarity\"\npositive_output = 1.0\npositive_file = \"plan.toml\"\n"
                    "negative_output = 2.0\n",
                    "needs exactly one of 'positive_file' and 'positive_output'");
}

TEST(ProcedureStep, ChoicesAndUnknownKeysAreCheckedBeforeAnythingRuns) {
  expect_plan_error("[[procedure]]\nkind = \"polarity\"\npositive_output = 1\nnegative_output = 2\nexpected = \"up\"\n",
                    "must be \"positive\" or \"negative\"");
  // The unit is the instrument's: a key of its own would be a second name for it.
  expect_plan_error(
      "[[procedure]]\nkind = \"polarity\"\npositive_output = 1\nnegative_output = 2\noutput_unit = \"V\"\n",
      "output_unit");
}

// A parameter the step has no key for (threshold's latitude, [site]'s) is asked for where it is given,
// before anything runs (it was found by the run, with no word of [site]).
TEST(ProcedureStep, AParameterOfTheSiteIsAskedForInTheSite) {
  expect_plan_error("[[procedure]]\nkind = \"threshold\"\nmethod = 2\nfile = \"plan.toml\"\nscale_factor = 1\n",
                    "latitude is needed by method 2: its input is the Earth rate's horizontal component, Omega_e "
                    "cos(latitude) (GJB 2426A eqs. 16-17) (give it as [site] latitude_deg)");
  // Said once (the Earth rate's message had said it too).
  ScratchDirectory scratch;
  const std::string plan = scratch.write("plan.toml", std::string(kHeader) +
                                                          "[[procedure]]\nkind = \"bias\"\nfile = \"plan.toml\"\n"
                                                          "scale_factor = 1\nremove_earth_rate = true\n");
  try {
    validate_plan(plan);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_THAT(message, ::testing::HasSubstr("latitude_deg is needed to remove the Earth rate (give it as [site] "
                                              "latitude_deg)"));
    EXPECT_EQ(message.find("[site]"), message.rfind("[site]")) << message;
  }
}

TEST(ProcedureStep, LimitOnAnUndeclaredFigureIsAPlanErrorBeforeAnythingRuns) {
  // validate_plan runs nothing: the declared fields decide.
  expect_plan_error("[[procedure]]\nkind = \"polarity\"\nname = \"pol\"\npositive_output = 1\nnegative_output = 2\n"
                    "[procedure.limits]\nwobble = { max = 1 }\n",
                    "limit on 'wobble': procedure 'pol' reports no such figure (it reports: polarity, sign,");
  expect_plan_error("[[procedure]]\nkind = \"polarity\"\nname = \"pol\"\npositive_output = 1\nnegative_output = 2\n"
                    "[procedure.limits]\n\"/wobble/value\" = { max = 1 }\n",
                    "limit on '/wobble/value': procedure 'pol' reports no such figure");
}

TEST(ProcedureStep, LimitOnAListOrATextIsAPlanErrorBeforeAnythingRuns) {
  const std::string step = "[[procedure]]\nkind = \"scale_factor\"\nname = \"sf\"\nfile = \"plan.toml\"\n";
  expect_plan_error(step + "[procedure.limits]\nnonlinearity_curve = { max = 1 }\n",
                    "limit on 'nonlinearity_curve': procedure 'sf' reports it as a list of rows (name one with a JSON "
                    "pointer, e.g. '/nonlinearity_curve/0/...')");
  expect_plan_error(step + "[procedure.limits]\nwarnings = { max = 1 }\n",
                    "limit on 'warnings': procedure 'sf' reports it as a text or a yes/no, not a figure or a number");
}

// A triad's bias and scale factors are [x, y, z], its misalignment 3x3: a limit on a whole one crashed
// after processing ("type must be number, but is array", no file or line). A limit names one element,
// as the report lists it and the archive keeps it, and is judged on it with the figure's unit.
TEST(ProcedureStep, LimitOnAnArrayFigureNamesOneElement) {
  const std::string step = "[[procedure]]\nkind = \"imu_calibration\"\nname = \"imu\"\nfile = \"" +
                           testing::source_path("examples/imu_calibration/tumble.csv") + "\"\n[procedure.limits]\n";
  expect_plan_error(step + "\"/accelerometer/misalignment\" = { max = 0.01, unit = \"rad\" }\n",
                    "limit on '/accelerometer/misalignment': '/accelerometer/misalignment' is a 3x3 (matrix) figure; a "
                    "limit names one element: '/accelerometer/bias/value/I', '/accelerometer/misalignment/value/I/J', "
                    "'/accelerometer/scale_factor/value/I' with I and J in 0, 1, 2 (x, y, z)");
  expect_plan_error(step + "\"/gyro/bias\" = { max = 1 }\n", "'/gyro/bias' is an [x, y, z] (vector) figure");
  expect_plan_error(step + "\"/gyro/bias/value\" = { max = 1 }\n", "'/gyro/bias' is an [x, y, z] (vector) figure");
  expect_plan_error(step + "\"/gyro/bias/value/3\" = { max = 1 }\n", "no element '3'");
  expect_plan_error(step + "accelerometer = { max = 1 }\n", "'accelerometer' holds array figures, not one figure");

  ScratchDirectory scratch;
  const std::string plan = scratch.write(
      "plan.toml", "[instrument]\nid = \"IMU\"\noutput_unit = \"count\"\n\n" + step +
                       "\"/accelerometer/misalignment/value/0/1\" = { max = 1, unit = \"deg\" }\n"
                       "\"/accelerometer/bias/value/2\" = { max = 1e-9 }\n");
  const auto results = run_campaign(plan, scratch.path() + "/out").results;
  const auto& triad = results.at("procedures").at(0).at("result").at("accelerometer");
  const auto& misalignment = results.at("verdicts").at(0);
  EXPECT_NEAR(misalignment.at("value").get<double>(),
              triad.at("misalignment").at("value").at(0).at(1).get<double>() * 180.0 / constants::kPi, 1e-12);
  EXPECT_EQ(misalignment.at("unit"), "deg");
  EXPECT_TRUE(misalignment.at("pass").get<bool>());
  const auto& bias = results.at("verdicts").at(1);
  EXPECT_EQ(bias.at("value"), triad.at("bias").at("value").at(2));
  EXPECT_EQ(bias.at("unit"), triad.at("bias").at("unit"));
  EXPECT_FALSE(bias.at("pass").get<bool>());
}

// An export outside the output directory escaped the campaign's staging: a later step's failure left
// "../leak.json" (or an absolute path) written. Such a path is a plan error before anything runs.
TEST(ProcedureStep, AnExportOutsideTheOutputDirectoryIsAPlanError) {
  const std::string imu = "[[procedure]]\nkind = \"imu_calibration\"\nfile = \"" +
                          testing::source_path("examples/imu_calibration/tumble.csv") + "\"\n";
  expect_plan_error(imu + "export = \"../leak.json\"\n",
                    ":8:10: plan.procedure[1]: 'export' names '../leak.json', outside the output directory");
  expect_plan_error(imu + "export = \"/tmp/leak.json\"\n", "'export' names '/tmp/leak.json', outside the output directory");
  expect_plan_error(imu + "export = \"a/../../leak.json\"\n", "outside the output directory");
  expect_plan_error("[[procedure]]\nkind = \"allan\"\nfile = \"plan.toml\"\nsample_rate_hz = 10\n"
                    "export = [\"json\", \"../leak.json\"]\n",
                    "'export' names '../leak.json', outside the output directory");
  ScratchDirectory scratch;
  validate_plan(scratch.write("plan.toml", std::string(kHeader) + imu + "export = \"calibration/imu.json\"\n"));
  ProcedureCall call;
  call.output_directory = scratch.path();
  EXPECT_THROW(call.output_path("../leak.json"), Error);
  EXPECT_EQ(call.output_path("a/b.json"), scratch.path() + "/a/b.json");
}

// A declared plain number (a count) is judged as it is, without a unit; the limit passed
// validation and failed after processing ("reports no such figure").
TEST(ProcedureStep, LimitOnAPlainNumberIsJudgedWithoutAUnit) {
  const std::string step = "[[procedure]]\nkind = \"bias\"\nname = \"b\"\nsample_rate_hz = 1\nfile = \"rest.txt\"\n"
                           "[procedure.limits]\n";
  expect_plan_error(step + "samples = { min = 3, unit = \"1\" }\n",
                    "limit on 'samples': procedure 'b' reports it as a plain number without a unit: give the limit "
                    "without 'unit'");
  ScratchDirectory scratch;
  scratch.write("rest.txt", "1\n2\n1\n2\n");
  const std::string plan = scratch.write(
      "plan.toml", std::string(kHeader) + "nominal_scale_factor = 1\n" + step + "samples = { min = 3 }\n\"/samples\" = { min = 5 }\n");
  const auto verdicts = run_campaign(plan, scratch.path() + "/out").results.at("verdicts");
  EXPECT_EQ(verdicts.at(0).at("value"), 4.0);
  EXPECT_EQ(verdicts.at(0).at("unit"), "");
  EXPECT_TRUE(verdicts.at(0).at("pass").get<bool>());
  EXPECT_FALSE(verdicts.at(1).at("pass").get<bool>());  // 4 < 5
}

// A required parameter with an instrument default: the step's key, else [instrument], else an error.
TEST(ProcedureStep, RequiredParameterFromTheStepOrTheInstrument) {
  expect_plan_error("[[procedure]]\nkind = \"resolution\"\nfile = \"plan.toml\"\n",
                    "missing 'scale_factor' (give it here or as [instrument] nominal_scale_factor)");
  expect_plan_error("[[procedure]]\nkind = \"resolution\"\nfile = \"plan.toml\"\nscale_factor = 0\n",
                    "the scale factor K must be a nonzero number");
}

TEST(ProcedureStep, InstrumentDefaultOnlyWhereItsConditionHolds) {
  // The nominal scale factor is per deg/s, as input_axis_misalignment's K is whatever rate_unit is.
  const std::string body = "nominal_scale_factor = 36000\n[[procedure]]\nkind = \"input_axis_misalignment\"\n"
                           "file = \"plan.toml\"\nrate = 1\n";
  ScratchDirectory scratch;
  EXPECT_NO_THROW(validate_plan(scratch.write("plan.toml", std::string(kHeader) + body + "rate_unit = \"rad/s\"\n")));
  // Records in deg/h take no K: the instrument's nominal one is not given to them, and one the step
  // gives is an error at its key.
  const std::string bias = "nominal_scale_factor = 36000\nsample_rate_hz = 100\n[[procedure]]\nkind = \"bias\"\n"
                           "file = \"plan.toml\"\ninput = \"deg/h\"\n";
  EXPECT_NO_THROW(validate_plan(scratch.write("bias.toml", std::string(kHeader) + bias)));
  expect_plan_error(bias + "scale_factor = 36000\n",
                    "bias: the scale factor K and records in deg/h (--input-deg-h; input = \"deg/h\") exclude each other");
}

}  // namespace
}  // namespace inertest
