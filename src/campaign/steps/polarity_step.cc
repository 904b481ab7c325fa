// Plan kind "polarity": GJB 2426A-2004 5.7.
//   positive_file = "plus.txt"     # record at the positive rate (or positive_output = mean output)
//   negative_file = "minus.txt"    # record at the negative rate (or negative_output = mean output)
//   format, column                 # as for "bias"
//   expected = "positive"          # optional: the specified polarity; gives "pass"
#include "campaign/steps/record_keys.h"
#include "inertest/numerics/statistics.h"
#include "inertest/procedures/polarity.h"

namespace inertest::campaign {
namespace {

struct Side {
  std::optional<std::string> file;
  std::optional<double> output;
};

Side read_side(PlanTable& step, const std::string& which) {
  Side side{step.optional_file(which + "_file"), step.optional_number(which + "_output")};
  if (side.file.has_value() == side.output.has_value()) {
    step.fail("needs exactly one of '" + which + "_file' and '" + which + "_output'");
  }
  return side;
}

StepAction prepare(PlanTable& step, const PlanContext& context) {
  const Side positive = read_side(step, "positive");
  const Side negative = read_side(step, "negative");
  const OutputRecordSource source = read_record_keys(step, "");
  PolarityOptions options;
  options.output_unit = context.instrument.output_unit;
  if (auto expected = step.optional_string("expected")) {
    if (*expected != "positive" && *expected != "negative") step.fail_at("expected", "must be \"positive\" or \"negative\"");
    options.expected = *expected == "positive" ? 1 : -1;
  }
  return [positive, negative, source, options](const StepRunContext&) {
    auto value = [&](const Side& side) {
      if (side.output) return *side.output;
      OutputRecordSource record = source;
      record.path = *side.file;
      return mean(read_output_record(record));
    };
    return polarity(value(positive), value(negative), options).to_json();
  };
}

const bool registered = register_step("polarity", prepare);

}  // namespace
}  // namespace inertest::campaign
