// Scale factor repeatability: GJB 2426A-2004 5.8.4, eq. (12).
//
// The scale factor test of 5.8.1 is repeated Q times, the gyro and its equipment switched off and
// cooled to room temperature between runs (5.8.4.3: "Q times, 6 or more"). With Ki the scale factor
// of run i and K̄ their mean, Kr = (1/K̄)·[Σ(Ki − K̄)²/(Q − 1)]^½ (eq. 12), reported in ppm.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/procedures/scale_factor.h"

namespace inertest {

struct ScaleFactorRepeatabilityOptions {
  ScaleFactorOptions scale_factor;  // how each run's K is computed (5.8.1.4)
  // 5.8.4.3 asks for at least 6 runs: fewer is an Error. A lab may lower this (to no less than 2,
  // what eq. 12 needs); the result then carries a warning that it is not per the standard.
  std::size_t minimum_runs = 6;

  void validate() const;
  // Throws Error when `runs` is fewer than minimum_runs.
  void check_run_count(std::size_t runs) const;
};

struct ScaleFactorRepeatabilityResult {
  Figure scale_factor_repeatability;  // Kr, eq. (12), ppm
  Figure mean_scale_factor;           // K̄
  std::vector<Figure> run_scale_factors;  // Ki, one per run, in the order given
  std::vector<std::string> warnings;
};

// From the scale factors of the runs (output unit per rate unit, given by unit). Throws Error when
// fewer than options.minimum_runs values are given or the mean is zero.
ScaleFactorRepeatabilityResult scale_factor_repeatability(std::span<const double> scale_factors,
                                                          const std::string& unit,
                                                          const ScaleFactorRepeatabilityOptions& options = {});

// From the test points of each run: K of each by eqs. (1)-(6), then eq. (12). Errors in a run name it.
ScaleFactorRepeatabilityResult scale_factor_repeatability(std::span<const std::vector<ScaleFactorPoint>> runs,
                                                          const ScaleFactorRepeatabilityOptions& options = {});

// The procedure's spec (src/procedures/scale_factor_repeatability_spec.cc): CLI, plan step, JSON
// and text, each run's test points read from its file.
ProcedureSpec scale_factor_repeatability_spec();

}  // namespace inertest
