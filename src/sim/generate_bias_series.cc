// Simulated bias series tests and the records taken from power-on, the gyro static with IA east
// (bias_temperature, bias_repeatability, turn_on_time) or on the rate table (polarity):
//
// bias_temperature (GJB 2426A-2004 5.12.4): in the temperature chamber, soaked at each set point in
// turn (the first is room temperature), then a static record. Keys: temperatures_c = [20, -40, 60],
// soak_s = 3600, thermal_time_constant_s = 600, seconds = 600. Writes <name>/bias_<T>C.f64. Truth:
// eq. (22) with the model's bias at the set points; expected: at the temperatures the gyro had.
//
// bias_repeatability (5.12.3): `runs` power-ons, each with its own bias offset drawn from the gyro's
// bias_repeatability_deg_h. Keys: runs = 6, seconds = 600. Writes <name>/run_N.f64. Truth: eq. (21)
// on the bias each power-on really had.
//
// turn_on_time (5.5): static records from power-on showing the turn-on transient. Keys: runs = 1,
// seconds = 1200, rest_band_deg_h = 0.2, smoothing_s = 60. Writes <name>/power_on_N.f64. The plan
// gives the calibrated zero F0 (the gyro's settled output). Truth: 5.5.4 on the noise-free window
// means.
//
// polarity (5.7): IA up on the rate table at +Ω and −Ω. Keys: rate_deg_s = 10, seconds = 10.
// Writes <name>/plus.csv, <name>/minus.csv. Truth: the sign of the scale factor.
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/units.h"
#include "sim/generators.h"

namespace inertest::sim {
namespace {

constexpr double kDegHour = 3600.0;  // deg/h per deg/s

const Matrix3& ia_east() {
  static const Matrix3 m = mounting({1, 0, 0}, {0, 1, 0});
  return m;
}

double seconds_key(campaign::PlanTable& test, const char* key, double fallback) {
  const double value = test.number_or(key, fallback);
  if (!(value > 0.0)) test.fail_at(key, "must be positive");
  return value;
}

double whole_key(campaign::PlanTable& test, const char* key, double fallback, double minimum) {
  const double value = test.number_or(key, fallback);
  if (!(value >= minimum) || value != std::floor(value)) test.fail_at(key, fmt::format("must be a whole number >= {}", minimum));
  return value;
}

// Records a static run with IA east as f64; returns the noise-free mean bias (deg/h) over it.
double record_static_f64(Lab& lab, GyroModel& model, const TemperatureProfile& temperature, double seconds,
                         const std::string& file) {
  const Rig rig = static_rig(lab.site, ia_east(), temperature);
  const double fs = model.parameters().sample_rate_hz;
  const double start = model.time_s();
  const auto pulses = model.record(rig, lab.samples(seconds, fs), 1);
  lab.write(file, f64_record(pulses, fs));
  double total = 0.0;
  const int points = 200;
  for (int i = 0; i < points; ++i) {
    const double t = start + (i + 0.5) * seconds / points;
    total += model.static_output_deg_s(rig(t), t);
  }
  return total / points * kDegHour;
}

double sample_sd(const std::vector<double>& v) {
  double mean = 0.0;
  for (const double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  double sum = 0.0;
  for (const double x : v) sum += (x - mean) * (x - mean);
  return std::sqrt(sum / static_cast<double>(v.size() - 1));
}

double bias_sensitivity(const std::vector<double>& temperatures, const std::vector<double>& biases) {
  double worst = 0.0;
  for (std::size_t i = 1; i < biases.size(); ++i) {
    worst = std::max(worst, std::abs((biases[i] - biases[0]) / (temperatures[i] - temperatures[0])));
  }
  return worst;
}

}  // namespace

void generate_bias_temperature(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const std::vector<double> temperatures =
      test.optional_numbers("temperatures_c").value_or(std::vector<double>{20, -40, 60});
  const double soak = test.number_or("soak_s", 3600.0);
  const double lag = seconds_key(test, "thermal_time_constant_s", 600.0);
  const double seconds = seconds_key(test, "seconds", 600.0);
  if (temperatures.size() < 2) test.fail_at("temperatures_c", "needs room temperature and at least one other");
  for (std::size_t i = 1; i < temperatures.size(); ++i) {
    if (temperatures[i] == temperatures[0]) test.fail_at("temperatures_c", "a test temperature equals room temperature");
  }
  if (!(soak >= 0.0)) test.fail_at("soak_s", "must not be negative");
  if (lab.dry_run) return;
  const GyroParameters& gyro = lab.gyro;
  const double power_on = 3600.0;
  const TemperatureChamber chamber{temperatures, soak + seconds, lag, temperatures[0]};
  const TemperatureProfile profile = chamber.profile(power_on);
  std::vector<double> expected, truth;
  std::string runs;
  const double sigma = noise_of_record_mean_deg_s(gyro, seconds) * kDegHour;
  for (std::size_t i = 0; i < temperatures.size(); ++i) {
    GyroModel model(gyro, lab.random(fmt::format("{}/{}C", name, temperatures[i])),
                    power_on + static_cast<double>(i) * (soak + seconds) + soak);
    const std::string file = fmt::format("{}/bias_{}C.f64", name, temperatures[i]);
    expected.push_back(record_static_f64(lab, model, profile, seconds, file));
    const Rig at_set_point = static_rig(lab.site, ia_east(), constant_temperature(temperatures[i]));
    truth.push_back(model.static_output_deg_s(at_set_point(0.0), 1e9) * kDegHour);
    runs += fmt::format("[[procedure.run]]\ntemperature_degC = {}\nfile = \"{}\"\n", exact(temperatures[i]), file);
  }
  double tolerance = 0.0;
  for (std::size_t i = 1; i < temperatures.size(); ++i) {
    tolerance = std::max(tolerance, 4.0 * std::sqrt(2.0) * sigma / std::abs(temperatures[i] - temperatures[0]));
  }
  const double true_value = bias_sensitivity(temperatures, truth);
  lab.truth.push_back({name, "bias temperature sensitivity", "bias_temperature_sensitivity", true_value, "deg/h/degC",
                       tolerance, "4 sigma of two record means over the temperature step; expected includes the "
                                  "gyro's thermal lag behind the chamber",
                       bias_sensitivity(temperatures, expected) - true_value});
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"bias_temperature\"\nname = \"{}\"\nformat = \"f64\"\n"
                                "room_temperature_degC = {}\n{}\n",
                                name, exact(temperatures[0]), runs);
  lab.tests.push_back({{"name", name}, {"kind", "bias_temperature"}, {"temperatures_c", temperatures}, {"soak_s", soak},
                       {"thermal_time_constant_s", lag}, {"seconds", seconds}});
}

void generate_bias_repeatability(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const double runs = whole_key(test, "runs", 6.0, 2.0);
  const double seconds = seconds_key(test, "seconds", 600.0);
  const double temperature = test.number_or("temperature_c", lab.gyro.reference_temperature_c);
  if (lab.dry_run) return;
  Random turn_on = lab.random(name + "/turn-on");
  std::vector<double> truth;
  std::string files;
  for (int q = 1; q <= static_cast<int>(runs); ++q) {
    GyroParameters gyro = lab.gyro;
    gyro.bias_deg_h += gyro.bias_repeatability_deg_h * turn_on.normal();
    GyroModel model(gyro, lab.random(fmt::format("{}/run{}", name, q)), 3600.0);
    const std::string file = fmt::format("{}/run_{}.f64", name, q);
    truth.push_back(record_static_f64(lab, model, constant_temperature(temperature), seconds, file));
    files += fmt::format("{}\"{}\"", q == 1 ? "" : ", ", file);
  }
  const double sigma = noise_of_record_mean_deg_s(lab.gyro, seconds) * kDegHour;
  lab.truth.push_back({name, "bias repeatability", "bias_repeatability", sample_sd(truth), "deg/h",
                       sample_sd_bound(sigma, runs), "4-sigma chi bound on the sample sd of the runs' mean noise"});
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"bias_repeatability\"\nname = \"{}\"\nformat = \"f64\"\n"
                                "files = [{}]\n\n",
                                name, files);
  lab.tests.push_back({{"name", name}, {"kind", "bias_repeatability"}, {"runs", runs}, {"seconds", seconds},
                       {"true_run_biases_deg_h", truth}});
}

namespace {

// Turn-on time (5.5) or, with warm_up, warm-up time (5.6, computed as 5.5.4): records from power-on
// at rest, the figure the time the thermal transient takes to settle into the band.
void generate_power_on_time(campaign::PlanTable& test, const std::string& name, Lab& lab, bool warm_up) {
  const std::string kind = warm_up ? "warm_up_time" : "turn_on_time";
  const double runs = whole_key(test, "runs", 1.0, 1.0);
  const double seconds = seconds_key(test, "seconds", 1200.0);
  const double band = seconds_key(test, "rest_band_deg_h", 0.2);
  const double smoothing = seconds_key(test, "smoothing_s", 60.0);
  const double temperature = test.number_or("temperature_c", lab.gyro.reference_temperature_c);
  if (lab.dry_run) return;
  const GyroParameters& gyro = lab.gyro;
  const double fs = gyro.sample_rate_hz;
  const Rig rig = static_rig(lab.site, ia_east(), constant_temperature(temperature));
  std::string steps;
  double settled = 0.0;
  for (int q = 1; q <= static_cast<int>(runs); ++q) {
    GyroModel model(gyro, lab.random(fmt::format("{}/run{}", name, q)), 0.0);
    settled = gyro.scale_factor * model.static_output_deg_s(rig(0.0), 1e9);
    const std::string file = fmt::format("{}/power_on_{}.f64", name, q);
    lab.write(file, f64_record(model.record(rig, lab.samples(seconds, fs), 1), fs));
    steps += fmt::format("[[procedure.run]]\nfile = \"{}\"\n", file);
  }
  // 5.5.4 on the noise-free transient b·e^(−t/τ): window k, [kS, (k+1)S), has the mean
  // b·τ/S·(e^(−kS/τ) − e^(−(k+1)S/τ)); the time is the end of the first window within the band. The
  // noise of a window mean, σ_w, moves the crossing by τ·σ_w/band (the transient's slope there is
  // band/τ); the tolerance is 4 of those, rounded up to whole windows, plus one window.
  const double b = gyro.turn_on_bias_deg_h;
  const double tau = gyro.turn_on_time_constant_s;
  double truth = smoothing;
  if (tau > 0.0) {
    for (int k = 0; k * smoothing < seconds; ++k) {
      const double mean = b * tau / smoothing * (std::exp(-k * smoothing / tau) - std::exp(-(k + 1) * smoothing / tau));
      if (std::abs(mean) <= band) break;
      truth = (k + 2) * smoothing;
    }
  }
  const double sigma_w = noise_of_record_mean_deg_s(gyro, smoothing) * kDegHour;
  const double shift = tau > 0.0 ? 4.0 * tau * sigma_w / band : 0.0;
  lab.truth.push_back({name, warm_up ? "warm-up time" : "turn-on time", kind, truth, "s",
                       smoothing * (std::ceil(shift / smoothing) + 1.0),
                       fmt::format("4 sigma of a {} s window mean moves the crossing by tau*sigma/band, in whole windows",
                                   smoothing)});
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"{}\"\nname = \"{}\"\nformat = \"f64\"\n"
                                "sample_rate_hz = {}\nzero_output = {}\nrest_band_deg_h = {}\nsmoothing_s = {}\n{}\n",
                                kind, name, exact(fs), exact(settled), exact(band), exact(smoothing), steps);
  lab.tests.push_back({{"name", name}, {"kind", kind}, {"runs", runs}, {"seconds", seconds},
                       {"rest_band_deg_h", band}, {"smoothing_s", smoothing}});
}

}  // namespace

void generate_turn_on_time(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  generate_power_on_time(test, name, lab, false);
}

void generate_warm_up_time(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  generate_power_on_time(test, name, lab, true);
}

void generate_polarity(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const double rate = seconds_key(test, "rate_deg_s", 10.0);
  const double seconds = seconds_key(test, "seconds", 10.0);
  if (lab.dry_run) return;
  const GyroParameters& gyro = lab.gyro;
  const double fs = gyro.sample_rate_hz;
  const Matrix3 ia_up = mounting({0, 0, 1}, {1, 0, 0});
  GyroModel model(gyro, lab.random(name), 3600.0);
  for (const double sign : {1.0, -1.0}) {
    const Rig rig = lab.rate_table.rig(lab.site, ia_up, sign * rate * constants::kDegree, 0.0, model.time_s(),
                                       constant_temperature(gyro.reference_temperature_c));
    model.record(rig, static_cast<std::size_t>(std::llround(fs)));
    const double start = model.time_s();
    const auto pulses = model.record(rig, lab.samples(seconds, fs));
    lab.write(fmt::format("{}/{}.csv", name, sign > 0 ? "plus" : "minus"),
              time_series_csv(pulses, fs, start, fmt::format("table rate {} deg/s about IA", sign * rate)));
  }
  // The polarity is exact: a sign; nothing but a rate response below the noise could flip it.
  lab.truth.push_back({name, "polarity (sign)", "sign", gyro.scale_factor > 0 ? 1.0 : -1.0, "1", rounding_tolerance(1.0),
                       "exact (a sign)"});
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"polarity\"\nname = \"{}\"\npositive_file = \"{}/plus.csv\"\n"
                                "negative_file = \"{}/minus.csv\"\ncolumn = \"output\"\nexpected = \"positive\"\n\n",
                                name, name, name);
  lab.tests.push_back({{"name", name}, {"kind", "polarity"}, {"rate_deg_s", rate}, {"seconds", seconds}});
}

}  // namespace inertest::sim
