// The misalignment input files read into rows.
#include "inertest/misalignment/misalignment_files.h"

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

// The record listing is split by the shared row parser: a quoted file name may hold a comma, and a
// quote left open names its line and column.
// Positions in radians were read as angles of a few degrees (gamma came out 148 716 arcsec).
TEST(MisalignmentFiles, PositionsInRadiansAreRefused) {
  testing::ScratchDirectory dir;
  const std::string gyro = dir.write("gyro.csv", "alpha_deg,beta_deg,rate_dps,output\n0,0,20,-0.06\n0,0,-20,0.06\n"
                                                 "0,3.14159265,20,-0.05\n0,3.14159265,-20,0.06\n"
                                                 "1.57079633,0,20,0.03\n1.57079633,0,-20,-0.03\n");
  EXPECT_THAT([&] { read_gyro_misalignment_positions(gyro); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr(gyro + ":6: alpha_deg 1.57079633: the column's angles "
                                                                          "all lie within 2 pi")));
  const std::string accelerometer =
      dir.write("accelerometer.csv", "beta_deg,output\n0,-0.0018\n1.57079633,0.0004\n3.14159265,0.0019\n");
  EXPECT_THAT([&] { read_accelerometer_misalignment_positions(accelerometer); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr(accelerometer + ":3: beta_deg 1.57079633")));
}

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
