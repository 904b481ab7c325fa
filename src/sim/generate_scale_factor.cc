// Simulated scale-factor test, GJB 2426A-2004 5.8.1.3: static run, the rates each way, static run;
// IA up along the rate-table axis. Test keys:
//   rates_deg_s = [...]       # positive rates; each is run +Ω then the set again −Ω (default 11+)
//   seconds_per_rate = 60     # recorded after 1 s of settling at each rate
//   static_seconds = 60       # each static run
//   temperature_c             # default: the gyro's reference temperature
// Writes <name>/rate_NN.csv (raw) and <name>/points.csv (rate,output means); plan kind scale_factor.
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/units.h"
#include "sim/generators.h"

namespace inertest::sim {
namespace {

struct Line {
  double slope = 0.0;
  double intercept = 0.0;
  double sxx = 0.0;  // Σ(x − x̄)²
};

// Least-squares line, written out here so the truth does not depend on the library's fit.
Line line(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0.0;
  double my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= static_cast<double>(x.size());
  my /= static_cast<double>(y.size());
  Line l;
  double sxy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    l.sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  l.slope = sxy / l.sxx;
  l.intercept = my - l.slope * mx;
  return l;
}

}  // namespace

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
  std::vector<double> rates = {0.0};
  for (const double r : magnitudes) rates.push_back(r);
  for (const double r : magnitudes) rates.push_back(-r);
  rates.push_back(0.0);

  const Matrix3 ia_up = mounting({0, 0, 1}, {1, 0, 0});
  GyroModel model(gyro, lab.random(name), 3600.0);
  const double fs = gyro.sample_rate_hz;
  std::string points = fmt::format("# simulated scale factor test '{}', mean output per rate (GJB 2426A 5.8.1.3)\n"
                                    "rate,output\n",
                                    name);
  for (std::size_t j = 0; j < rates.size(); ++j) {
    const double rate = rates[j];
    const double duration = rate == 0.0 ? static_seconds : seconds;
    const Rig rig = lab.rate_table.rig(lab.site, ia_up, rate * constants::kDegree, 0.0, model.time_s(),
                                       constant_temperature(temperature));
    model.record(rig, static_cast<std::size_t>(std::llround(fs)));  // settling, not recorded
    const double start = model.time_s();
    const auto pulses = model.record(rig, static_cast<std::size_t>(std::llround(duration * fs)));
    lab.write(fmt::format("{}/rate_{:02d}.csv", name, j),
              time_series_csv(pulses, fs, start, fmt::format("table rate {} deg/s, {} degC", rate, temperature)));
    long double total = 0.0L;
    for (const auto p : pulses) total += static_cast<long double>(p);
    points += fmt::format("{},{}\n", exact(rate), exact(static_cast<double>(total * fs / pulses.size())));
  }
  lab.write(name + "/points.csv", points);

  // Truth: the GJB 2426A definitions (eqs. 2-11) applied to the noise-free instrument at these rates.
  auto output = [&](double rate_deg_s) {
    Stimulus s;
    s.rate = {rate_deg_s * constants::kDegree + lab.site.earth_rate_enu()[2], 0.0, 0.0};
    s.specific_force = {lab.site.specific_force_enu_g()[2], 0.0, 0.0};
    s.temperature_c = temperature;
    return gyro.scale_factor * model.static_output_deg_s(s, 1e9);
  };
  const double rest = output(0.0);
  std::vector<double> x;
  std::vector<double> y;
  std::vector<double> xp, yp, xn, yn;
  for (const double r : rates) {
    if (r == 0.0) continue;
    x.push_back(r);
    y.push_back(output(r) - rest);
    (r > 0 ? xp : xn).push_back(r);
    (r > 0 ? yp : yn).push_back(output(r) - rest);
  }
  const Line all = line(x, y);
  double largest = 0.0;
  for (const double f : y) largest = std::max(largest, std::abs(f));
  double nonlinearity = 0.0;
  for (std::size_t j = 0; j < x.size(); ++j) {
    nonlinearity = std::max(nonlinearity, std::abs(all.slope * x[j] + all.intercept - y[j]) / largest);
  }
  const Line positive = line(xp, yp);
  const Line negative = line(xn, yn);
  const double mean_k = 0.5 * (positive.slope + negative.slope);
  const double asymmetry = std::abs(positive.slope - negative.slope) / std::abs(mean_k);

  // Tolerances: 4 sigma of each estimator from the noise of one rate's mean (σ_F), plus the rate
  // table's rate error for K (a systematic the fit cannot see).
  const double sigma_f = std::abs(gyro.scale_factor) * noise_of_mean_deg_s(gyro, seconds);
  const double sigma_k = sigma_f / std::sqrt(all.sxx);
  const double sigma_asymmetry = sigma_f * std::sqrt(1.0 / positive.sxx + 1.0 / negative.sxx) / std::abs(mean_k);
  const std::string k_unit = gyro.output_unit + "/(deg/s)";
  const std::string basis = fmt::format("4 sigma from the noise of a {} s mean", seconds);
  lab.truth.push_back({name, "scale factor", "scale_factor", all.slope, k_unit,
                       4.0 * sigma_k + std::abs(lab.rate_table.rate_error * all.slope),
                       basis + " + rate-table rate error"});
  lab.truth.push_back({name, "scale factor nonlinearity", "nonlinearity", nonlinearity * 1e6, "ppm",
                       4.0 * sigma_f / largest * 1e6, basis});
  lab.truth.push_back({name, "scale factor asymmetry", "asymmetry", asymmetry * 1e6, "ppm",
                       4.0 * sigma_asymmetry * 1e6, basis});

  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"scale_factor\"\nname = \"{}\"\nfile = \"{}/points.csv\"\n\n",
                                name, name);
  lab.tests.push_back({{"name", name}, {"kind", "scale_factor"}, {"temperature_c", temperature},
                       {"rates_deg_s", rates}, {"seconds_per_rate", seconds}});
}

}  // namespace inertest::sim
