#include "campaign/steps/record_keys.h"

#include <cmath>

#include "inertest/io/binary_record.h"

namespace inertest::campaign {

OutputRecordSource read_record_keys(PlanTable& step, const std::string& file) {
  OutputRecordSource source;
  source.path = file;
  source.format = step.string_or("format", "");
  source.column = step.string_or("column", "");
  if (!source.format.empty()) {
    try {
      BinaryFormat::parse(source.format);
    } catch (const Error& e) {
      step.fail_at("format", e.message());
    }
  }
  return source;
}

double read_sample_rate(PlanTable& step, const PlanContext& context) {
  const auto rate = step.optional_number("sample_rate_hz");
  if (rate) {
    if (!(*rate > 0.0)) step.fail_at("sample_rate_hz", "must be positive");
    return *rate;
  }
  if (!context.instrument.sample_rate_hz) {
    step.fail("missing 'sample_rate_hz' (give it here or in [instrument])");
  }
  return *context.instrument.sample_rate_hz;
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

bool read_input_in_deg_h(PlanTable& step) {
  const std::string input = step.string_or("input", "output");
  if (input != "output" && input != "deg/h") step.fail_at("input", "must be \"output\" or \"deg/h\"");
  return input == "deg/h";
}

std::optional<AxisOrientation> read_earth_rate_removal(PlanTable& step, const PlanContext& context) {
  const bool remove = step.boolean_or("remove_earth_rate", false);
  const double elevation = step.number_or("ira_elevation_deg", 0.0);
  if (!remove) {
    if (step.contains("ira_elevation_deg")) step.fail_at("ira_elevation_deg", "is used only with remove_earth_rate = true");
    return std::nullopt;
  }
  AxisOrientation axis{context.site.latitude_deg, context.site.heading_deg, elevation};
  check_in_plan(step, [&] { axis.validate(); });
  return axis;
}

}  // namespace inertest::campaign
