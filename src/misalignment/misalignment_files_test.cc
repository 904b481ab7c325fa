// The misalignment input files read into rows.
#include "inertest/misalignment/misalignment_files.h"

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

// The record listing is split by the shared row parser: a quoted file name may hold a comma, and a
// quote left open names its line and column.
TEST(MisalignmentFiles, GyroRecordListingTakesQuotedFileNames) {
  testing::ScratchDirectory dir;
  dir.write("run 1, +20.csv", "table_angle_deg,output\n0,1.0\n90,2.0\n180,3.0\n270,2.0\n360,1.0\n");
  const std::string listing =
      dir.write("list.csv", "\"alpha_deg\",\"beta_deg\",\"rate_dps\",\"file\"\n0,0,\"20\",\"run 1, +20.csv\"\n");
  const std::vector<GyroMisalignmentRow> rows = read_gyro_misalignment_records(listing);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].rate_dps, 20.0);
  EXPECT_EQ(rows[0].line, 2u);
  const std::string open_quote = dir.write("open.csv", "alpha_deg,beta_deg,rate_dps,file\n0,0,20,\"run 1.csv\n");
  EXPECT_THAT([&] { read_gyro_misalignment_records(open_quote); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr(open_quote + ":2:8: a quoted field with no closing quote")));
}

// A listing saved by a European Excel separates its cells with ';' (it was "the header has no column
// 'alpha_deg'"); one with tabs reads as well.
TEST(MisalignmentFiles, GyroRecordListingBySemicolonsOrTabs) {
  testing::ScratchDirectory dir;
  dir.write("a.csv", "table_angle_deg,output\n0,1.0\n90,2.0\n180,3.0\n270,2.0\n360,1.0\n");
  for (const char* listing : {"alpha_deg;beta_deg;rate_dps;file\n0;90;20;a.csv\n", "alpha_deg\tbeta_deg\trate_dps\tfile\n0\t90\t20\ta.csv\n"}) {
    const std::vector<GyroMisalignmentRow> rows = read_gyro_misalignment_records(dir.write("list.csv", listing));
    ASSERT_EQ(rows.size(), 1u) << listing;
    EXPECT_EQ(rows[0].beta_deg, 90.0);
    EXPECT_EQ(rows[0].rate_dps, 20.0);
  }
}

}  // namespace
}  // namespace inertest
