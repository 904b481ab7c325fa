// Maximum input rate: GJB 2426A-2004 5.9.
//
// 5.9: "Test the scale factor by 5.8.1. At the maximum input rate the gyro's input/output
// characteristic shall meet the scale factor nonlinearity requirement." The scale-factor test is
// run out to rates beyond the expected maximum; for each tested rate magnitude R (ascending) the
// points with |Ω| <= R (and the static runs) are processed by 5.8.1.4-5.8.2.4 (eqs. 1-9). The
// maximum input rate is the largest R whose nonlinearity Kn(R) meets the requirement, as 5.9 reads
// ("at the maximum input rate"); smaller ranges that miss it are a warning. (Requiring every smaller
// range to meet it too refused the README's own record: over |Ω| <= 0.2 deg/s its noise alone is
// 34 ppm of that full scale, while over +-300 deg/s Kn is 17 ppm.)
#pragma once

#include <span>
#include <string>
#include <vector>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/procedures/scale_factor.h"

namespace inertest {

struct MaximumInputRateOptions {
  ScaleFactorOptions scale_factor;
  double nonlinearity_limit_ppm = 0.0;  // the nonlinearity requirement, > 0

  void validate() const;
};

struct RangeNonlinearity {
  double rate = 0.0;          // R, the range's largest |Ω|
  double nonlinearity = 0.0;  // Kn over |Ω| <= R, ppm
  bool meets_requirement = false;
};

struct MaximumInputRateResult {
  Figure maximum_input_rate;     // the largest R, rate unit
  Figure nonlinearity;           // Kn at that R, ppm
  Figure nonlinearity_limit;     // the requirement, ppm
  Figure scale_factor;           // K over |Ω| <= maximum_input_rate
  std::vector<RangeNonlinearity> ranges;  // every R tried, ascending
  std::string rate_unit;
  std::vector<std::string> warnings;
};

// Throws Error when the points cannot be processed by scale_factor() (missing static runs, rates
// not on both sides of zero) or the requirement is not met even over the smallest range (two
// rates each way).
MaximumInputRateResult maximum_input_rate(std::span<const ScaleFactorPoint> points,
                                          const MaximumInputRateOptions& options);

// The procedure's spec (src/procedures/maximum_input_rate_spec.cc): CLI, plan step, JSON and text.
ProcedureSpec maximum_input_rate_spec();

}  // namespace inertest
