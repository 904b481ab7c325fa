// Bias repeatability (run to run, day to day): GJB 2426A-2004 5.12.3, eq. (21).
//
//   Br = [ Σ_{i=1..Q} (B0i − B̄0)² / (Q − 1) ]^½                                          (21)
//
// Input: the bias B0i of each of Q runs in deg/h, each by eq. (19) (bias.h, bias_deg_h).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"

namespace inertest {

struct BiasRepeatabilityResult {
  Figure bias_repeatability;      // Br, deg/h
  Figure mean_bias;               // B̄0, deg/h
  std::vector<double> run_biases; // B0i, deg/h, in the order given
  std::vector<std::string> warnings;
};

// 5.12.3.3 d) asks for Q >= 6 runs; fewer gives a warning. Throws Error for fewer than 2 runs
// (eq. 21 has no value) or a non-finite bias.
BiasRepeatabilityResult bias_repeatability(std::span<const double> run_biases_deg_h);

// The procedure's spec (src/procedures/bias_repeatability_spec.cc): CLI, plan step, JSON and text,
// each run's bias by eq. (19) from its output record (bias_deg_h).
ProcedureSpec bias_repeatability_spec();

}  // namespace inertest
