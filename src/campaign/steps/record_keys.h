// Plan keys shared by the steps that read instrument-output records: the record (file, format,
// column) and the scale factor with the instrument's default.
#pragma once

#include <string>

#include "campaign/plan_table.h"
#include "campaign/step_registry.h"
#include "inertest/io/output_record.h"

namespace inertest::campaign {

// `format` (binary "f64", "f32", ...; absent for text) and `column` (text records), checked.
OutputRecordSource read_record_keys(PlanTable& step, const std::string& file);

// `scale_factor` (output units per deg/s), else the instrument's nominal; fails when neither or zero.
double read_scale_factor(PlanTable& step, const PlanContext& context);

// Runs check() and turns its Error into a plan error located at the step.
template <typename Check>
void check_in_plan(PlanTable& step, Check check) {
  try {
    check();
  } catch (const Error& e) {
    step.fail(e.message());
  }
}

}  // namespace inertest::campaign
