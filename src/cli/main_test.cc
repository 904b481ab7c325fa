// The command line's own errors take the product's form: "inertest: error: ..." and status 2 (CLI11
// printed "FILE: File does not exist: x" and exited 104-106); output that cannot be written is an
// error, not a success.
#include <gmock/gmock.h>

#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
using testing::run_cli;

TEST(CommandLine, ErrorsOfTheCommandLineExitWithStatusTwo) {
  auto run = run_cli({"nosuchcmd"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "inertest: error: unknown command 'nosuchcmd' (see inertest --help)\n");
  run = run_cli({"allan", "no_such_record.csv", "--rate", "100"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, StartsWith("inertest: error: "));
  EXPECT_THAT(run.err, HasSubstr("no_such_record.csv"));
  EXPECT_THAT(run.err, HasSubstr("(see inertest allan --help)"));
  run = run_cli({"scale-factor", testing::source_path("examples/scale_factor/points.csv"), "--rate-unit"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, StartsWith("inertest: error: "));
  run = run_cli({});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, StartsWith("inertest: error: "));
  // Help and the version are no errors.
  EXPECT_EQ(run_cli({"--version"}).exit_code, 0);
  EXPECT_EQ(run_cli({"allan", "--help"}).exit_code, 0);
}

// A slip of the keys is answered with the nearest command or option (it was "unknown command" and
// "arguments were not expected" alone); a word near none gets no guess.
TEST(CommandLine, AMistypedCommandOrOptionIsAnsweredWithTheNearest) {
  auto run = run_cli({"scalefactor"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err,
            "inertest: error: unknown command 'scalefactor' (did you mean scale-factor?) (see inertest --help)\n");
  run = run_cli({"scale-factor", testing::source_path("examples/scale_factor/points.csv"), "--rateunit", "deg/s"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("(--rateunit: did you mean --rate-unit?) (see inertest scale-factor --help)"));
  run = run_cli({"archive", "fleet", "--figur", "x/y"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("(--figur: did you mean --figure?)"));
  run = run_cli({"scale-factor", testing::source_path("examples/scale_factor/points.csv"), "--wobble", "1"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, ::testing::Not(HasSubstr("did you mean")));
}

TEST(CommandLine, OutputThatCannotBeWrittenIsAnError) {
  const auto run = run_cli({"scale-factor", testing::source_path("examples/scale_factor/points.csv"), "--json"},
                           "/dev/full");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("inertest: error: cannot write the standard output"));
}

}  // namespace
}  // namespace inertest
