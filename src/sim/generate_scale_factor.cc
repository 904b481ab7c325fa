// Simulated scale-factor test, GJB 2426A-2004 5.8.1.3: static run, the rates each way, static run;
// IA up along the rate-table axis. Test keys:
//   rates_deg_s = [...]       # positive rates; each is run +Ω then the set again −Ω (default 12)
//   seconds_per_rate = 60     # recorded after 1 s of settling at each rate
//   static_seconds = 60       # each static run
//   temperature_c             # default: the gyro's reference temperature
// Writes <name>/rate_NN.csv (raw) and <name>/points.csv (rate,output means); plan kind scale_factor.
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/units.h"
#include "sim/generators.h"
#include "sim/scale_factor_run.h"

namespace inertest::sim {

void generate_scale_factor(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const GyroParameters& gyro = lab.gyro;
  std::vector<double> magnitudes = test.optional_numbers("rates_deg_s").value_or(
      std::vector<double>{0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100, 200, 300});
  for (const double r : magnitudes) {
    if (!(r > 0.0)) test.fail_at("rates_deg_s", "must hold positive rates (each is run both ways)");
  }
  const double seconds = test.number_or("seconds_per_rate", 60.0);
  const double static_seconds = test.number_or("static_seconds", 60.0);
  const double temperature = test.number_or("temperature_c", gyro.reference_temperature_c);
  if (!(seconds > 0.0) || !(static_seconds > 0.0)) test.fail("seconds_per_rate and static_seconds must be positive");
  if (lab.dry_run) return;

  GyroModel model(gyro, lab.random(name), 3600.0);
  const ScaleFactorRun run = record_scale_factor_run(
      lab, model, magnitudes, seconds, static_seconds, constant_temperature(temperature),
      fmt::format("simulated scale factor test '{}', mean output per rate (GJB 2426A 5.8.1.3), {} degC", name, temperature),
      name + "/rate_");
  lab.write(name + "/points.csv", run.points_csv);

  // Truth: the GJB 2426A definitions (eqs. 2-11) applied to the noise-free instrument at these
  // rates; expected: the same on the noise-free run on the real table (its rate error scales K).
  // Tolerances: 4 sigma of K and Ka from the covariance of all the points' noise (the flicker and the
  // random walk correlate them over the run), of Kn from the noise of one rate's mean (σ_F).
  const ScaleFactorTruth& t = run.truth;
  const ScaleFactorTruth& e = run.expected;
  const double sigma_k = run.sigma_scale_factor;
  const double sigma_asymmetry = run.sigma_asymmetry;
  const std::string k_unit = gyro.output_unit + "/(deg/s)";
  const std::string basis = fmt::format("4 sigma from the noise of the {} s means", seconds);
  lab.truth.push_back({name, "scale factor", "scale_factor", t.scale_factor, k_unit, 4.0 * sigma_k,
                       basis + "; expected includes the rate table's rate error", e.scale_factor - t.scale_factor});
  lab.truth.push_back({name, "scale factor nonlinearity", "nonlinearity", t.nonlinearity * 1e6, "ppm",
                       4.0 * run.sigma_point / t.largest_output * 1e6, basis, (e.nonlinearity - t.nonlinearity) * 1e6});
  lab.truth.push_back({name, "scale factor asymmetry", "asymmetry", t.asymmetry * 1e6, "ppm",
                       4.0 * sigma_asymmetry * 1e6, basis, (e.asymmetry - t.asymmetry) * 1e6});

  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"scale_factor\"\nname = \"{}\"\nfile = \"{}/points.csv\"\n\n",
                                name, name);
  lab.tests.push_back({{"name", name}, {"kind", "scale_factor"}, {"temperature_c", temperature},
                       {"rates_deg_s", run.rates}, {"seconds_per_rate", seconds}});
}

}  // namespace inertest::sim
