#include "procedures/fifty_percent_criterion.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "inertest/core/error.h"

namespace inertest::criterion {

Outcome search(std::vector<Point> points, Denominator denominator, const std::string& what) {
  if (points.empty()) throw Error(what + ": no test points");
  std::stable_sort(points.begin(), points.end(),
                   [](const Point& a, const Point& b) { return std::abs(a.input) > std::abs(b.input); });
  for (auto& p : points) {
    // A measured output of exactly 0 (a dead band, whole pulse counts) is no denominator: that point
    // is judged against the expected output, |(F_exp − 0)/F_exp| = 1, and misses the criterion as it
    // does by any reading (an infinite error stopped the run with a message about overflow).
    const double reference = denominator == Denominator::kMeasured && p.measured != 0.0 ? p.measured : p.expected;
    p.relative_error = reference != 0.0 ? std::abs((p.expected - p.measured) / reference)
                                        : std::numeric_limits<double>::infinity();
    p.satisfies = p.relative_error <= kLimit;  // eq. (15) / (18)
  }
  if (!points.front().satisfies) {
    throw Error(fmt::format("{}: the output misses the 50 % criterion already at the largest input {} (relative "
                            "error {:.3g}); test from a larger input, or check the scale factor and the zero",
                            what, points.front().input, points.front().relative_error));
  }
  Outcome outcome;
  std::size_t i = 0;
  while (i + 1 < points.size() && points[i + 1].satisfies) ++i;
  outcome.candidate = i;
  outcome.bounded = i + 1 < points.size();
  outcome.points = std::move(points);
  return outcome;
}

}  // namespace inertest::criterion
