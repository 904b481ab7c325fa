#include "inertest/io/angle_column.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "inertest/core/error.h"

namespace inertest {
namespace {

TextTable angles_table(std::vector<double> angles) {
  TextTable table;
  table.source = "positions.csv";
  table.names = {"beta_deg"};
  table.columns = {std::move(angles)};
  for (std::size_t i = 0; i < table.columns[0].size(); ++i) table.row_lines.push_back(i + 2);
  return table;
}

// Four positions in radians (0, 90, 180, 270 deg): refused at the first that is no whole degree.
TEST(AngleColumn, RadiansInADegreeColumnAreRefusedAtTheirRow) {
  EXPECT_THAT([] { check_degrees_not_radians(angles_table({0.0, 1.5707963, 3.1415927, 4.712389}), "beta_deg"); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr(
                  "positions.csv:3: beta_deg 1.5707963: the column's angles all lie within 2 pi and are not all whole "
                  "degrees: radians? Give them in degrees")));
  EXPECT_THROW(check_degrees_not_radians(angles_table({-3.1415927, -1.5707963, 0.0, 1.5707963}), "beta_deg"), Error);
  EXPECT_THROW(check_degrees_not_radians(angles_table({0.0, 3.1415927, 0.0, 3.1415927}), "beta_deg"), Error);
  // 360 deg written as 2 pi, to its printed digits.
  EXPECT_EQ(radians_among_degrees(std::vector<double>{0.0, 1.5708, 3.1416, 4.7124, 6.2832}), std::optional<std::size_t>(1));
  // Small positions in fractions of a degree are taken for radians: said in the header.
  EXPECT_EQ(radians_among_degrees(std::vector<double>{-1.5, -0.5, 0.5, 1.5}), std::optional<std::size_t>(0));
}

// Degrees pass, whatever their spacing; one angle, or whole numbers, say nothing.
TEST(AngleColumn, DegreesPass) {
  for (const std::vector<double>& angles :
       {std::vector<double>{0, 90, 180, 270}, std::vector<double>{0, 22.5, 45, 67.5, 90}, std::vector<double>{0, 1, 2, 3},
        std::vector<double>{1.5, 1.5}, std::vector<double>{-90, 0, 90}, std::vector<double>{0, 6.5, 13}}) {
    EXPECT_NO_THROW(check_degrees_not_radians(angles_table(angles), "beta_deg"));
  }
}

}  // namespace
}  // namespace inertest
