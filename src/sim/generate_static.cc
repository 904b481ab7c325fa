// Simulated static records: the bias test (GJB 2426A-2004 5.12, kind "bias") and the long static
// record for Allan variance analysis (IEEE Std 952-1997 Annex C, kind "allan"). The gyro stands on
// the position table with IA east, OA north, SA up, so the Earth rate has no IA component.
//   bias:  seconds = 7200, temperature_c
//   allan: hours = 30, sample_rate_hz (default: the gyro's), temperature_c
// Writes <name>.csv (time,output).
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/units.h"
#include "sim/generators.h"

namespace inertest::sim {
namespace {

constexpr double kDegHourPerDegSecond = 3600.0;

struct StaticRun {
  GyroParameters gyro;
  double seconds = 0.0;
  double temperature = 0.0;
  double true_bias_deg_h = 0.0;
};

StaticRun record_static(const std::string& name, Lab& lab, GyroParameters gyro, double seconds, double temperature) {
  const Matrix3 ia_east = mounting({1, 0, 0}, {0, 1, 0});
  const Rig rig = static_rig(lab.site, ia_east, constant_temperature(temperature));
  GyroModel model(gyro, lab.random(name), 3600.0);
  const double start = model.time_s();
  const auto pulses = model.record(rig, static_cast<std::size_t>(std::llround(seconds * gyro.sample_rate_hz)), 1);
  lab.write(name + ".csv", time_series_csv(pulses, gyro.sample_rate_hz, start,
                                           fmt::format("static, IA east, SA up, {} degC, {} Hz", temperature,
                                                       gyro.sample_rate_hz)));
  return {gyro, seconds, temperature, model.static_output_deg_s(rig(start), 1e9) * kDegHourPerDegSecond};
}

}  // namespace

void generate_static(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const double seconds = test.number_or("seconds", 7200.0);
  const double temperature = test.number_or("temperature_c", lab.gyro.reference_temperature_c);
  if (!(seconds > 0.0)) test.fail_at("seconds", "must be positive");
  if (lab.dry_run) return;
  const StaticRun run = record_static(name, lab, lab.gyro, seconds, temperature);
  // The bias: the model's static output with g along SA (eq. 2: DF + DS·fS + DSS·fS²) at T.
  lab.truth.push_back({name, "bias", "", run.true_bias_deg_h, "deg/h",
                       4.0 * noise_of_mean_deg_s(lab.gyro, seconds) * kDegHourPerDegSecond,
                       fmt::format("4 sigma of the mean of a {} s record", seconds)});
  lab.tests.push_back({{"name", name}, {"kind", "bias"}, {"file", name + ".csv"}, {"seconds", seconds},
                       {"temperature_c", temperature}});
}

void generate_allan(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const double hours = test.number_or("hours", 30.0);
  GyroParameters gyro = lab.gyro;
  gyro.sample_rate_hz = test.number_or("sample_rate_hz", gyro.sample_rate_hz);
  const double temperature = test.number_or("temperature_c", gyro.reference_temperature_c);
  if (!(hours > 0.0)) test.fail_at("hours", "must be positive");
  if (!(gyro.sample_rate_hz > 0.0)) test.fail_at("sample_rate_hz", "must be positive");
  if (lab.dry_run) return;
  const double seconds = hours * 3600.0;
  record_static(name, lab, gyro, seconds, temperature);
  // IEEE 952 Annex C coefficients as simulated. Tolerances: the relative 1-sigma of an overlapping
  // Allan deviation at τ with T/τ clusters is about 1/√(2(T/τ − 1)) (IEEE 952 C.11); each term
  // is judged at the τ where it is read (N at τ = 1 s, B at its floor, K at T/10), 4 sigma.
  auto relative = [&](double tau) { return 1.0 / std::sqrt(2.0 * (seconds / tau - 1.0)); };
  lab.truth.push_back({name, "angle random walk", "", gyro.angle_random_walk_deg_rt_h, "deg/sqrt(h)",
                       4.0 * relative(1.0) * gyro.angle_random_walk_deg_rt_h, "4 sigma of the Allan deviation at 1 s"});
  lab.truth.push_back({name, "bias instability", "", gyro.bias_instability_deg_h, "deg/h",
                       4.0 * relative(seconds / 100.0) * gyro.bias_instability_deg_h,
                       "4 sigma of the Allan deviation at T/100"});
  lab.truth.push_back({name, "rate random walk", "", gyro.rate_random_walk_deg_h_rt_h, "deg/h/sqrt(h)",
                       4.0 * relative(seconds / 10.0) * gyro.rate_random_walk_deg_h_rt_h,
                       "4 sigma of the Allan deviation at T/10"});
  lab.tests.push_back({{"name", name}, {"kind", "allan"}, {"file", name + ".csv"}, {"hours", hours},
                       {"sample_rate_hz", gyro.sample_rate_hz}, {"temperature_c", temperature}});
}

}  // namespace inertest::sim
