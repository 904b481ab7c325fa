// Plan keys shared by the steps that read instrument-output records: the record (file, format,
// column), the sample rate and scale factor with the instrument's defaults, and the IRA geometry
// for Earth-rate removal from the site.
#pragma once

#include <optional>
#include <string>

#include "campaign/plan_table.h"
#include "campaign/step_registry.h"
#include "inertest/io/output_record.h"
#include "inertest/procedures/earth_rate.h"

namespace inertest::campaign {

// `format` (binary "f64", "f32", ...; absent for text) and `column` (text records), checked.
OutputRecordSource read_record_keys(PlanTable& step, const std::string& file);

// `sample_rate_hz`, else the instrument's; fails naming the key when neither is given or it is not positive.
double read_sample_rate(PlanTable& step, const PlanContext& context);

// `scale_factor` (output units per deg/s), else the instrument's nominal; fails when neither or zero.
double read_scale_factor(PlanTable& step, const PlanContext& context);

// `input`: "output" (default) or "deg/h" (the records hold rate already). True for "deg/h".
bool read_input_in_deg_h(PlanTable& step);

// With `remove_earth_rate = true`: the site's latitude and heading and `ira_elevation_deg` (default 0).
std::optional<AxisOrientation> read_earth_rate_removal(PlanTable& step, const PlanContext& context);

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
