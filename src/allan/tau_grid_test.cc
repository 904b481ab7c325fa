#include "inertest/allan/tau_grid.h"

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::ElementsAre;

TEST(TauGrid, OctaveDecadeAllAndPerDecade) {
  EXPECT_THAT(TauGrid::parse("octave").averaging_factors(100.0, 40), ElementsAre(1, 2, 4, 8, 16, 32));
  EXPECT_THAT(TauGrid::parse("decade").averaging_factors(100.0, 450), ElementsAre(1, 2, 4, 10, 20, 40, 100, 200, 400));
  EXPECT_THAT(TauGrid::parse("all").averaging_factors(1.0, 4), ElementsAre(1, 2, 3, 4));
  // round(10^(i/4)) = 1, 2 (1.78), 3 (3.16), 6 (5.62), 10, 18, 32, 56, 100
  EXPECT_THAT(TauGrid::parse("4/decade").averaging_factors(1.0, 100), ElementsAre(1, 2, 3, 6, 10, 18, 32, 56, 100));
  // Distinct factors only: 10/decade starts 1, 1, 2, 2, 3, ...
  EXPECT_THAT(TauGrid::parse("10/decade").averaging_factors(1.0, 4), ElementsAre(1, 2, 3, 4));
}

TEST(TauGrid, ExplicitListInSecondsLeavesOutWhatTheRecordCannotSupport) {
  const TauGrid grid = TauGrid::parse(" 10, 0.01,1 ,100000");
  EXPECT_EQ(grid.kind, TauGrid::Kind::kExplicit);
  EXPECT_THAT(grid.averaging_factors(100.0, 5000), ElementsAre(1, 100, 1000));
  EXPECT_EQ(TauGrid::parse("octave").to_string(), "octave");
  EXPECT_EQ(TauGrid::parse("5/decade").to_string(), "5/decade");
}

TEST(TauGrid, BadSpecificationsAreErrors) {
  for (const char* bad : {"", "octaves", "0/decade", "x/decade", "1,,2", "1,-2", "1,abc", "nan"}) {
    EXPECT_THROW(TauGrid::parse(bad), Error) << bad;
  }
  // 0.015 s at 100 Hz is 1.5 samples.
  EXPECT_THROW(TauGrid::parse("0.015").averaging_factors(100.0, 100), Error);
  EXPECT_THROW(TauGrid::parse("octave").averaging_factors(0.0, 100), Error);
}

}  // namespace
}  // namespace inertest
