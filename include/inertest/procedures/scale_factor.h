// Scale factor, scale factor nonlinearity and scale factor asymmetry:
// GJB 2426A-2004 5.8.1-5.8.3, eqs. (1)-(11); IEEE Std 952-1997 clause 13 (A.12).
//
// Input: the mean instrument output at each table rate, in test order. The zero-rate points before
// the first and after the last nonzero rate are the static runs at the start and the end; their
// means F̄s and F̄e give F̄r = (F̄s + F̄e)/2 (eq. 2), subtracted from every point (eq. 3). The
// nonzero rates are fitted by least squares F = K·Ω + F0 (eqs. 4-6). Rates are in the caller's
// rate unit (deg/s by default), outputs in the instrument's unit.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"

namespace inertest {

struct ScaleFactorPoint {
  double rate = 0.0;    // table rate, signed, in ScaleFactorOptions::rate_unit
  double output = 0.0;  // mean instrument output at that rate (eq. 1), in output_unit
};

struct ScaleFactorOptions {
  std::string rate_unit = "deg/s";
  std::string output_unit = "1";  // the instrument's output unit, e.g. "pulse/s", "V"
  // GJB 2426A 5.8.1.3: at least 11 rates each way, including the maximum. Fewer gives a warning.
  std::size_t recommended_rates_per_direction = 11;

  // Throws Error saying what is wrong (unknown unit, rate unit that is not a rate).
  void validate() const;
};

struct NonlinearityPoint {
  double rate = 0.0;       // in the rate unit
  double deviation = 0.0;  // α_j of eq. (8), in ppm
};

struct ScaleFactorResult {
  Figure scale_factor;            // K, eq. (5), output unit per rate unit
  Figure zero_offset;             // F0, eq. (6), output unit
  Figure nonlinearity;            // Kn, eq. (9), ppm
  Figure asymmetry;               // Ka, eqs. (10)-(11), ppm
  Figure scale_factor_positive;   // K(+): eqs. (5)-(6) over the positive rates alone
  Figure scale_factor_negative;   // K(-): eqs. (5)-(6) over the negative rates alone
  Figure static_output_start;     // F̄s
  Figure static_output_end;       // F̄e
  Figure fit_residual_rms;        // rms of v_j of eq. (4), output unit
  std::string rate_unit;          // unit of the rates in nonlinearity_curve
  std::vector<NonlinearityPoint> nonlinearity_curve;  // eq. (8), one per nonzero rate, test order
  std::vector<std::string> warnings;
};

// Throws Error when the static runs are missing, fewer than two rates lie on either side of zero,
// or the options are invalid.
ScaleFactorResult scale_factor(std::span<const ScaleFactorPoint> points, const ScaleFactorOptions& options = {});

// The declaration of the procedure (core/procedure_spec.h): `inertest scale-factor` with a table of
// test points, one long record or a record per point, plan kind "scale_factor".
ProcedureSpec scale_factor_spec();

}  // namespace inertest
