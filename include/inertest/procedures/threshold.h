// Threshold: GJB 2426A-2004 5.10, all three methods; IEEE Std 952-1997 clause 13 (A.8).
//
// Every method compares the measured output F_j (the zero output removed) with the theoretical
// output of the input Ω_j,
//   F̄_j = K·Ω_j                                                                           (14)
// and an input is a candidate threshold while the 50 % criterion holds. By default it is
//   | (F̄_j − F_j) / F̄_j | <= 50 %
// relative to the expected output, as IEEE Std 952-1997 defines the threshold (the smallest input
// giving an output of at least 50 % of the one expected from the scale factor) and as GJB 2426A
// eq. (18) writes it for the resolution. GJB 2426A eq. (15) as printed divides by the measured F_j,
//   | (F̄_j − F_j) / F_j | <= 50 %                                                         (15)
// which passes an output down to F̄_j/1.5, i.e. a 67 % criterion; it is kept as an option
// (ThresholdOptions::criterion_denominator = kMeasured). The inputs are walked from the largest |Ω_j|
// down, as the test decreases them; a branch's candidate is the smallest |Ω_j| that satisfies the
// criterion with every larger input of the branch satisfying it too. The threshold is the largest candidate
// over the branches (5.10.3.1 e, 5.10.3.2 d, 5.10.4.3).
//
// Method 1 (rate table, 5.10.4.1): Ω_j the table rate; the table axis is orthogonal to the Earth's
//   axis (5.10.3.1 a or b), so Earth rate adds nothing. Branches: positive and negative rates.
// Method 2 (dividing head, 5.10.4.2): the IRA horizontal at angle β_j from north,
//   Ω_j = Ωe·cos ψ·cos β_j                                                                 (16)
//   Branches: IRA toward north (cos β > 0) and toward south (cos β < 0).
// Method 3 (slow rotation, 5.10.4.3): the IRA horizontal on a table turning at ω,
//   Ω_j = Ωe·cos ψ·cos(ω·t_j + Φ)                                                          (17)
//   Four branches around the two zero crossings of the input (two positive, two negative):
//   with θ = ωt + Φ mod 360°, θ in [0, 90), (90, 180], [180, 270), (270, 360).
//
// K is in output units per deg/s. Thresholds are reported in deg/h.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"

namespace inertest {

// The denominator of the 50 % criterion (see above).
enum class CriterionDenominator {
  kExpected,  // F̄_j: IEEE Std 952-1997, as GJB 2426A eq. (18) (the default)
  kMeasured,  // F_j: GJB 2426A eq. (15) as printed
};
// "expected" or "measured".
std::string_view to_string(CriterionDenominator denominator);
// Parses "expected" or "measured"; throws Error naming the two otherwise.
CriterionDenominator parse_criterion_denominator(std::string_view text);
// How the criterion reads, with its source (e.g. "... GJB 2426A-2004 eq. (15) as printed ...").
const char* criterion_text(CriterionDenominator denominator);

struct ThresholdOptions {
  double scale_factor = 0.0;  // K, output units per deg/s (from 5.8.1)
  CriterionDenominator criterion_denominator = CriterionDenominator::kExpected;
  // The zero output (the output at zero input). When absent: method 1 uses the mean output at the
  // zero-rate points, method 2 at the angles where cos β = 0 (IRA east or west), method 3 the mean
  // output over the record (the input averages to zero over whole revolutions).
  std::optional<double> zero_output;
  std::string output_unit = "1";    // the instrument's output unit: the zero output's
  std::string rate_unit = "deg/s";  // method 1: unit of the table rates
  // ψ, methods 2 and 3 (their input is Ωe cos ψ, eqs. 16-17): required by them, no default (a
  // latitude of 0 assumed unsaid inflated the threshold by 1/cos ψ, +43 % at 45.75 deg N).
  std::optional<double> latitude_deg;
  // Method 2: azimuth of the dividing head's zero mark from north (β_j = reading + heading).
  // Method 3: Φ, the IRA's azimuth from north at t = 0.
  double heading_deg = 0.0;

  void validate() const;  // throws Error for a zero scale factor, a latitude outside [-90, 90], a bad unit
  // ψ for methods 2 and 3; a ParameterError on "latitude" when it was not given.
  double latitude_for(const char* method) const;
};

struct ThresholdPoint {
  double input_deg_h = 0.0;     // Ω_j
  double expected_output = 0.0; // F̄_j, eq. (14)
  double output = 0.0;          // F_j, zero removed
  double relative_error = 0.0;  // left side of the 50 % criterion
  bool satisfies = false;
};

struct ThresholdBranch {
  std::string name;              // "positive", "negative", "toward north", ...
  double candidate_deg_h = 0.0;  // |Ω| of the branch's candidate threshold
  bool bounded = false;          // a smaller input of the branch failed the criterion
  std::vector<ThresholdPoint> points;  // by decreasing |Ω|
};

struct ThresholdResult {
  int method = 1;
  CriterionDenominator criterion_denominator = CriterionDenominator::kExpected;  // the one used
  Figure threshold;    // deg/h
  Figure zero_output;  // output unit
  std::vector<ThresholdBranch> branches;
  std::vector<std::string> warnings;
};

struct RateTablePoint {
  double rate = 0.0;    // table rate, signed, in ThresholdOptions::rate_unit
  double output = 0.0;  // mean output at that rate
};
// Method 1. Throws Error when a direction has no rate, the zero output is neither given nor
// measured, or the largest rate of a direction already fails the criterion.
ThresholdResult threshold_rate_table(std::span<const RateTablePoint> points, const ThresholdOptions& options);

struct DividingHeadPoint {
  double angle_deg = 0.0;  // dividing-head reading; β_j = reading + heading_deg
  double output = 0.0;     // mean output at that angle
};
// Method 2. Throws Error as method 1 (directions: IRA toward north and toward south).
ThresholdResult threshold_dividing_head(std::span<const DividingHeadPoint> points, const ThresholdOptions& options);

// Method 3: output samples at times t_j (s) while the table turns at table_rate_deg_s (the rate at
// which the IRA's azimuth grows). Throws Error for a zero table rate, fewer samples than branches,
// or a record that leaves one of the four branches empty (less than one revolution).
ThresholdResult threshold_rotating(std::span<const double> time_s, std::span<const double> output,
                                   double table_rate_deg_s, const ThresholdOptions& options);

// The declaration of the procedure (core/procedure_spec.h): `inertest threshold FILE --method 1|2|3`,
// plan kind "threshold" (latitude and heading from [site]).
ProcedureSpec threshold_spec();

}  // namespace inertest
