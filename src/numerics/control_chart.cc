#include "inertest/numerics/control_chart.h"

#include <algorithm>
#include <cmath>

#include "inertest/core/error.h"
#include "inertest/numerics/statistics.h"

namespace inertest {

// d2 for subgroups of n = 2 (a moving range of two points): the mean range of two standard
// normal draws, 2/√π = 1.128 (NIST/SEMATECH e-Handbook 6.3.2.2; Montgomery, Introduction to
// Statistical Quality Control, table VI).
constexpr double d2_for_two = 1.1283791670955126;

// The run length of Western Electric rule 4 (Western Electric Statistical Quality Control
// Handbook, 1956): eight successive points on one side of the center line.
constexpr std::size_t run_on_one_side = 8;

ControlChart individuals_control_chart(std::span<const double> values) {
  if (values.size() < 2) throw Error("a control chart needs at least 2 values (one moving range)");
  ControlChart chart;
  chart.center = mean(values);
  std::vector<double> ranges;
  for (std::size_t i = 1; i < values.size(); ++i) ranges.push_back(std::abs(values[i] - values[i - 1]));
  chart.moving_range_mean = mean(ranges);
  // NIST/SEMATECH 6.3.2.2: UCL, LCL = x̄ ± 3 MR̄ / 1.128.
  chart.sigma = chart.moving_range_mean / d2_for_two;
  chart.ucl = chart.center + 3.0 * chart.sigma;
  chart.lcl = chart.center - 3.0 * chart.sigma;
  std::size_t run = 0;
  int side = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const int this_side = values[i] > chart.center ? 1 : (values[i] < chart.center ? -1 : 0);
    run = (this_side != 0 && this_side == side) ? run + 1 : (this_side != 0 ? 1 : 0);
    side = this_side;
    if (values[i] > chart.ucl || values[i] < chart.lcl) {
      chart.out_of_control.push_back({i, "beyond_3_sigma"});
    } else if (run >= run_on_one_side) {
      chart.out_of_control.push_back({i, "8_on_one_side"});
    }
  }
  return chart;
}

ProcessCapability process_capability(double center, double sigma, std::optional<double> lower_limit,
                                     std::optional<double> upper_limit) {
  if (!(sigma > 0.0)) throw Error("process capability needs a positive standard deviation");
  ProcessCapability capability;
  // NIST/SEMATECH 6.1.6: Cp = (USL − LSL)/6σ, Cpk = min(Cpu, Cpl), Cpu = (USL − μ)/3σ, Cpl = (μ − LSL)/3σ.
  if (lower_limit && upper_limit) capability.cp = (*upper_limit - *lower_limit) / (6.0 * sigma);
  std::optional<double> cpu, cpl;
  if (upper_limit) cpu = (*upper_limit - center) / (3.0 * sigma);
  if (lower_limit) cpl = (center - *lower_limit) / (3.0 * sigma);
  if (cpu && cpl) {
    capability.cpk = std::min(*cpu, *cpl);
  } else if (cpu || cpl) {
    capability.cpk = cpu ? cpu : cpl;
  }
  return capability;
}

}  // namespace inertest
