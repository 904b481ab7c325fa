#include "inertest/io/angle_column.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "inertest/core/error.h"

namespace inertest {

void check_degrees_not_radians(const TextTable& table, std::string_view column) {
  const std::vector<double>& angles = table.column(column);
  constexpr double kTurnInRadians = 2.0 * 3.14159265358979323846 * (1.0 + 1e-9);
  const std::set<double> distinct(angles.begin(), angles.end());
  const bool within_a_turn_of_radians = std::all_of(angles.begin(), angles.end(),
                                                    [](double a) { return std::abs(a) <= kTurnInRadians; });
  if (distinct.size() < 2 || !within_a_turn_of_radians) return;
  const auto fraction = std::find_if(angles.begin(), angles.end(), [](double a) { return a != std::round(a); });
  if (fraction == angles.end()) return;
  const auto row = static_cast<std::size_t>(fraction - angles.begin());
  throw Error(SourceLocation{table.source, table.row_lines.empty() ? 0 : table.row_lines[row], 0},
              fmt::format("{} {}: the column's angles all lie within 2 pi and are not whole degrees: radians? "
                          "Give them in degrees",
                          column, *fraction));
}

}  // namespace inertest
