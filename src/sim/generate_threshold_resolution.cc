// Simulated threshold (GJB 2426A-2004 5.10, method 2: dividing head) and resolution (5.11) tests.
// The simulated gyro has no dead zone, so the sim knows no threshold or resolution of its own: these
// tests give records to process, and their figures are bounded by the noise only (no truth entry).
//
// threshold: IA horizontal on the dividing head (zero mark north), at each reading β the gyro
// senses Ωe·cos φ·cos β (eq. 16). Keys: angles_deg = [0, 30, 60, 80, 85, 88, 89, 90, 91, 92, 95,
// 100, 120, 150, 180], seconds = 60. Writes <name>/positions.csv (angle_deg,output).
//
// resolution: IA up on the rate table at the base rate ±Ω0, then Ω0 + ΔΩj, the base output measured
// again before every increment. Keys: base_rate_deg_s = 1, increments_deg_s = [1e-2, 5e-3, 2e-3,
// 1e-3, 5e-4, 2e-4, 1e-4], seconds = 30. Writes <name>/steps.csv (base_rate,base_output,rate,output).
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/units.h"
#include "sim/generators.h"

namespace inertest::sim {

void generate_threshold(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const std::vector<double> angles = test.optional_numbers("angles_deg").value_or(
      std::vector<double>{0, 30, 60, 80, 85, 88, 89, 90, 91, 92, 95, 100, 120, 150, 180});
  const double seconds = test.number_or("seconds", 60.0);
  if (!(seconds > 0.0)) test.fail_at("seconds", "must be positive");
  if (lab.dry_run) return;
  const GyroParameters& gyro = lab.gyro;
  const double fs = gyro.sample_rate_hz;
  GyroModel model(gyro, lab.random(name), 3600.0);
  std::string text = fmt::format("# threshold '{}' (GJB 2426A 5.10, method 2): IA horizontal on the dividing head, "
                                 "mean output over {} s per reading\nangle_deg,output\n",
                                 name, seconds);
  for (const double angle : angles) {
    const double beta = angle * constants::kDegree;
    const Rig rig = static_rig(lab.site, mounting({std::sin(beta), std::cos(beta), 0.0}, {0, 0, 1}),
                               constant_temperature(gyro.reference_temperature_c));
    model.record(rig, static_cast<std::size_t>(std::llround(fs)));
    const auto pulses = model.record(rig, static_cast<std::size_t>(std::llround(seconds * fs)));
    fmt::format_to(std::back_inserter(text), "{},{}\n", exact(angle), exact(mean_output(pulses, fs)));
  }
  lab.write(name + "/positions.csv", text);
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"threshold\"\nname = \"{}\"\nmethod = 2\nfile = \"{}/positions.csv\"\n"
                                "heading_deg = 0\n\n",
                                name, name);
  lab.tests.push_back({{"name", name}, {"kind", "threshold"}, {"method", 2}, {"angles_deg", angles}, {"seconds", seconds}});
}

void generate_resolution(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const double base = test.number_or("base_rate_deg_s", 1.0);
  const std::vector<double> increments = test.optional_numbers("increments_deg_s")
                                             .value_or(std::vector<double>{1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4});
  const double seconds = test.number_or("seconds", 30.0);
  if (!(base > 0.0)) test.fail_at("base_rate_deg_s", "must be positive (it is run both ways)");
  if (!(seconds > 0.0)) test.fail_at("seconds", "must be positive");
  for (const double d : increments) {
    if (!(d > 0.0)) test.fail_at("increments_deg_s", "must be positive");
  }
  if (lab.dry_run) return;
  const GyroParameters& gyro = lab.gyro;
  const double fs = gyro.sample_rate_hz;
  const Matrix3 ia_up = mounting({0, 0, 1}, {1, 0, 0});
  GyroModel model(gyro, lab.random(name), 3600.0);
  auto mean_at = [&](double rate) {
    const Rig rig = lab.rate_table.rig(lab.site, ia_up, rate * constants::kDegree, 0.0, model.time_s(),
                                       constant_temperature(gyro.reference_temperature_c));
    model.record(rig, static_cast<std::size_t>(std::llround(fs)));
    return mean_output(model.record(rig, static_cast<std::size_t>(std::llround(seconds * fs))), fs);
  };
  std::string text = fmt::format("# resolution '{}' (GJB 2426A 5.11): mean outputs over {} s\n"
                                 "base_rate,base_output,rate,output\n",
                                 name, seconds);
  for (const double sign : {1.0, -1.0}) {
    for (const double d : increments) {
      const double base_output = mean_at(sign * base);
      const double output = mean_at(sign * base + d);
      fmt::format_to(std::back_inserter(text), "{},{},{},{}\n", exact(sign * base), exact(base_output),
                     exact(sign * base + d), exact(output));
    }
  }
  lab.write(name + "/steps.csv", text);
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"resolution\"\nname = \"{}\"\nfile = \"{}/steps.csv\"\n\n", name,
                                name);
  lab.tests.push_back({{"name", name}, {"kind", "resolution"}, {"base_rate_deg_s", base},
                       {"increments_deg_s", increments}, {"seconds", seconds}});
}

}  // namespace inertest::sim
