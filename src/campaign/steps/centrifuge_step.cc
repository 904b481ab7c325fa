// Plan kind "centrifuge": drift coefficients from a centrifuge test with a counter-rotating platform
// (the centrifuge paper, core/citations.h, eqs. 2, 5-16; see inertest/centrifuge/drift_calibration.h).
//   file = "table3.csv"         # harmonic amplitudes or raw samples (inertest/centrifuge/centrifuge_record.h)
//   radius_m = 1.0              # optional, default 1 m
//   latitude_deg = 45.75        # optional, default the plan's [site] latitude
//   gravity_m_s2 = 9.8          # optional, default the plan's [site] gravity
//   k1_rad = -2e-5              # optional measured centrifuge errors; absent: 0, or estimated
//   k2_rad = 2e-5
//   delta_omega_rad_s = 1e-5
//   compensation = true         # optional; false sets epsilon = 0
//   estimate_errors = false     # optional; estimate the unmeasured errors (two or more g-levels)
#include "campaign/step_registry.h"
#include "inertest/centrifuge/centrifuge_record.h"
#include "inertest/centrifuge/drift_calibration.h"

namespace inertest::campaign {
namespace {

StepAction prepare(PlanTable& step, const PlanContext& context) {
  const std::string file = step.file("file");
  centrifuge::DriftCalibrationOptions options;
  options.site.radius_m = step.number_or("radius_m", options.site.radius_m);
  options.site.latitude_rad = step.number_or("latitude_deg", context.site.latitude_deg) * constants::kDegree;
  options.site.gravity_m_s2 = step.number_or("gravity_m_s2", context.site.gravity_m_s2);
  options.k1_rad = step.optional_number("k1_rad");
  options.k2_rad = step.optional_number("k2_rad");
  options.delta_omega_rad_s = step.optional_number("delta_omega_rad_s");
  options.compensation = step.boolean_or("compensation", options.compensation);
  options.estimate_errors = step.boolean_or("estimate_errors", options.estimate_errors);
  try {
    options.validate();
  } catch (const Error& e) {
    step.fail(e.message());
  }
  return [file, options](const StepRunContext&) {
    const centrifuge::CentrifugeRecord record = centrifuge::read_centrifuge_record(file);
    return centrifuge::calibrate_drift_coefficients(record.runs(), options).to_json();
  };
}

const bool registered = register_step("centrifuge", prepare);

}  // namespace
}  // namespace inertest::campaign
