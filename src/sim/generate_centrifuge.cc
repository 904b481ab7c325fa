// Simulated centrifuge drift calibration (reference section 1): at each g-level and each work-face
// angle β the platform is sampled 36 times per revolution (encoder-triggered counting), for a
// number of revolutions. Test keys:
//   g_levels = [10, 20]          # A = Ω²R0/g0
//   beta_deg = [0, 90, 180, 270]
//   revolutions = 100
//   samples_per_revolution = 36
//   temperature_c
// Writes <name>/g<A>_beta<β>.csv with columns time (s), gamma (deg, IA to the centripetal
// direction at the centre of the counting interval, from the platform encoder), output (mean over
// the interval, in the instrument's unit).
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/units.h"
#include "sim/generators.h"

namespace inertest::sim {

void generate_centrifuge(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const std::vector<double> levels = test.optional_numbers("g_levels").value_or(std::vector<double>{10.0, 20.0});
  const std::vector<double> betas = test.optional_numbers("beta_deg").value_or(std::vector<double>{0, 90, 180, 270});
  const double revolutions = test.number_or("revolutions", 100.0);
  const double per_revolution = test.number_or("samples_per_revolution", 36.0);
  const double temperature = test.number_or("temperature_c", lab.gyro.reference_temperature_c);
  if (!(revolutions >= 1.0) || !(per_revolution >= 4.0)) test.fail("revolutions must be >= 1 and samples_per_revolution >= 4");
  for (const double a : levels) {
    if (!(a > 0.0)) test.fail_at("g_levels", "must be positive");
  }
  if (lab.dry_run) return;
  nlohmann::json files = nlohmann::json::array();
  for (const double level : levels) {
    for (const double beta : betas) {
      Centrifuge c = lab.centrifuge;
      c.rate_rad_s = std::sqrt(level * constants::kStandardGravity / c.radius_m);
      c.beta_rad = beta * constants::kDegree;
      GyroParameters gyro = lab.gyro;
      const double bin_rate = per_revolution * (c.rate_rad_s - c.errors.platform_rate_error) / (2.0 * constants::kPi);
      gyro.sample_rate_hz = bin_rate;
      const std::string stream = fmt::format("{}/g{}_beta{}", name, level, beta);
      GyroModel model(gyro, lab.random(stream), 3600.0);
      const double start = model.time_s();
      const Rig rig = c.rig(lab.site, start, constant_temperature(temperature));
      const auto count = static_cast<std::size_t>(std::llround(revolutions * per_revolution));
      const auto pulses = model.record(rig, count, 8);
      std::string text = fmt::format("# centrifuge {} g, beta {} deg, {} samples per revolution, {} degC\n"
                                     "time,gamma,output\n",
                                     level, beta, per_revolution, temperature);
      for (std::size_t i = 0; i < pulses.size(); ++i) {
        const double local = (static_cast<double>(i) + 0.5) / bin_rate;
        const double gamma = std::fmod(c.gamma(local) / constants::kDegree, 360.0);
        fmt::format_to(std::back_inserter(text), "{:.6f},{:.6f},{}\n", start + local, gamma,
                       exact(static_cast<double>(pulses[i]) * bin_rate));
      }
      const std::string file = fmt::format("{}/g{:02.0f}_beta{:03.0f}.csv", name, level, beta);
      lab.write(file, text);
      files.push_back({{"file", file}, {"g_level", level}, {"beta_deg", beta}, {"rate_rad_s", c.rate_rad_s}});
    }
  }
  const auto& d = lab.gyro.drift;
  const double df = lab.gyro.bias_deg_h + lab.gyro.bias_temperature_deg_h_per_c * (temperature - lab.gyro.reference_temperature_c);
  const std::pair<const char*, double> first[] = {{"DI", d.DI}, {"DO", d.DO}, {"DS", d.DS}};
  const std::pair<const char*, double> second[] = {{"DII", d.DII}, {"DOO", d.DOO}, {"DSS", d.DSS},
                                                   {"DIO", d.DIO}, {"DIS", d.DIS}, {"DOS", d.DOS}};
  lab.truth.push_back({name, "drift coefficient DF", "", df, "deg/h", 0.0, "not yet derived"});
  for (const auto& [key, value] : first) {
    lab.truth.push_back({name, std::string("drift coefficient ") + key, "", value, "deg/h/g", 0.0, "not yet derived"});
  }
  for (const auto& [key, value] : second) {
    lab.truth.push_back({name, std::string("drift coefficient ") + key, "", value, "deg/h/g^2", 0.0, "not yet derived"});
  }
  lab.tests.push_back({{"name", name}, {"kind", "centrifuge"}, {"runs", files}, {"revolutions", revolutions},
                       {"samples_per_revolution", per_revolution}, {"temperature_c", temperature}});
}

}  // namespace inertest::sim
