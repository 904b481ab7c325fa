// Input-axis misalignment: GJB 2426A-2004 5.15, eqs. (47)-(50).
//
// The gyro is mounted with its IRA perpendicular to the table axis; position 1 puts the case axis
// ox along the table axis, position 2 (turned 90° about IRA) puts oy there. At each position the
// table turns at +Ω and −Ω, over whole turns. For position j,
//   δj = (F(j+) − F(j−)) / (2·K·Ω)                                   (eqs. 47-48)
// with K the scale factor in output per input rate (per deg/s, as threshold and resolution take
// it, Ω converted to deg/s from its unit), so δj is the (small) angle of IA out of the plane normal
// to the table axis. The printed (F+ − F−)·K/(2Ω) holds only for K in input per output;
// see the reference notes. Two positions: α = asin(√(δ1² + δ2²)) (eq. 49).
//
// Positions 3 and 4 (5.15.3: the gyro turned about 180° about IRA from positions 1 and 2, "to
// remove the mounting error"): turning about IRA reverses the IA components along ox and oy but not
// the fixture's tilt ε of IRA toward the table axis, so δ1 = δx + ε, δ3 = −δx + ε (δ2, δ4 alike).
// We therefore take δx = (δ1 − δ3)/2, δy = (δ2 − δ4)/2, α = asin(√(δx² + δy²)), and report
// ε = (δ1 + δ2 + δ3 + δ4)/4. Eq. (50) as printed, asin(√(δ1² + … + δ4²)), equals asin(√(2α'² + 4ε²))
// under that model (α' the true angle): it removes nothing and is √2 too large when ε = 0. It is
// reported as misalignment_eq50_as_printed for comparison only.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"

namespace inertest {

struct MisalignmentPosition {
  double output_positive = 0.0;  // F(j+): mean output over whole turns at +Ω
  double output_negative = 0.0;  // F(j−): mean output over whole turns at −Ω
};

struct InputAxisMisalignmentOptions {
  double scale_factor = 0.0;  // K, output unit per deg/s (from 5.8.1), nonzero, whatever rate_unit is
  double rate = 0.0;          // Ω, > 0, rate unit
  std::string rate_unit = "deg/s";
  std::string output_unit = "1";

  void validate() const;
};

struct InputAxisMisalignmentResult {
  Figure misalignment;          // α, arcsec
  Figure misalignment_deg;      // α, deg
  std::vector<Figure> deltas;   // δj of eqs. (47)-(48) per position, arcsec
  // Four positions only:
  // IA's component along ox: its tilt toward ox, a turn about oy (position 1 has ox along the table
  // axis, and δ1 is IA's angle out of the plane normal to it).
  std::optional<Figure> misalignment_toward_ox;  // δx = (δ1 − δ3)/2, arcsec
  std::optional<Figure> misalignment_toward_oy;  // δy = (δ2 − δ4)/2, arcsec: toward oy, about ox
  std::optional<Figure> mounting_error;         // ε, arcsec
  std::optional<Figure> misalignment_eq50_as_printed;  // arcsec
  std::vector<std::string> warnings;
};

// Throws Error unless 2 or 4 positions are given, K is nonzero, Ω positive, and √(Σδ²) <= 1.
InputAxisMisalignmentResult input_axis_misalignment(std::span<const MisalignmentPosition> positions,
                                                    const InputAxisMisalignmentOptions& options);

// The positions of a CSV with the header 'position,output_positive,output_negative', positions
// 1, 2[, 3, 4] in order.
std::vector<MisalignmentPosition> read_misalignment_positions(const std::string& path);

// The procedure's spec (src/procedures/input_axis_misalignment_spec.cc): CLI, plan step, JSON and text.
ProcedureSpec input_axis_misalignment_spec();

}  // namespace inertest
