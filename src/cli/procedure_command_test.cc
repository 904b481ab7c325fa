// The command made from a procedure's spec (issue 22): exactly one source per input, parameters
// checked before any file is read, and a procedure's complaint about a file's data naming the file.
#include <gmock/gmock.h>

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

}  // namespace
}  // namespace inertest
