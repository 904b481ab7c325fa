// Plan kind "scale_factor": GJB 2426A-2004 5.8.1-5.8.3 from a table of test points.
//   file = "points.csv"        # header rate,output (one row per test point, in test order)
//   rate_unit = "deg/s"        # optional
#include "campaign/step_registry.h"
#include "inertest/io/text_table.h"
#include "inertest/procedures/scale_factor.h"

namespace inertest::campaign {
namespace {

StepAction prepare(PlanTable& step, const PlanContext& context) {
  const std::string file = step.file("file");
  ScaleFactorOptions options;
  options.rate_unit = step.string_or("rate_unit", options.rate_unit);
  options.output_unit = context.instrument.output_unit;
  try {
    options.validate();
  } catch (const Error& e) {
    step.fail(e.message());
  }
  return [file, options](const StepRunContext&) {
    TextTableOptions read;
    read.columns = {ColumnSelector{"rate"}, ColumnSelector{"output"}};
    read.header = TextTableOptions::Header::kPresent;
    const TextTable table = read_text_table(file, read);
    std::vector<ScaleFactorPoint> points(table.rows());
    for (std::size_t i = 0; i < points.size(); ++i) points[i] = {table.columns[0][i], table.columns[1][i]};
    return scale_factor(points, options).to_json();
  };
}

const bool registered = register_step("scale_factor", prepare);

}  // namespace
}  // namespace inertest::campaign
