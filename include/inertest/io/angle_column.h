// A column of angles named in degrees (alpha_deg, beta_deg, angle_deg) that holds radians: a
// dividing head's or a table's 0, 90, 180, 270 deg written as 0, 1.5708, 3.1416, 4.7124 read as
// angles of a few degrees, and the misalignment came out 41 deg (148 716 arcsec) with no word.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "inertest/io/text_table.h"

namespace inertest {

// The place of the first angle that is not a whole degree when `angles` (named in degrees) hold two
// or more distinct values, all within +-(2 pi + 0.01) and not all whole degrees: radians. Positions
// in degrees (0, 90, 180... or 0, 22.5, 45...) pass; positions within 6.3 deg of 0 that are not all
// whole degrees (+-0.5, +-1.5) are taken for radians, which no position of these procedures is.
std::optional<std::size_t> radians_among_degrees(std::span<const double> angles);

// "beta_deg 1.5708: the column's angles all lie within 2 pi and are not all whole degrees: radians? ..."
std::string radians_message(std::string_view column, double angle);

// Throws Error at the row of radians_among_degrees in the table's column.
void check_degrees_not_radians(const TextTable& table, std::string_view column);

}  // namespace inertest
