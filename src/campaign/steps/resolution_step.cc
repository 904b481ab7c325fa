// Plan kind "resolution": GJB 2426A-2004 5.11.
//   file = "resolution.csv"   # header base_rate,base_output,rate,output
//   scale_factor = 5000       # optional, output units per deg/s, default [instrument] nominal
//   rate_unit = "deg/s"       # optional
#include "campaign/steps/record_keys.h"
#include "inertest/io/text_table.h"
#include "inertest/procedures/resolution.h"

namespace inertest::campaign {
namespace {

StepAction prepare(PlanTable& step, const PlanContext& context) {
  const std::string file = step.file("file");
  ResolutionOptions options;
  options.scale_factor = read_scale_factor(step, context);
  options.rate_unit = step.string_or("rate_unit", options.rate_unit);
  check_in_plan(step, [&] { options.validate(); });
  return [file, options](const StepRunContext&) {
    TextTableOptions read;
    read.header = TextTableOptions::Header::kPresent;
    read.columns = {ColumnSelector{"base_rate"}, ColumnSelector{"base_output"}, ColumnSelector{"rate"},
                    ColumnSelector{"output"}};
    const TextTable table = read_text_table(file, read);
    std::vector<ResolutionStep> steps;
    for (std::size_t i = 0; i < table.rows(); ++i) {
      steps.push_back({table.columns[0][i], table.columns[1][i], table.columns[2][i], table.columns[3][i]});
    }
    return resolution(steps, options).to_json();
  };
}

const bool registered = register_step("resolution", prepare);

}  // namespace
}  // namespace inertest::campaign
