// Resolution: GJB 2426A-2004 5.11, eq. (18); IEEE Std 952-1997 clause 13 (A.9).
//
// The table turns at a base rate Ω0 (more than 100 times the threshold); the rate is changed by
// increments ΔΩ_j, decreasing step by step, and the output increment ΔF_j is measured against the
// output at the base rate. The fitted line of 5.8.1.4 predicts ΔF̂_j = K·ΔΩ_j, and an increment is
// a candidate resolution while
//   | (ΔF̂_j − ΔF_j) / ΔF̂_j | <= 50 %                                                      (18)
// Walked from the largest |ΔΩ_j| down, each direction's candidate is the smallest |ΔΩ_j| that
// satisfies (18) with every larger increment satisfying it too; the resolution is the larger of the
// forward (Ω0 > 0) and reverse (Ω0 < 0) candidates (5.11.3 f). K is in output units per deg/s;
// rates in rate_unit (deg/s by default); the resolution is reported in deg/h.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"

namespace inertest {

struct ResolutionStep {
  double base_rate = 0.0;    // Ω0, signed, rate_unit; its sign says the direction
  double base_output = 0.0;  // mean output at Ω0, measured before this increment (5.11.3 c)
  double rate = 0.0;         // Ω0 + ΔΩ_j, rate_unit
  double output = 0.0;       // mean output at that rate
};

struct ResolutionOptions {
  double scale_factor = 0.0;  // K, output units per deg/s (the fitted line of 5.8.1.4)
  std::string rate_unit = "deg/s";
  std::string output_unit = "1";  // the instrument's output unit: the output increments'
  void validate() const;  // throws Error for a zero scale factor or a unit that is not a rate
};

struct ResolutionPoint {
  double increment_deg_h = 0.0;  // ΔΩ_j
  double expected_increment = 0.0;  // ΔF̂_j, output_unit
  double output_increment = 0.0;    // ΔF_j, output_unit
  double relative_error = 0.0;      // left side of eq. (18)
  bool satisfies = false;
};

struct ResolutionBranch {
  std::string name;  // "forward" or "reverse"
  double candidate_deg_h = 0.0;
  bool bounded = false;  // a smaller increment failed eq. (18)
  std::vector<ResolutionPoint> points;  // by decreasing |ΔΩ|
};

struct ResolutionResult {
  Figure resolution;  // deg/h
  std::vector<ResolutionBranch> branches;
  std::string output_unit;  // of the points' output increments
  std::vector<std::string> warnings;
};

// Throws Error when a direction has no step, a base rate is zero, an increment is zero, or the
// largest increment of a direction already fails eq. (18).
ResolutionResult resolution(std::span<const ResolutionStep> steps, const ResolutionOptions& options);

// The increments of a CSV with the header 'base_rate,base_output,rate,output', one row each.
std::vector<ResolutionStep> read_resolution_steps(const std::string& path);

// The procedure's spec (src/procedures/resolution_spec.cc): CLI, plan step, JSON and text.
ProcedureSpec resolution_spec();

}  // namespace inertest
