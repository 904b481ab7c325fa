// Polarity: GJB 2426A-2004 5.7; IEEE Std 952-1997 clause 13 (A.6).
//
// The table turns so that the input vector lies along the positive IRA, then the opposite way; the
// output's sign is recorded each time. The polarity is the sign of the output change for a
// positive input, sign(F(+) − F(−)): "positive" when the output grows with a positive input about
// the IRA. The signs of F(+) and F(−) themselves are reported as the standard records them; when a
// bias larger than the rate response gives both the same sign, `signs_opposite` is false and a
// warning says so (the difference still gives the polarity).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"

namespace inertest {

struct PolarityOptions {
  std::string output_unit = "1";
  std::optional<int> expected;  // +1 or −1 when the specification states the polarity
  void validate() const;        // throws Error when expected is neither +1 nor −1
};

struct PolarityResult {
  int polarity = 1;                 // +1 or −1
  Figure output_positive_rate;      // mean output F(+)
  Figure output_negative_rate;      // mean output F(−)
  bool signs_opposite = true;
  std::optional<bool> pass;         // against PolarityOptions::expected
  std::vector<std::string> warnings;
};

// Throws Error when F(+) = F(−) (the output does not respond) or a value is not finite.
// The outputs' standard errors, where they are means of records, are the figures' uncertainties; a
// difference within 3 of its standard errors of zero is an Error (the means differ by noise: a gyro
// that does not respond passed as positive).
PolarityResult polarity(double output_positive_rate, double output_negative_rate, const PolarityOptions& options = {},
                        std::optional<double> positive_standard_error = std::nullopt,
                        std::optional<double> negative_standard_error = std::nullopt);

// "positive", "negative" or "zero": the sign of an output as GJB 2426A-2004 5.7 records it.
const char* output_sign_name(double output);

// The procedure's spec (src/procedures/polarity_spec.cc): CLI, plan step, JSON and text.
ProcedureSpec polarity_spec();

}  // namespace inertest
