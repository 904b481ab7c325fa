#include "campaign/steps/record_keys.h"

#include <cmath>

#include "inertest/io/output_record.h"

namespace inertest::campaign {

OutputRecordSource read_record_keys(PlanTable& step, const std::string& file) {
  OutputRecordSource source;
  source.path = file;
  source.format = step.string_or("format", "");
  source.column = step.string_or("column", "");
  if (!source.format.empty()) {
    try {
      check_output_record_format(source.format);
    } catch (const Error& e) {
      step.fail_at("format", e.message());
    }
  }
  return source;
}

double read_scale_factor(PlanTable& step, const PlanContext& context) {
  const auto k = step.optional_number("scale_factor");
  if (k) {
    if (*k == 0.0 || !std::isfinite(*k)) step.fail_at("scale_factor", "must be a nonzero number (output units per deg/s)");
    return *k;
  }
  if (!context.instrument.nominal_scale_factor || *context.instrument.nominal_scale_factor == 0.0) {
    step.fail("missing 'scale_factor' (give it here or as [instrument] nominal_scale_factor)");
  }
  return *context.instrument.nominal_scale_factor;
}

}  // namespace inertest::campaign
