// Simulated scale-factor series tests, each made of scale-factor runs (scale_factor_run.h):
//
// scale_factor_temperature (GJB 2426A-2004 5.8.5): the gyro in the temperature chamber, soaked at
// each set point in turn (the first is room temperature), then a scale-factor run. Test keys:
//   temperatures_c = [20, -40, 60], soak_s = 3600, thermal_time_constant_s = 600,
//   rates_deg_s = [1, 10, 100, 300], seconds_per_rate = 10, static_seconds = 10
// Writes <name>/points_<T>C.csv. Truth: eq. (13) on the noise-free K at the set points; expected:
// on the noise-free K at the temperature the gyro had (it lags the chamber).
//
// scale_factor_repeatability (5.8.4): `runs` power-ons, each with its own scale-factor offset drawn
// from the gyro's scale_factor_repeatability_ppm. Keys: runs = 6, rates_deg_s, seconds_per_rate,
// static_seconds. Writes <name>/run_N.csv. Truth: eq. (12) on the K each power-on really had.
//
// maximum_input_rate (5.9): one scale-factor run out beyond the expected maximum. Keys:
// rates_deg_s = [1, 10, 50, 100, 200, 300, 400, 500], nonlinearity_limit_ppm = 10,
// seconds_per_rate, static_seconds. Writes <name>/points.csv. Truth: 5.9 on the noise-free outputs.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/units.h"
#include "sim/generators.h"
#include "sim/scale_factor_run.h"

namespace inertest::sim {
namespace {

struct RunKeys {
  std::vector<double> magnitudes;
  double seconds = 10.0;
  double static_seconds = 10.0;
};

RunKeys read_run_keys(campaign::PlanTable& test, std::vector<double> default_rates) {
  RunKeys keys;
  keys.magnitudes = test.optional_numbers("rates_deg_s").value_or(default_rates);
  for (const double r : keys.magnitudes) {
    if (!(r > 0.0)) test.fail_at("rates_deg_s", "must hold positive rates (each is run both ways)");
  }
  if (keys.magnitudes.size() < 2) test.fail_at("rates_deg_s", "needs at least two rates");
  keys.seconds = test.number_or("seconds_per_rate", keys.seconds);
  keys.static_seconds = test.number_or("static_seconds", keys.static_seconds);
  if (!(keys.seconds > 0.0) || !(keys.static_seconds > 0.0)) test.fail("seconds_per_rate and static_seconds must be positive");
  return keys;
}

double run_duration(const RunKeys& keys) {
  return 2.0 * (keys.static_seconds + 1.0) + 2.0 * keys.magnitudes.size() * (keys.seconds + 1.0);
}

// The instrument's own K at temperature T (exact rates about IA, vertical Earth rate, g along IA).
double scale_factor_at(const GyroModel& model, const Lab& lab, const std::vector<double>& rates, double temperature) {
  std::vector<double> outputs;
  for (const double rate : rates) {
    Stimulus s;
    s.rate = {rate * constants::kDegree + lab.site.earth_rate_enu()[2], 0.0, 0.0};
    s.specific_force = {lab.site.specific_force_enu_g()[2], 0.0, 0.0};
    s.temperature_c = temperature;
    outputs.push_back(model.parameters().scale_factor * model.static_output_deg_s(s, 1e9));
  }
  return scale_factor_truth(rates, outputs).scale_factor;
}

// Eq. (13): max over the test temperatures of |(Ki − Km)/(Km·(Ti − Tm))|, ppm/degC; the first is Tm.
double temperature_sensitivity(const std::vector<double>& temperatures, const std::vector<double>& k) {
  double worst = 0.0;
  for (std::size_t i = 1; i < k.size(); ++i) {
    worst = std::max(worst, std::abs((k[i] - k[0]) / (k[0] * (temperatures[i] - temperatures[0]))) * 1e6);
  }
  return worst;
}

double sample_sd(const std::vector<double>& values) {
  double mean = 0.0;
  for (const double v : values) mean += v;
  mean /= static_cast<double>(values.size());
  double sum = 0.0;
  for (const double v : values) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / static_cast<double>(values.size() - 1));
}

double mean_of(const std::vector<double>& values) {
  double mean = 0.0;
  for (const double v : values) mean += v;
  return mean / static_cast<double>(values.size());
}

}  // namespace

void generate_scale_factor_temperature(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const std::vector<double> temperatures =
      test.optional_numbers("temperatures_c").value_or(std::vector<double>{20, -40, 60});
  const double soak = test.number_or("soak_s", 3600.0);
  const double lag = test.number_or("thermal_time_constant_s", 600.0);
  const RunKeys keys = read_run_keys(test, {1, 10, 100, 300});
  if (temperatures.size() < 2) test.fail_at("temperatures_c", "needs room temperature and at least one other");
  for (std::size_t i = 1; i < temperatures.size(); ++i) {
    if (temperatures[i] == temperatures[0]) test.fail_at("temperatures_c", "a test temperature equals room temperature");
  }
  if (!(soak >= 0.0) || !(lag > 0.0)) test.fail("soak_s must be >= 0 and thermal_time_constant_s positive");
  if (lab.dry_run) return;
  const GyroParameters& gyro = lab.gyro;
  const double duration = run_duration(keys);
  TemperatureChamber chamber{temperatures, soak + duration, lag, temperatures[0]};
  const double power_on = 3600.0;
  const TemperatureProfile profile = chamber.profile(power_on);
  std::vector<double> k_true, k_expected, sigma;
  std::string runs;
  for (std::size_t i = 0; i < temperatures.size(); ++i) {
    GyroModel model(gyro, lab.random(fmt::format("{}/{}C", name, temperatures[i])),
                    power_on + static_cast<double>(i) * (soak + duration) + soak);
    const ScaleFactorRun run = record_scale_factor_run(
        lab, model, keys.magnitudes, keys.seconds, keys.static_seconds, profile,
        fmt::format("scale factor test '{}' in the chamber at {} degC after a {} s soak", name, temperatures[i], soak));
    const std::string file = fmt::format("{}/points_{}C.csv", name, temperatures[i]);
    lab.write(file, run.points_csv);
    k_true.push_back(scale_factor_at(model, lab, run.rates, temperatures[i]));
    k_expected.push_back(run.expected.scale_factor);
    sigma.push_back(run.sigma_scale_factor);
    runs += fmt::format("[[procedure.run]]\ntemperature_degC = {}\nfile = \"{}\"\n", exact(temperatures[i]), file);
  }
  // |max|a + e| − max|a|| <= max|e|: 4 sigma of the noisiest ratio.
  double tolerance = 0.0;
  for (std::size_t i = 1; i < temperatures.size(); ++i) {
    tolerance = std::max(tolerance, 4.0 * std::hypot(sigma[i], sigma[0]) /
                                        std::abs(k_expected[0] * (temperatures[i] - temperatures[0])) * 1e6);
  }
  const double truth = temperature_sensitivity(temperatures, k_true);
  lab.truth.push_back({name, "scale factor temperature sensitivity", "scale_factor_temperature_sensitivity", truth,
                       "ppm/degC", tolerance,
                       "4 sigma of each K from the noise of its points; expected includes the gyro's thermal lag "
                       "behind the chamber and the rate table's errors",
                       temperature_sensitivity(temperatures, k_expected) - truth});
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"scale_factor_temperature\"\nname = \"{}\"\n"
                                "reference_temperature_degC = {}\n{}\n",
                                name, exact(temperatures[0]), runs);
  lab.tests.push_back({{"name", name}, {"kind", "scale_factor_temperature"}, {"temperatures_c", temperatures},
                       {"soak_s", soak}, {"thermal_time_constant_s", lag}, {"rates_deg_s", keys.magnitudes}});
}

void generate_scale_factor_repeatability(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const double runs = test.number_or("runs", 6.0);
  const double temperature = test.number_or("temperature_c", lab.gyro.reference_temperature_c);
  const RunKeys keys = read_run_keys(test, {1, 10, 100, 300});
  if (!(runs >= 2.0) || runs != std::floor(runs)) test.fail_at("runs", "must be a whole number >= 2");
  if (lab.dry_run) return;
  Random turn_on = lab.random(name + "/turn-on");
  std::vector<double> k_true, k_expected;
  double sigma = 0.0;
  std::string files;
  for (int q = 1; q <= static_cast<int>(runs); ++q) {
    GyroParameters gyro = lab.gyro;
    gyro.scale_factor *= 1.0 + gyro.scale_factor_repeatability_ppm * 1e-6 * turn_on.normal();
    GyroModel model(gyro, lab.random(fmt::format("{}/run{}", name, q)), 3600.0);
    const ScaleFactorRun run = record_scale_factor_run(
        lab, model, keys.magnitudes, keys.seconds, keys.static_seconds, constant_temperature(temperature),
        fmt::format("scale factor repeatability '{}', run {} (after a power-off and cool-down)", name, q));
    const std::string file = fmt::format("{}/run_{}.csv", name, q);
    lab.write(file, run.points_csv);
    k_true.push_back(run.truth.scale_factor);
    k_expected.push_back(run.expected.scale_factor);
    sigma = std::max(sigma, run.sigma_scale_factor);
    files += fmt::format("{}\"{}\"", q == 1 ? "" : ", ", file);
  }
  // Eq. (12) on the K each power-on had; the noise of each K moves the sample sd by at most the
  // sample sd of the noise (triangle inequality), bounded at 4 sigma by its chi quantile.
  // Kr >= 0: the sd over |K̄| (a gyro of negative K, -36000 pulse/s per deg/s, has the same Kr).
  const double truth = sample_sd(k_true) / std::abs(mean_of(k_true)) * 1e6;
  const double expected = sample_sd(k_expected) / std::abs(mean_of(k_expected)) * 1e6;
  lab.truth.push_back({name, "scale factor repeatability", "scale_factor_repeatability", truth, "ppm",
                       sample_sd_bound(sigma, runs) / std::abs(mean_of(k_true)) * 1e6,
                       "4-sigma chi bound on the sample sd of the runs' K noise", expected - truth});
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"scale_factor_repeatability\"\nname = \"{}\"\nfiles = [{}]\n"
                                "minimum_runs = {}\n\n",
                                name, files, std::min(6, static_cast<int>(runs)));
  lab.tests.push_back({{"name", name}, {"kind", "scale_factor_repeatability"}, {"runs", runs},
                       {"rates_deg_s", keys.magnitudes}, {"true_run_scale_factors", k_true}});
}

void generate_maximum_input_rate(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const double limit = test.number_or("nonlinearity_limit_ppm", 10.0);
  const double temperature = test.number_or("temperature_c", lab.gyro.reference_temperature_c);
  const RunKeys keys = read_run_keys(test, {1, 10, 50, 100, 200, 300, 400, 500});
  if (!(limit > 0.0)) test.fail_at("nonlinearity_limit_ppm", "must be positive");
  if (!std::is_sorted(keys.magnitudes.begin(), keys.magnitudes.end())) test.fail_at("rates_deg_s", "must increase");
  if (lab.dry_run) return;
  GyroModel model(lab.gyro, lab.random(name), 3600.0);
  const ScaleFactorRun run = record_scale_factor_run(
      lab, model, keys.magnitudes, keys.seconds, keys.static_seconds, constant_temperature(temperature),
      fmt::format("maximum input rate test '{}': scale factor points beyond the expected maximum", name));
  lab.write(name + "/points.csv", run.points_csv);
  // 5.9 on the noise-free run: ranges from the second magnitude up; Kn(R) of the points |Ω| <= R.
  // The noise moves Kn(R) by about σ_F/F_max(R); a range within 4 of those of the limit could go
  // either way, and the tolerance covers every answer such ranges allow.
  std::vector<double> clean_outputs;
  const Matrix3 ia_up = mounting({0, 0, 1}, {1, 0, 0});
  for (const double rate : run.rates) {
    const Rig rig =
        lab.rate_table.rig(lab.site, ia_up, rate * constants::kDegree, 0.0, 0.0, constant_temperature(temperature));
    clean_outputs.push_back(lab.gyro.scale_factor * model.static_output_deg_s(rig(0.0), 1e9));
  }
  double answer = 0.0, lowest = 0.0, highest = 0.0;
  bool surely_failed = false, maybe_failed = false, failed = false;
  for (std::size_t m = 1; m < keys.magnitudes.size(); ++m) {
    const double range = keys.magnitudes[m];
    std::vector<double> rates, outputs;
    for (std::size_t j = 0; j < run.rates.size(); ++j) {
      if (std::abs(run.rates[j]) <= range) {
        rates.push_back(run.rates[j]);
        outputs.push_back(clean_outputs[j]);
      }
    }
    const ScaleFactorTruth t = scale_factor_truth(rates, outputs);
    const double kn = t.nonlinearity * 1e6;
    const double margin = 4.0 * run.sigma_point / t.largest_output * 1e6;
    failed = failed || kn > limit;
    maybe_failed = maybe_failed || kn + margin > limit;
    surely_failed = surely_failed || kn - margin > limit;
    if (!failed) answer = range;
    if (!maybe_failed) lowest = range;
    if (!surely_failed) highest = range;
  }
  if (answer == 0.0) test.fail("the noise-free gyro fails nonlinearity_limit_ppm over the smallest range");
  lab.truth.push_back({name, "maximum input rate", "maximum_input_rate", answer, "deg/s",
                       std::max(answer - lowest, highest - answer) + rounding_tolerance(answer),
                       "the tested rates the noise (4 sigma of each range's Kn) could select; else exact but for "
                       "rounding"});
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"maximum_input_rate\"\nname = \"{}\"\nfile = \"{}/points.csv\"\n"
                                "nonlinearity_limit_ppm = {}\n\n",
                                name, name, exact(limit));
  lab.tests.push_back({{"name", name}, {"kind", "maximum_input_rate"}, {"rates_deg_s", keys.magnitudes},
                       {"nonlinearity_limit_ppm", limit}});
}

}  // namespace inertest::sim
