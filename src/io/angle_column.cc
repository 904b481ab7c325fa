#include "inertest/io/angle_column.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include <fmt/format.h>

#include "inertest/core/error.h"

namespace inertest {

std::optional<std::size_t> radians_among_degrees(std::span<const double> angles) {
  // A turn in radians, 360 deg written as 6.2832 included.
  constexpr double kTurnInRadians = 2.0 * 3.14159265358979323846 + 0.01;
  const std::set<double> distinct(angles.begin(), angles.end());
  if (distinct.size() < 2) return std::nullopt;
  if (!std::all_of(angles.begin(), angles.end(), [](double a) { return std::abs(a) <= kTurnInRadians; })) {
    return std::nullopt;
  }
  const auto fraction = std::find_if(angles.begin(), angles.end(), [](double a) { return a != std::round(a); });
  if (fraction == angles.end()) return std::nullopt;
  return static_cast<std::size_t>(fraction - angles.begin());
}

std::string radians_message(std::string_view column, double angle) {
  return fmt::format("{} {}: the column's angles all lie within 2 pi and are not all whole degrees: radians? Give "
                     "them in degrees",
                     column, angle);
}

void check_degrees_not_radians(const TextTable& table, std::string_view column) {
  const std::vector<double>& angles = table.column(column);
  if (const std::optional<std::size_t> row = radians_among_degrees(angles)) {
    throw Error(SourceLocation{table.source, table.row_lines.empty() ? 0 : table.row_lines[*row], 0},
                radians_message(column, angles[*row]));
  }
}

}  // namespace inertest
