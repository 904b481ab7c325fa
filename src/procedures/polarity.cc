#include "inertest/procedures/polarity.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/units.h"

namespace inertest {

const char* output_sign_name(double output) { return output > 0.0 ? "positive" : output < 0.0 ? "negative" : "zero"; }

void PolarityOptions::validate() const {
  if (expected && *expected != 1 && *expected != -1) {
    throw Error(fmt::format("polarity: the expected polarity must be +1 or -1, got {}", *expected));
  }
}

PolarityResult polarity(double output_positive_rate, double output_negative_rate, const PolarityOptions& options,
                        std::optional<double> positive_standard_error, std::optional<double> negative_standard_error) {
  options.validate();
  if (!std::isfinite(output_positive_rate) || !std::isfinite(output_negative_rate)) {
    throw Error("polarity: an output is not a finite number");
  }
  if (output_positive_rate == output_negative_rate) {
    throw Error(fmt::format("polarity: the output is {} at both the positive and the negative rate; it does not "
                            "respond to the input",
                            output_positive_rate));
  }
  // sign(F(+) − F(−)) is a measurement only where the difference stands out of the records' noise.
  const double difference = output_positive_rate - output_negative_rate;
  const double standard_error = std::hypot(positive_standard_error.value_or(0.0), negative_standard_error.value_or(0.0));
  if (std::abs(difference) <= 3.0 * standard_error) {
    const std::string unit = unit_suffix(options.output_unit);
    throw Error(fmt::format("polarity: F(+) - F(-) = {:.6g}{} is within 3 standard errors ({:.3g}{}) of zero: the "
                            "records' means differ by their noise, and do not show the output responding to the input",
                            difference, unit, standard_error, unit));
  }
  PolarityResult result;
  result.polarity = difference > 0.0 ? 1 : -1;  // sign of F(+) − F(−)
  result.output_positive_rate = {output_positive_rate, options.output_unit, positive_standard_error};
  result.output_negative_rate = {output_negative_rate, options.output_unit, negative_standard_error};
  result.signs_opposite = output_positive_rate * output_negative_rate < 0.0;
  if (!result.signs_opposite) {
    result.warnings.push_back(fmt::format("the output is {} at the positive rate and {} at the negative rate: the bias "
                                          "exceeds the rate response; the polarity follows from the difference",
                                          output_sign_name(output_positive_rate), output_sign_name(output_negative_rate)));
  }
  if (options.expected) result.pass = result.polarity == *options.expected;
  return result;
}

}  // namespace inertest
