#include "inertest/numerics/statistics.h"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <fmt/format.h>
#include <string>

#include "inertest/core/error.h"
#include "inertest/numerics/compensated_sum.h"

namespace inertest {

double mean(std::span<const double> values) {
  if (values.empty()) throw Error("mean of an empty set of values");
  return compensated_sum(values) / static_cast<double>(values.size());
}

MeanWithError mean_with_error(std::span<const double> values) {
  MeanWithError result{mean(values), std::nullopt};
  if (values.size() >= 2) {
    result.standard_error = sample_standard_deviation(values) / std::sqrt(static_cast<double>(values.size()));
  }
  return result;
}

double sample_standard_deviation(std::span<const double> values) {
  if (values.size() < 2) {
    throw Error("a standard deviation needs at least 2 values, got " + std::to_string(values.size()));
  }
  // About the first value: the mean of values near a large offset is rounded at the offset's
  // magnitude, and that error e adds e^2 to the variance (3.6e-9 of it for noise 1e-3 at 1e9); the
  // differences from a value near them are exact (Sterbenz) and their mean small.
  const double reference = values.front();
  CompensatedSum sum;
  for (double v : values) sum.add(v - reference);
  const double m = sum.value() / static_cast<double>(values.size());
  CompensatedSum squares;
  for (double v : values) squares.add(((v - reference) - m) * ((v - reference) - m));
  return std::sqrt(squares.value() / static_cast<double>(values.size() - 1));
}

std::vector<double> window_means(std::span<const double> values, std::size_t window, double reference) {
  if (window == 0) throw Error("averaging window of zero samples");
  if (window > values.size()) {
    throw Error("averaging window of " + std::to_string(window) + " samples is longer than the record (" +
                std::to_string(values.size()) + " samples)");
  }
  const std::size_t count = values.size() / window;
  std::vector<double> means(count);
  for (std::size_t i = 0; i < count; ++i) {
    CompensatedSum sum;
    for (const double v : values.subspan(i * window, window)) sum.add(v - reference);
    means[i] = sum.value() / static_cast<double>(window);
  }
  return means;
}

bool is_constant(std::span<const double> values) {
  if (values.size() < 2) return false;
  return std::all_of(values.begin() + 1, values.end(), [first = values.front()](double v) { return v == first; });
}

double one_sigma_coverage(double degrees_of_freedom) {
  return 1.0 - 2.0 * boost::math::cdf(boost::math::complement(boost::math::students_t(degrees_of_freedom), 1.0));
}

std::optional<std::string> few_degrees_of_freedom_warning(const std::string& fit, std::size_t degrees_of_freedom,
                                                          const std::string& cases) {
  if (degrees_of_freedom == 0 || degrees_of_freedom >= kFewDegreesOfFreedom) return std::nullopt;
  return fmt::format("{} has {} degree{} of freedom: its 1-sigma uncertainties, estimated from so few residuals, hold "
                     "the truth in about {:.0f} % of {}, not 68 % (Student's t)",
                     fit, degrees_of_freedom, degrees_of_freedom == 1 ? "" : "s",
                     100.0 * one_sigma_coverage(static_cast<double>(degrees_of_freedom)), cases);
}

}  // namespace inertest
