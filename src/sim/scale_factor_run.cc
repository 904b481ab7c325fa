#include "sim/scale_factor_run.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/units.h"

namespace inertest::sim {
namespace {

struct Line {
  double slope = 0.0;
  double intercept = 0.0;
  double sxx = 0.0;  // Σ(x − x̄)²
};

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

std::vector<double> scale_factor_rates(const std::vector<double>& magnitudes) {
  std::vector<double> rates = {0.0};
  for (const double r : magnitudes) rates.push_back(r);
  for (const double r : magnitudes) rates.push_back(-r);
  rates.push_back(0.0);
  return rates;
}

ScaleFactorTruth scale_factor_truth(const std::vector<double>& rates, const std::vector<double>& outputs) {
  double rest = 0.0;
  int statics = 0;
  for (std::size_t j = 0; j < rates.size(); ++j) {
    if (rates[j] == 0.0) {
      rest += outputs[j];
      ++statics;
    }
  }
  rest /= statics;
  std::vector<double> x, y, xp, yp, xn, yn;
  for (std::size_t j = 0; j < rates.size(); ++j) {
    if (rates[j] == 0.0) continue;
    x.push_back(rates[j]);
    y.push_back(outputs[j] - rest);
    (rates[j] > 0 ? xp : xn).push_back(rates[j]);
    (rates[j] > 0 ? yp : yn).push_back(outputs[j] - rest);
  }
  ScaleFactorTruth t;
  const Line all = line(x, y);
  for (const double f : y) t.largest_output = std::max(t.largest_output, std::abs(f));
  for (std::size_t j = 0; j < x.size(); ++j) {
    t.nonlinearity = std::max(t.nonlinearity, std::abs(all.slope * x[j] + all.intercept - y[j]) / t.largest_output);
  }
  const Line positive = line(xp, yp);
  const Line negative = line(xn, yn);
  const double mean_k = 0.5 * (positive.slope + negative.slope);
  t.scale_factor = all.slope;
  t.asymmetry = std::abs(positive.slope - negative.slope) / std::abs(mean_k);
  return t;
}

ScaleFactorRun record_scale_factor_run(Lab& lab, GyroModel& model, const std::vector<double>& magnitudes,
                                       double seconds, double static_seconds, const TemperatureProfile& temperature,
                                       const std::string& title, const std::string& raw_prefix) {
  const GyroParameters& gyro = model.parameters();
  const Matrix3 ia_up = mounting({0, 0, 1}, {1, 0, 0});
  const double fs = gyro.sample_rate_hz;
  ScaleFactorRun run;
  run.rates = scale_factor_rates(magnitudes);
  run.points_csv = "# " + title + "\nrate,output\n";
  std::vector<double> clean;
  std::vector<double> ideal;
  std::vector<std::array<double, 2>> intervals;
  const double t0 = model.time_s();
  for (std::size_t j = 0; j < run.rates.size(); ++j) {
    const double rate = run.rates[j];
    const double duration = rate == 0.0 ? static_seconds : seconds;
    const Rig rig = lab.rate_table.rig(lab.site, ia_up, rate * constants::kDegree, 0.0, model.time_s(), temperature);
    model.record(rig, static_cast<std::size_t>(std::llround(fs)));  // settling, not recorded
    const double start = model.time_s();
    const auto pulses = model.record(rig, static_cast<std::size_t>(std::llround(duration * fs)));
    if (!raw_prefix.empty()) {
      lab.write(fmt::format("{}{:02d}.csv", raw_prefix, j),
                time_series_csv(pulses, fs, start, fmt::format("table rate {} deg/s", rate)));
    }
    run.outputs.push_back(mean_output(pulses, fs));
    intervals.push_back({start, model.time_s()});
    fmt::format_to(std::back_inserter(run.points_csv), "{},{}\n", exact(rate), exact(run.outputs.back()));
    // Noise-free: the instrument at the rate the table gives (Earth rate and table errors included),
    // at the gyro's temperature at the middle of the point.
    const Stimulus s = rig(start + 0.5 * duration);
    clean.push_back(gyro.scale_factor * model.static_output_deg_s(s, 1e9));
    Stimulus exact_input;
    exact_input.rate = {rate * constants::kDegree + lab.site.earth_rate_enu()[2], 0.0, 0.0};
    exact_input.specific_force = {lab.site.specific_force_enu_g()[2], 0.0, 0.0};
    exact_input.temperature_c = s.temperature_c;
    ideal.push_back(gyro.scale_factor * model.static_output_deg_s(exact_input, 1e9));
  }
  run.truth = scale_factor_truth(run.rates, ideal);
  run.expected = scale_factor_truth(run.rates, clean);
  run.sigma_point = std::abs(gyro.scale_factor) * noise_of_mean_deg_s(gyro, seconds);
  // The estimators as linear combinations of the point means: the slope of the rate points (the
  // rest output shifts every y alike and drops out), c_j = (x_j − x̄)/Sxx, over all of them, the
  // positive and the negative ones; Ka = (K+ − K−)/K̄.
  const auto cov = interval_mean_covariance(gyro, intervals, t0);
  auto slope_weights = [&](int sign) {
    std::vector<double> c(run.rates.size(), 0.0);
    double mean = 0.0;
    int count = 0;
    for (const double r : run.rates) {
      if (r != 0.0 && (sign == 0 || (r > 0) == (sign > 0))) {
        mean += r;
        ++count;
      }
    }
    mean /= count;
    double sxx = 0.0;
    for (const double r : run.rates) {
      if (r != 0.0 && (sign == 0 || (r > 0) == (sign > 0))) sxx += (r - mean) * (r - mean);
    }
    for (std::size_t j = 0; j < run.rates.size(); ++j) {
      const double r = run.rates[j];
      if (r != 0.0 && (sign == 0 || (r > 0) == (sign > 0))) c[j] = (r - mean) / sxx;
    }
    return c;
  };
  auto sigma_of = [&](const std::vector<double>& c) {
    double v = 0.0;
    for (std::size_t i = 0; i < c.size(); ++i) {
      for (std::size_t j = 0; j < c.size(); ++j) v += c[i] * cov[i][j] * c[j];
    }
    return std::abs(gyro.scale_factor) * std::sqrt(v);
  };
  run.sigma_scale_factor = sigma_of(slope_weights(0));
  const auto plus = slope_weights(1);
  const auto minus = slope_weights(-1);
  std::vector<double> difference(plus.size());
  for (std::size_t j = 0; j < plus.size(); ++j) difference[j] = plus[j] - minus[j];
  run.sigma_asymmetry = sigma_of(difference) / std::abs(run.truth.scale_factor);
  return run;
}

}  // namespace inertest::sim
