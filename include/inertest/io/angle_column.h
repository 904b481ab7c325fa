// A column of angles named in degrees (beta_deg, angle_deg) that holds radians: a dividing head's or
// a table's 0, 90, 180, 270 deg written as 0, 1.5708, 3.1416, 4.7124 read as angles of a few degrees,
// and the misalignment came out 41 deg (148 716 arcsec) with no word.
#pragma once

#include <string_view>

#include "inertest/io/text_table.h"

namespace inertest {

// Throws Error at the row of the first angle that is not a whole degree when the column holds two or
// more distinct angles, all within +-2 pi and not all whole degrees: radians, in a column whose name
// says degrees (positions 0 and 180 deg: 0 and 3.1416). Positions in degrees (0, 45, 90... or 0,
// 22.5, 45...) pass; so would positions a fraction of a degree apart and no more, which no test of
// these procedures uses.
void check_degrees_not_radians(const TextTable& table, std::string_view column);

}  // namespace inertest
