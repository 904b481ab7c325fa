// The hand-checks command: checks of GJB 2426A 5.2-5.4 given on the command line.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;
using testing::run_cli;

TEST(HandChecksCommand, FiguresAndVerdicts) {
  const auto run = run_cli({"hand-checks", "--check", "name=Insulation resistance,value=120,unit=Mohm,min=20",
                            "--check", "name=Appearance,value=pass", "--check",
                            "name=Power +15 V,value=3.2,unit=W,max=3", "--json"});
  EXPECT_EQ(run.exit_code, 1);  // one check fails: 3.2 W above 3 W
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["insulation_resistance"]["value"], 120.0);
  EXPECT_EQ(json["insulation_resistance"]["unit"], "Mohm");
  EXPECT_TRUE(json["check_pass"]["insulation_resistance"].get<bool>());
  EXPECT_TRUE(json["check_pass"]["appearance"].get<bool>());
  EXPECT_FALSE(json["check_pass"]["power_15_v"].get<bool>());
  EXPECT_FALSE(json["all_pass"].get<bool>());
}

TEST(HandChecksCommand, BadChecksAreErrors) {
  auto run = run_cli({"hand-checks", "--check", "name=R,value=abc", "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  EXPECT_THAT(run.err, HasSubstr("'abc' is not a number"));
  run = run_cli({"hand-checks", "--check", "name=R,value=1,unit=furlong"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("unknown unit 'furlong'"));
  run = run_cli({"hand-checks", "--check", "name=R,colour=red"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("unknown key 'colour'"));
  // A key twice kept its last value (120 Mohm passed as 120 kohm): an error.
  run = run_cli({"hand-checks", "--check", "name=R,value=120,unit=Mohm,min=20,unit=kohm"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("key 'unit' given twice in --check"));
  run = run_cli({"hand-checks", "--check", "name=Appearance,value=PASS"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("value 'PASS': a verdict is written pass or fail"));
  run = run_cli({"hand-checks", "--check", "name=R,value=5,min=nan"});  // a nan bound failed every value
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("the min of 'R' is not a finite number"));
}

}  // namespace
}  // namespace inertest
