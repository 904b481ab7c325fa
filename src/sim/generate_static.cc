// Simulated static records: the bias test (GJB 2426A-2004 5.12.1-5.12.2, kind "bias") and the long
// static record for Allan variance analysis (IEEE Std 952-1997 Annex C, kind "allan"). The gyro
// stands on the position table with IA east, OA north, SA up, so the Earth rate has no IA component
// (only what the IA misalignment leaks, which the bias keeps, as the standard's bias does).
//   bias:  seconds = 7200, temperature_c, format = "f64" | "csv", smoothing_s (default those of
//          1, 10, 100 s that fit twice in the record)
//   allan: hours = 30, sample_rate_hz (default: the gyro's), temperature_c, format = "f64" | "csv",
//          fit_from_tau_s = 8 (the shortest τ of the noise-term fit)
// Writes <name>.f64 (raw little-endian f64, the output in the instrument's unit at the sample rate)
// or <name>.csv (time,output).
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/units.h"
#include "sim/generators.h"

namespace inertest::sim {
namespace {

constexpr double kDegHourPerDegSecond = 3600.0;

struct StaticRun {
  std::string file;
  double true_bias_deg_h = 0.0;
};

std::string read_format(campaign::PlanTable& test) {
  const std::string format = test.string_or("format", "f64");
  if (format != "f64" && format != "csv") test.fail_at("format", "must be \"f64\" or \"csv\"");
  return format;
}

StaticRun record_static(const std::string& name, Lab& lab, const GyroParameters& gyro, double seconds,
                        double temperature, const std::string& format) {
  const Matrix3 ia_east = mounting({1, 0, 0}, {0, 1, 0});
  const Rig rig = static_rig(lab.site, ia_east, constant_temperature(temperature));
  GyroModel model(gyro, lab.random(name), 3600.0);
  const double start = model.time_s();
  const double fs = gyro.sample_rate_hz;
  const std::size_t count = lab.samples(seconds, fs);
  StaticRun run;
  run.true_bias_deg_h = model.static_output_deg_s(rig(start), 1e9) * kDegHourPerDegSecond;
  // Long records are made in blocks so that progress can be shown.
  std::vector<std::int64_t> pulses;
  pulses.reserve(count);
  const std::size_t block = static_cast<std::size_t>(std::llround(600.0 * fs));
  while (pulses.size() < count) {
    const auto part = model.record(rig, std::min(block, count - pulses.size()), 1);
    pulses.insert(pulses.end(), part.begin(), part.end());
    if (lab.progress && count > 10 * block) {
      lab.progress("simulate " + name, static_cast<double>(pulses.size()) / static_cast<double>(count));
    }
  }
  if (format == "f64") {
    run.file = name + ".f64";
    lab.write(run.file, f64_record(pulses, fs));
  } else {
    run.file = name + ".csv";
    lab.write(run.file, time_series_csv(pulses, fs, start,
                                        fmt::format("static, IA east, SA up, {} degC, {} Hz", temperature, fs)));
  }
  return run;
}

std::string format_key(const std::string& format) {
  return format == "f64" ? "format = \"f64\"\n" : (format == "csv" ? "column = \"output\"\n" : "");
}

}  // namespace

void generate_static(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const double seconds = test.number_or("seconds", 7200.0);
  const double temperature = test.number_or("temperature_c", lab.gyro.reference_temperature_c);
  const std::string format = read_format(test);
  if (!(seconds > 0.0)) test.fail_at("seconds", "must be positive");
  std::vector<double> smoothing;
  for (const double s : {1.0, 10.0, 100.0}) {
    if (2.0 * s <= seconds) smoothing.push_back(s);  // default: those of 1, 10, 100 s that fit twice
  }
  smoothing = test.optional_numbers("smoothing_s").value_or(smoothing);
  for (const double s : smoothing) {
    if (!(s > 0.0) || !(2.0 * s <= seconds)) test.fail_at("smoothing_s", "each must be positive and fit twice in the record");
  }
  if (lab.dry_run) return;
  const StaticRun run = record_static(name, lab, lab.gyro, seconds, temperature, format);
  // Bias (eq. 19): the model's static output with g along SA (eq. 2: DF + DS·fS + DSS·fS²) at T; the
  // tolerance is 4 sigma of the mean of this record about it (every simulated noise process).
  lab.truth.push_back({name, "bias", "bias", run.true_bias_deg_h, "deg/h",
                       4.0 * noise_of_record_mean_deg_s(lab.gyro, seconds) * kDegHourPerDegSecond,
                       fmt::format("4 sigma of the mean of a {} s record", seconds)});
  // Bias stability (eq. 20) at each smoothing time: the expected standard deviation of the n window
  // means (lab.h, expected_window_sd_deg_s); its estimator's 1-sigma from their autocovariance
  // (window_sd_sigma_deg_s), about s/√(2(n − 1)) for white noise.
  std::string smoothing_list;
  for (std::size_t i = 0; i < smoothing.size(); ++i) {
    const double windows = std::floor(seconds / smoothing[i] + 1e-9);
    const double expected = expected_window_sd_deg_s(lab.gyro, smoothing[i], windows) * kDegHourPerDegSecond;
    lab.truth.push_back({name, fmt::format("bias stability ({} s)", smoothing[i]), fmt::format("/bias_stability/{}", i),
                         expected, "deg/h", 4.0 * window_sd_sigma_deg_s(lab.gyro, smoothing[i], windows) * kDegHourPerDegSecond,
                         fmt::format("expected sd of {} window means; 4 sigma of the sample sd from the window means' "
                                     "autocovariance", windows)});
    if (i > 0) smoothing_list += ", ";
    smoothing_list += exact(smoothing[i]);
  }
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"bias\"\nname = \"{}\"\nfile = \"{}\"\n{}smoothing_s = [{}]\n\n",
                                name, run.file, format_key(format), smoothing_list);
  lab.tests.push_back({{"name", name}, {"kind", "bias"}, {"file", run.file}, {"seconds", seconds},
                       {"temperature_c", temperature}});
}

void generate_allan(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const double hours = test.number_or("hours", 30.0);
  GyroParameters gyro = lab.gyro;
  gyro.sample_rate_hz = test.number_or("sample_rate_hz", gyro.sample_rate_hz);
  const double temperature = test.number_or("temperature_c", gyro.reference_temperature_c);
  const std::string format = read_format(test);
  const double fit_from = test.number_or("fit_from_tau_s", 8.0);
  if (!(hours > 0.0)) test.fail_at("hours", "must be positive");
  if (!(gyro.sample_rate_hz > 0.0)) test.fail_at("sample_rate_hz", "must be positive");
  const double seconds = hours * 3600.0;
  if (!(fit_from * gyro.sample_rate_hz >= 1.0) || !(fit_from * 8.0 <= seconds)) {
    test.fail_at("fit_from_tau_s", "must be at least one sample and leave three octaves in the record");
  }
  if (lab.dry_run) return;
  const StaticRun run = record_static(name, lab, gyro, seconds, temperature, format);
  // IEEE 952 Annex C coefficients as simulated; the tolerance is 4 times the 1-sigma uncertainty
  // the fit reports, which comes from the edf of each Allan variance (NIST SP 1065 Table 5) through
  // the weighted least squares of GJB 2426A eq. (30).
  const std::string basis = "4 sigma: the fit's edf-based uncertainty (GJB 2426A eq. 30)";
  TruthEntry n{name, "angle random walk N", "/noise/angle_random_walk", gyro.angle_random_walk_deg_rt_h,
               "deg/sqrt(h)", 0.0, basis};
  TruthEntry b{name, "bias instability B", "/noise/bias_instability", gyro.bias_instability_deg_h, "deg/h", 0.0, basis};
  TruthEntry k{name, "rate random walk K", "/noise/rate_random_walk", gyro.rate_random_walk_deg_h_rt_h,
               "deg/h/sqrt(h)", 0.0, basis};
  for (TruthEntry* entry : {&n, &b, &k}) {
    entry->tolerance_sigmas = 4.0;
    lab.truth.push_back(*entry);
  }
  // The fit's τ: octaves from fit_from_tau_s up to T/3. Below a few seconds the pulse counter's
  // quantisation is not the white angle noise of IEEE 952 C.2 (the remainder wanders while the
  // angle gains less than a pulse per sample, so its Allan deviation falls below √3·Q/τ), and those
  // τ, which carry the largest edf and so the largest weights, would pull the fit of eq. (30) off
  // N and B (measured: N 45 % high, B held at 0, with τ from 0.1 s on a 10 Hz record).
  std::string taus;
  for (double tau = fit_from; tau <= seconds / 3.0; tau *= 2.0) {
    if (!taus.empty()) taus += ',';
    taus += exact(tau);
  }
  std::string step = fmt::format("[[procedure]]\nkind = \"allan\"\nname = \"{}\"\nfile = \"{}\"\nsample_rate_hz = {}\n"
                                 "taus = \"{}\"\n",
                                 name, run.file, exact(gyro.sample_rate_hz), taus);
  step += format == "f64" ? "format = \"f64\"\n" : "column = \"output\"\n";
  step += fmt::format("scale_factor = {}\n\n", exact(gyro.scale_factor));
  lab.plan_steps += step;
  lab.tests.push_back({{"name", name}, {"kind", "allan"}, {"file", run.file}, {"hours", hours},
                       {"sample_rate_hz", gyro.sample_rate_hz}, {"temperature_c", temperature}});
}

}  // namespace inertest::sim
