#include "inertest/procedures/polarity.h"

#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"

namespace inertest {
namespace {

const char* sign_name(double value) { return value > 0.0 ? "positive" : value < 0.0 ? "negative" : "zero"; }

}  // namespace

void PolarityOptions::validate() const {
  if (expected && *expected != 1 && *expected != -1) {
    throw Error(fmt::format("polarity: the expected polarity must be +1 or -1, got {}", *expected));
  }
}

PolarityResult polarity(double output_positive_rate, double output_negative_rate, const PolarityOptions& options) {
  options.validate();
  if (!std::isfinite(output_positive_rate) || !std::isfinite(output_negative_rate)) {
    throw Error("polarity: an output is not a finite number");
  }
  if (output_positive_rate == output_negative_rate) {
    throw Error(fmt::format("polarity: the output is {} at both the positive and the negative rate; it does not "
                            "respond to the input",
                            output_positive_rate));
  }
  PolarityResult result;
  result.polarity = output_positive_rate > output_negative_rate ? 1 : -1;  // sign of F(+) − F(−)
  result.output_positive_rate = {output_positive_rate, options.output_unit, std::nullopt};
  result.output_negative_rate = {output_negative_rate, options.output_unit, std::nullopt};
  result.signs_opposite = output_positive_rate * output_negative_rate < 0.0;
  if (!result.signs_opposite) {
    result.warnings.push_back(fmt::format("the output is {} at the positive rate and {} at the negative rate: the bias "
                                          "exceeds the rate response; the polarity follows from the difference",
                                          sign_name(output_positive_rate), sign_name(output_negative_rate)));
  }
  if (options.expected) result.pass = result.polarity == *options.expected;
  return result;
}

nlohmann::json PolarityResult::to_json() const {
  nlohmann::json json = {
      {"procedure", "polarity"},
      {"clause", "GJB 2426A-2004 5.7"},
      {"polarity", polarity > 0 ? "positive" : "negative"},
      {"sign", Figure{static_cast<double>(polarity), "1", std::nullopt}},
      {"output_positive_rate", output_positive_rate},
      {"output_negative_rate", output_negative_rate},
      {"output_sign_positive_rate", sign_name(output_positive_rate.value)},
      {"output_sign_negative_rate", sign_name(output_negative_rate.value)},
      {"signs_opposite", signs_opposite},
      {"warnings", warnings},
  };
  if (pass) json["pass"] = *pass;
  return json;
}

std::string PolarityResult::report() const {
  std::string text = "Polarity (GJB 2426A-2004 5.7)\n";
  text += fmt::format("  {:<32} {:.9g} {} ({})\n", "output at positive rate", output_positive_rate.value,
                      output_positive_rate.unit, sign_name(output_positive_rate.value));
  text += fmt::format("  {:<32} {:.9g} {} ({})\n", "output at negative rate", output_negative_rate.value,
                      output_negative_rate.unit, sign_name(output_negative_rate.value));
  text += fmt::format("  {:<32} {}\n", "polarity", polarity > 0 ? "positive" : "negative");
  if (pass) text += fmt::format("  {:<32} {}\n", "as specified", *pass ? "PASS" : "FAIL");
  for (const auto& w : warnings) text += "  warning: " + w + "\n";
  return text;
}

}  // namespace inertest
