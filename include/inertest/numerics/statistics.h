// Sample statistics computed for long records: compensated sums, mean removed before squaring.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <span>
#include <vector>

namespace inertest {

double mean(std::span<const double> values);

// The mean of a record and its standard error, s / sqrt(n) (none for fewer than two samples).
struct MeanWithError {
  double mean = 0.0;
  std::optional<double> standard_error;
};
MeanWithError mean_with_error(std::span<const double> values);

// Sample standard deviation with n - 1 in the denominator (two-pass: mean removed first, so that a
// large common offset does not cancel the spread). Throws Error for fewer than two values.
double sample_standard_deviation(std::span<const double> values);

// Means of consecutive, non-overlapping windows of `window` samples, less `reference`; a partial
// last window is dropped. Throws Error if window is zero or longer than the record. A reference
// near the values (e.g. the first) keeps the means' small differences: a mean stored near an
// offset of 1e9 is rounded to 1.2e-7, what a bias stability of 1e-5 cannot lose.
std::vector<double> window_means(std::span<const double> values, std::size_t window, double reference = 0.0);

// True when there are two or more values and all are equal: a channel stuck at one value (or a
// wrong column). A procedure given such a record computes zero spread, zero harmonics or zero
// angles that are not measurements, and says so in its warnings.
bool is_constant(std::span<const double> values);

// How often a 1-sigma estimated from `degrees_of_freedom` residuals holds the truth: P(|t_nu| < 1),
// Student's t (0.50 at 1, 0.61 at 3, 0.66 at 10; 0.683 as nu grows).
double one_sigma_coverage(double degrees_of_freedom);

// Below this many degrees of freedom such a 1-sigma holds the truth in 66 % of cases or fewer.
inline constexpr std::size_t kFewDegreesOfFreedom = 10;

// "FIT has N degrees of freedom: its 1-sigma uncertainties, estimated from so few residuals, hold
// the truth in about P % of CASES, not 68 % (Student's t)" for 0 < N < kFewDegreesOfFreedom, else
// nothing (an exact fit, N = 0, gives no uncertainty at all).
std::optional<std::string> few_degrees_of_freedom_warning(const std::string& fit, std::size_t degrees_of_freedom,
                                                          const std::string& cases);

}  // namespace inertest
