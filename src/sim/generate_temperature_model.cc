// Simulated chamber ramp for the temperature model (issue 20): the gyro static with IA east in a
// chamber that soaks, heats and cools (sim/thermal_model.h). Keys: set_points_c = [60, -20, 20],
// ramps_c_per_min = [1, 2, 0.5] (one per set point), soak_s = 1800, start_c (the gyro's reference
// temperature), coil_time_constant_s = 300, sample_rate_hz = 1, and the thermal terms beyond the
// gyro's D_0 (bias_deg_h) and D_T (bias_temperature_deg_h_per_c): bias_t2_deg_h_per_c2 = 4e-5,
// rate_deg_h_per_c_per_min = 0.03, temperature_rate_deg_h_per_c2_per_min = 4e-4,
// hysteresis_deg_h = 0.005. Writes <name>/ramp.csv (time,output,coil,chamber). Truth: every
// coefficient of the model, checked within 4 of its reported sigma, and the residual bias stability
// at the noise floor, the white noise's 100 s window means.
#include <cmath>

#include <fmt/format.h>

#include "inertest/sim/thermal_model.h"
#include "sim/generators.h"

namespace inertest::sim {

void generate_temperature_model(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  ChamberProfile chamber;
  chamber.set_points_degC = test.optional_numbers("set_points_c").value_or(chamber.set_points_degC);
  chamber.ramps_degC_per_min = test.optional_numbers("ramps_c_per_min").value_or(chamber.ramps_degC_per_min);
  chamber.soak_s = test.number_or("soak_s", chamber.soak_s);
  chamber.start_degC = test.number_or("start_c", lab.gyro.reference_temperature_c);
  ThermalGyroParameters gyro;
  gyro.scale_factor = lab.gyro.scale_factor;
  gyro.reference_temperature_degC = lab.gyro.reference_temperature_c;
  gyro.angle_random_walk_deg_rt_h = lab.gyro.angle_random_walk_deg_rt_h;
  gyro.bias_polynomial_deg_h = {lab.gyro.bias_deg_h, lab.gyro.bias_temperature_deg_h_per_c,
                                test.number_or("bias_t2_deg_h_per_c2", gyro.bias_polynomial_deg_h[2])};
  gyro.rate_deg_h_per_degC_min = test.number_or("rate_deg_h_per_c_per_min", gyro.rate_deg_h_per_degC_min);
  gyro.temperature_rate_deg_h_per_degC2_min =
      test.number_or("temperature_rate_deg_h_per_c2_per_min", gyro.temperature_rate_deg_h_per_degC2_min);
  gyro.hysteresis_deg_h = test.number_or("hysteresis_deg_h", gyro.hysteresis_deg_h);
  gyro.coil_time_constant_s = test.number_or("coil_time_constant_s", gyro.coil_time_constant_s);
  gyro.sample_rate_hz = test.number_or("sample_rate_hz", gyro.sample_rate_hz);
  if (chamber.ramps_degC_per_min.size() != chamber.set_points_degC.size()) {
    test.fail_at("ramps_c_per_min", "needs one ramp rate per set point");
  }
  if (!(chamber.soak_s > 0.0)) test.fail_at("soak_s", "must be positive");
  if (lab.dry_run) return;
  Random random = lab.random(name + "/ramp");
  const std::string file = name + "/ramp.csv";
  lab.write(file, thermal_record_csv(simulate_thermal_record(chamber, gyro, random)));
  const auto coefficient = [&](const char* quantity, const char* key, double value, const char* unit) {
    lab.truth.push_back({name, quantity, fmt::format("/bias_coefficients/{}", key), value, unit, 0.0,
                         "4 sigma of the least-squares fit's reported uncertainty", 0.0, 4.0});
  };
  coefficient("bias D_0 at T_ref", "D_0", gyro.bias_polynomial_deg_h[0], "deg/h");
  coefficient("bias temperature coefficient D_T", "D_T", gyro.bias_polynomial_deg_h[1], "deg/h/degC");
  coefficient("bias coefficient D_T2", "D_T2", gyro.bias_polynomial_deg_h[2], "deg/h/degC^2");
  coefficient("bias temperature-rate coefficient D_dT", "D_dT", gyro.rate_deg_h_per_degC_min, "deg/h/(degC/min)");
  coefficient("bias coefficient D_TdT", "D_TdT", gyro.temperature_rate_deg_h_per_degC2_min, "deg/h/degC/(degC/min)");
  coefficient("bias hysteresis D_H", "D_H", gyro.hysteresis_deg_h, "deg/h");
  // The noise floor: white noise's 100 s window means, sigma_sample / sqrt(100 fs).
  lab.truth.push_back({name, "residual bias stability (noise floor)", "residual_bias_stability",
                       gyro.sample_noise_deg_h() / std::sqrt(100.0 * gyro.sample_rate_hz), "deg/h", 0.0,
                       "4 sigma of the reported uncertainty of a sample standard deviation", 0.0, 4.0});
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"temperature_model\"\nname = \"{}\"\nfile = \"{}\"\n"
                                "temperature_column = [\"coil\", \"chamber\"]\nreference_temperature = {}\n\n",
                                name, file, exact(gyro.reference_temperature_degC));
  lab.tests.push_back({{"name", name}, {"kind", "temperature_model"}, {"set_points_c", chamber.set_points_degC},
                       {"ramps_c_per_min", chamber.ramps_degC_per_min}, {"soak_s", chamber.soak_s},
                       {"coil_time_constant_s", gyro.coil_time_constant_s}, {"sample_rate_hz", gyro.sample_rate_hz}});
}

}  // namespace inertest::sim
