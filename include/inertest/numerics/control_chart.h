// Statistical process control for a fleet of instruments: the Shewhart individuals and moving
// range (I-MR) chart and the process capability indices, after the NIST/SEMATECH e-Handbook of
// Statistical Methods, 6.3.2.2 "Individuals control charts" and 6.1.6 "Process capability".
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace inertest {

// A point the chart flags, with the Western Electric rule that flagged it.
struct OutOfControlPoint {
  std::size_t index = 0;  // into the values given
  std::string rule;       // "beyond_3_sigma" (rule 1) or "8_on_one_side" (rule 4)
};

struct ControlChart {
  double center = 0.0;             // x̄
  double moving_range_mean = 0.0;  // MR̄, the mean of |x_i − x_{i−1}|
  double sigma = 0.0;              // MR̄ / d2, d2 = 1.128 for ranges of 2
  double ucl = 0.0;                // x̄ + 3 MR̄ / d2
  double lcl = 0.0;                // x̄ − 3 MR̄ / d2
  std::vector<OutOfControlPoint> out_of_control;
};

// The I-MR chart of values in production (or test) order. Throws Error for fewer than 2 values.
ControlChart individuals_control_chart(std::span<const double> values);

struct ProcessCapability {
  std::optional<double> cp;   // (USL − LSL) / 6σ; both limits needed
  std::optional<double> cpk;  // min(USL − x̄, x̄ − LSL) / 3σ; the one-sided index with one limit
};

// Cp and Cpk of a process of mean center and standard deviation sigma (> 0) against the
// specification limits that exist.
ProcessCapability process_capability(double center, double sigma, std::optional<double> lower_limit,
                                     std::optional<double> upper_limit);

}  // namespace inertest
