#include "inertest/numerics/statistics.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "inertest/core/error.h"
#include "inertest/numerics/compensated_sum.h"

namespace inertest {

double mean(std::span<const double> values) {
  if (values.empty()) throw Error("mean of an empty set of values");
  return compensated_sum(values) / static_cast<double>(values.size());
}

double sample_standard_deviation(std::span<const double> values) {
  if (values.size() < 2) {
    throw Error("a standard deviation needs at least 2 values, got " + std::to_string(values.size()));
  }
  const double m = mean(values);
  CompensatedSum squares;
  for (double v : values) squares.add((v - m) * (v - m));
  return std::sqrt(squares.value() / static_cast<double>(values.size() - 1));
}

std::vector<double> window_means(std::span<const double> values, std::size_t window) {
  if (window == 0) throw Error("averaging window of zero samples");
  if (window > values.size()) {
    throw Error("averaging window of " + std::to_string(window) + " samples is longer than the record (" +
                std::to_string(values.size()) + " samples)");
  }
  const std::size_t count = values.size() / window;
  std::vector<double> means(count);
  for (std::size_t i = 0; i < count; ++i) means[i] = mean(values.subspan(i * window, window));
  return means;
}

bool is_constant(std::span<const double> values) {
  if (values.size() < 2) return false;
  return std::all_of(values.begin() + 1, values.end(), [first = values.front()](double v) { return v == first; });
}

}  // namespace inertest
