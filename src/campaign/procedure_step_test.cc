// The plan step made from a procedure's spec (issue 22), on the declared polarity procedure.
#include "campaign/procedure_step.h"

#include <nlohmann/json.hpp>

#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
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

// A required parameter with an instrument default: the step's key, else [instrument], else an error.
TEST(ProcedureStep, RequiredParameterFromTheStepOrTheInstrument) {
  expect_plan_error("[[procedure]]\nkind = \"resolution\"\nfile = \"plan.toml\"\n",
                    "missing 'scale_factor' (give it here or as [instrument] nominal_scale_factor)");
  expect_plan_error("[[procedure]]\nkind = \"resolution\"\nfile = \"plan.toml\"\nscale_factor = 0\n",
                    "the scale factor K must be a nonzero number");
}

TEST(ProcedureStep, InstrumentDefaultOnlyWhereItsConditionHolds) {
  // The nominal scale factor is per deg/s: input_axis_misalignment's K is per rate_unit.
  const std::string body = "nominal_scale_factor = 36000\n[[procedure]]\nkind = \"input_axis_misalignment\"\n"
                           "file = \"plan.toml\"\nrate = 1\n";
  expect_plan_error(body + "rate_unit = \"rad/s\"\n",
                    "missing 'scale_factor' (give it here or as [instrument] nominal_scale_factor with rate_unit = "
                    "\"deg/s\")");
  ScratchDirectory scratch;
  const std::string plan = scratch.write("plan.toml", std::string(kHeader) + body);
  EXPECT_NO_THROW(validate_plan(plan));
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
