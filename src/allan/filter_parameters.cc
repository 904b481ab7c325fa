#include "inertest/allan/filter_parameters.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/json_text.h"
#include "inertest/core/units.h"

namespace inertest {
namespace {

// The largest Allan deviation of a first-order Gauss-Markov process of unit sigma, at tau = 1.8926 T
// (El-Sheimy, Hou and Niu 2008, eq. 23: sigma_A^2 = sigma^2 (2x - 3 + 4 e^-x - e^-2x) / x^2;
// maximised numerically, g(1.8926179) = 0.3811387).
constexpr double kGaussMarkovPeakTau = 1.8926179;
constexpr double kGaussMarkovPeakDeviation = 0.61736428;

// SI units of the white-noise density, the random-walk density and the bias, per sensor.
struct SiUnits {
  const char* white;
  const char* walk;
  const char* bias;
};
SiUnits si_units(SensorKind kind) {
  if (kind == SensorKind::kGyro) return {"rad/s/sqrt(Hz)", "rad/s^2/sqrt(Hz)", "rad/s"};
  return {"m/s^2/sqrt(Hz)", "m/s^3/sqrt(Hz)", "m/s^2"};
}

// The term p of the fit in SI: the estimate, or the upper bound when the fit held it at zero.
NoiseDensity density(const NoiseTerms& noise, const Figure& figure, int p, const char* si) {
  const auto k = static_cast<std::size_t>(p + 2);
  const std::optional<Figure>& bound = noise.upper_bounds[k];
  if (noise.identified[k]) {
    return {convert(figure.value, figure.unit, si), convert(figure.uncertainty.value_or(0.0), figure.unit, si), true,
            noise.significant[k], bound ? convert(bound->value, bound->unit, si) : 0.0};
  }
  return {convert(bound->value, bound->unit, si), 0.0, false, false, convert(bound->value, bound->unit, si)};
}

// The tau where the fitted sigma^2(tau) = sum A_p tau^p is least, within the taus of the curve
// (golden-section search on log tau; the sum is convex in log tau for A_p >= 0).
double tau_of_least_variance(const NoiseTerms& noise, double tau_first, double tau_last) {
  const auto variance = [&](double log_tau) {
    double sum = 0.0;
    for (int p = -2; p <= 2; ++p) sum += noise.coefficients[static_cast<std::size_t>(p + 2)] * std::exp(p * log_tau);
    return sum;
  };
  double a = std::log(tau_first);
  double b = std::log(tau_last);
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int i = 0; i < 200 && b - a > 1e-9; ++i) {
    const double c = b - ratio * (b - a);
    const double d = a + ratio * (b - a);
    if (variance(c) < variance(d)) {
      b = d;
    } else {
      a = c;
    }
  }
  return std::exp((a + b) / 2.0);
}

// A least within this fraction of the longest (or shortest) tau is at an end of the curve (the
// golden-section search stops within 1e-9 of it in log tau).
constexpr double kLeastAtTheEnd = 0.999;

std::string number(double value) { return fmt::format("{:.6g}", value); }

// "[x, y, z]" of one field over the sensors.
template <typename Field>
std::string vector_of(const std::vector<const SensorNoiseParameters*>& sensors, Field field, double scale = 1.0) {
  std::string text;
  for (const SensorNoiseParameters* s : sensors) text += (text.empty() ? "" : ", ") + number(field(*s) * scale);
  return "[" + text + "]";
}

std::vector<const SensorNoiseParameters*> of_kind(const std::vector<SensorNoiseParameters>& sensors, SensorKind kind) {
  std::vector<const SensorNoiseParameters*> chosen;
  for (const auto& s : sensors) {
    if (s.kind == kind) chosen.push_back(&s);
  }
  return chosen;
}

std::string channel_list(const std::vector<const SensorNoiseParameters*>& sensors) {
  std::string text;
  for (const SensorNoiseParameters* s : sensors) text += (text.empty() ? "" : ", ") + s->channel;
  return text;
}

// Which terms are upper bounds, and which estimates are within 2 sigma of zero, for the files' comments.
std::string bounds_note(const std::vector<const SensorNoiseParameters*>& sensors) {
  std::string text;
  for (const SensorNoiseParameters* s : sensors) {
    if (!s->white_noise_density.identified) text += " " + s->channel + ": white noise;";
    if (!s->random_walk_density.identified) text += " " + s->channel + ": random walk;";
    if (!s->bias_instability.identified) text += " " + s->channel + ": bias instability;";
  }
  std::string unknown_times;
  for (const SensorNoiseParameters* s : sensors) {
    if (!s->gauss_markov_identified) unknown_times += " " + s->channel + ";";
  }
  std::string insignificant;  // in SI, whatever unit the file writes the values in
  for (const SensorNoiseParameters* s : sensors) {
    const SiUnits units = si_units(s->kind);
    for (const auto& [name, d, unit] : {std::tuple{"white noise", &s->white_noise_density, units.white},
                                        std::tuple{"random walk", &s->random_walk_density, units.walk},
                                        std::tuple{"bias instability", &s->bias_instability, units.bias}}) {
      if (d->identified && !d->significant) {
        insignificant += fmt::format(" {}: {} (< {} {});", s->channel, name, number(d->upper_bound), unit);
      }
    }
  }
  if (!text.empty()) text = "upper bounds (not identified by the fit):" + text;
  if (!unknown_times.empty()) {
    text += (text.empty() ? "" : "; ") +
            std::string("Gauss-Markov correlation time not identified (the fitted curve is least at an end of its "
                        "taus: the value is that tau/1.8926, a figure of the record, and so are phi and the driving "
                        "sigma):") +
            unknown_times;
  }
  if (!insignificant.empty()) {
    text += (text.empty() ? "" : " ") +
            std::string("estimates within 2 sigma of zero, their 2-sigma upper bounds in brackets:") + insignificant;
  }
  return text;
}

constexpr const char* kHow =
    "from the fit of sigma^2(tau) = sum A_p tau^p (GJB 2426A-2004 eq. 30; IEEE Std 952-1997 C.1): white-noise "
    "density = N (sigma(tau) = N/sqrt(tau); = sqrt(S1/2) of the one-sided rate PSD S1), random-walk density = K "
    "(sigma(tau) = K sqrt(tau/3)), bias instability B (flat floor 0.664 B) with its first-order Gauss-Markov "
    "equivalent: T = tau_min/1.8926, sigma = 0.664 B/0.6174 (El-Sheimy et al. 2008, eq. 23); no inflation applied";

// The discrete-time values of the channels (one comment line), for the formats that take the
// continuous ones: white sigma N/sqrt(dt), random-walk step K sqrt(dt), Gauss-Markov phi and
// driving sigma, at the record's interval dt.
std::string discrete_note(const char* comment, const std::vector<const SensorNoiseParameters*>& chosen,
                          const SiUnits& units) {
  if (chosen.empty()) return "";
  return fmt::format(
      "{} discrete at dt = {} s ({}): white sigma {} {}, random-walk step sigma {} {}, Gauss-Markov phi {}, "
      "driving sigma {} {}\n",
      comment, number(1.0 / chosen.front()->sample_rate_hz), channel_list(chosen),
      vector_of(chosen, [](const auto& s) { return s.discrete_white_sigma; }), units.bias,
      vector_of(chosen, [](const auto& s) { return s.discrete_random_walk_sigma; }), units.bias,
      vector_of(chosen, [](const auto& s) { return s.discrete_gauss_markov_phi; }),
      vector_of(chosen, [](const auto& s) { return s.discrete_gauss_markov_sigma; }), units.bias);
}

// "gx 9.5e-06, gy ... rad/s^2/sqrt(Hz); ax ... m/s^3/sqrt(Hz)": K of each channel.
std::string random_walk_note(const std::vector<SensorNoiseParameters>& sensors) {
  std::string text;
  for (SensorKind kind : {SensorKind::kGyro, SensorKind::kAccelerometer}) {
    const auto chosen = of_kind(sensors, kind);
    if (chosen.empty()) continue;
    std::string values;
    for (const SensorNoiseParameters* s : chosen) {
      values += fmt::format("{}{} {}", values.empty() ? "" : ", ", s->channel, number(s->random_walk_density.value));
    }
    text += fmt::format("{}{} {}", text.empty() ? "" : "; ", values, si_units(kind).walk);
  }
  return text;
}

// What each target can load (their readers): Kalibr's imu.yaml has the keys of both sensors
// (kalibr ConfigReader: a missing field is an error); MATLAB's gyroparams/accelparams take a scalar
// or a 3-element row vector; gnss-ins-sim's IMU error model takes the x, y, z of both (imu_model.IMU
// needs gyro_* and accel_*). Anything else is an Error before a file is written.
void check_target(const std::vector<SensorNoiseParameters>& sensors, FilterFormat format) {
  const std::size_t gyros = of_kind(sensors, SensorKind::kGyro).size();
  const std::size_t accelerometers = of_kind(sensors, SensorKind::kAccelerometer).size();
  const std::string given = fmt::format("the channels give {} gyro and {} accelerometer axes", gyros, accelerometers);
  const std::string how = " (an acceleration unit makes a channel an accelerometer's: --input-unit ax=m/s^2)";
  if (format == FilterFormat::kKalibr && (gyros == 0 || accelerometers == 0)) {
    throw Error("Kalibr's imu.yaml needs a gyroscope and an accelerometer: " + given + how + "; json takes any");
  }
  if (format == FilterFormat::kMatlab && (gyros == 2 || gyros > 3 || accelerometers == 2 || accelerometers > 3)) {
    throw Error("MATLAB's gyroparams and accelparams take one axis or three: " + given);
  }
  if (format == FilterFormat::kGnssInsSim && (gyros != 3 || accelerometers != 3)) {
    throw Error("gnss-ins-sim's IMU error model takes three gyro and three accelerometer axes: " + given + how);
  }
}

std::string kalibr(const std::vector<SensorNoiseParameters>& sensors, const std::string& command) {
  std::string text = "# Kalibr IMU noise model (imu.yaml), written by inertest: " + command + "\n# " + kHow + "\n";
  text += "# Kalibr takes one value per sensor: the largest of its axes (the conservative choice).\n";
  const double rate = sensors.front().sample_rate_hz;
  const auto block = [&](SensorKind kind, const char* prefix, const SiUnits& units) {
    const auto chosen = of_kind(sensors, kind);
    if (chosen.empty()) return;
    const auto largest = [&](auto field) {
      double value = 0.0;
      for (const SensorNoiseParameters* s : chosen) value = std::max(value, field(*s).value);
      return value;
    };
    text += fmt::format("# {}: channels {}{}\n", prefix, channel_list(chosen),
                        bounds_note(chosen).empty() ? "" : "; " + bounds_note(chosen));
    text += fmt::format("{}_noise_density: {}  # {}, white noise N\n", prefix,
                        number(largest([](const auto& s) { return s.white_noise_density; })), units.white);
    text += fmt::format("{}_random_walk: {}  # {}, bias random walk K\n", prefix,
                        number(largest([](const auto& s) { return s.random_walk_density; })), units.walk);
  };
  block(SensorKind::kAccelerometer, "accelerometer", si_units(SensorKind::kAccelerometer));
  block(SensorKind::kGyro, "gyroscope", si_units(SensorKind::kGyro));
  text += "rostopic: /imu0\n";
  text += fmt::format("update_rate: {}  # Hz, the record's sample rate\n", number(rate));
  return text;
}

std::string matlab(const std::vector<SensorNoiseParameters>& sensors, const std::string& command) {
  std::string text = "% MATLAB Navigation Toolbox IMU parameters, written by inertest: " + command + "\n% " + kHow +
                     "\n% The Gauss-Markov equivalent of B is in the comments (gyroparams takes B itself).\n";
  const auto block = [&](SensorKind kind, const char* variable, const char* function) {
    const auto chosen = of_kind(sensors, kind);
    if (chosen.empty()) return;
    const SiUnits units = si_units(kind);
    text += fmt::format("% {}: channels {} as the axes{}\n", variable, channel_list(chosen),
                        bounds_note(chosen).empty() ? "" : "; " + bounds_note(chosen));
    text += fmt::format("{} = {}( ...\n", variable, function);
    text += fmt::format("    'NoiseDensity', {}, ...  % {}\n",
                        vector_of(chosen, [](const auto& s) { return s.white_noise_density.value; }), units.white);
    text += fmt::format("    'RandomWalk', {}, ...  % {}\n",
                        vector_of(chosen, [](const auto& s) { return s.random_walk_density.value; }), units.walk);
    text += fmt::format("    'BiasInstability', {});  % {}\n",
                        vector_of(chosen, [](const auto& s) { return s.bias_instability.value; }), units.bias);
    text += fmt::format("% Gauss-Markov sigma {} {}, correlation time {} s\n",
                        vector_of(chosen, [](const auto& s) { return s.gauss_markov_sigma; }), units.bias,
                        vector_of(chosen, [](const auto& s) { return s.gauss_markov_correlation_time_s; }));
    text += discrete_note("%", chosen, units);
  };
  block(SensorKind::kGyro, "gyro", "gyroparams");
  block(SensorKind::kAccelerometer, "accel", "accelparams");
  return text + fmt::format("sample_rate_hz = {};  % the record's (imuSensor's SampleRate)\n", number(sensors.front().sample_rate_hz));
}

std::string gnss_ins_sim(const std::vector<SensorNoiseParameters>& sensors, const std::string& command) {
  std::string text = "# gnss-ins-sim IMU error dictionary, written by inertest: " + command + "\n# " + kHow +
                     "\n# *_b_stability is the Gauss-Markov sigma, *_b_corr its correlation time; the constant bias "
                     "is not a noise figure and is left at 0.\n# The model has no rate or acceleration random walk: "
                     "K is left out (" + random_walk_note(sensors) + ").\n" +
                     discrete_note("#", of_kind(sensors, SensorKind::kGyro), si_units(SensorKind::kGyro)) +
                     discrete_note("#", of_kind(sensors, SensorKind::kAccelerometer), si_units(SensorKind::kAccelerometer)) +
                     "import numpy as np\n\nfs = " + number(sensors.front().sample_rate_hz) +
                     "  # Hz, the record's sample rate (the IMU's fs of gnss-ins-sim's Sim)\n\nimu_err = {\n";
  constexpr double kRadPerDeg = constants::kPi / 180.0;
  const auto gyro = of_kind(sensors, SensorKind::kGyro);
  if (!gyro.empty()) {
    text += fmt::format("    # channels {}{}\n", channel_list(gyro), bounds_note(gyro).empty() ? "" : "; " + bounds_note(gyro));
    text += fmt::format("    'gyro_b': np.array({}),  # deg/hr\n", vector_of(gyro, [](const auto&) { return 0.0; }));
    // rad/s/sqrt(Hz) = rad/sqrt(s) -> deg/sqrt(h): * 60 / (pi / 180).
    text += fmt::format("    'gyro_arw': np.array({}),  # deg/rt-hr\n",
                        vector_of(gyro, [](const auto& s) { return s.white_noise_density.value; }, 60.0 / kRadPerDeg));
    text += fmt::format("    'gyro_b_stability': np.array({}),  # deg/hr\n",
                        vector_of(gyro, [](const auto& s) { return s.gauss_markov_sigma; }, 3600.0 / kRadPerDeg));
    text += fmt::format("    'gyro_b_corr': np.array({}),  # s\n",
                        vector_of(gyro, [](const auto& s) { return s.gauss_markov_correlation_time_s; }));
  }
  const auto accel = of_kind(sensors, SensorKind::kAccelerometer);
  if (!accel.empty()) {
    text += fmt::format("    # channels {}{}\n", channel_list(accel), bounds_note(accel).empty() ? "" : "; " + bounds_note(accel));
    text += fmt::format("    'accel_b': np.array({}),  # m/s^2\n", vector_of(accel, [](const auto&) { return 0.0; }));
    // m/s^2/sqrt(Hz) = m/s/sqrt(s) -> m/s/sqrt(h): * 60.
    text += fmt::format("    'accel_vrw': np.array({}),  # m/s/rt-hr\n",
                        vector_of(accel, [](const auto& s) { return s.white_noise_density.value; }, 60.0));
    text += fmt::format("    'accel_b_stability': np.array({}),  # m/s^2\n",
                        vector_of(accel, [](const auto& s) { return s.gauss_markov_sigma; }));
    text += fmt::format("    'accel_b_corr': np.array({}),  # s\n",
                        vector_of(accel, [](const auto& s) { return s.gauss_markov_correlation_time_s; }));
  }
  return text + "}\n";
}

}  // namespace

std::vector<SensorNoiseParameters> filter_noise_parameters(const AllanChannels& channels) {
  std::vector<SensorNoiseParameters> sensors;
  for (const AllanChannel& channel : channels.channels) {
    const AllanResult& result = channel.result;
    SensorNoiseParameters s;
    s.channel = channel.name;
    s.kind = sensor_kind_of(result.input_unit);
    if (s.kind == SensorKind::kOther) {
      throw Error(fmt::format("channel {}: its unit {} is neither an angular rate nor a specific force, so it has no "
                              "filter parameters (give --input-unit {}=deg/s or ...=m/s^2)",
                              channel.name, result.input_unit, channel.name));
    }
    if (!result.noise) {
      // The result is not printed when its export fails: its warnings say why here.
      throw Error(fmt::format("channel {}: its noise terms were not fitted, so it has no filter parameters ({})",
                              channel.name, fmt::join(result.warnings, "; ")));
    }
    const NoiseTerms& noise = *result.noise;
    const SiUnits units = si_units(s.kind);
    s.sample_rate_hz = result.sample_rate_hz;
    s.white_noise_density = density(noise, noise.angle_random_walk, -1, units.white);
    s.random_walk_density = density(noise, noise.rate_random_walk, 1, units.walk);
    s.bias_instability = density(noise, noise.bias_instability, 0, units.bias);
    const double least = tau_of_least_variance(noise, result.tau_s.front(), result.tau_s.back());
    s.gauss_markov_correlation_time_s = least / kGaussMarkovPeakTau;
    s.gauss_markov_identified = least < kLeastAtTheEnd * result.tau_s.back() && least > result.tau_s.front() / kLeastAtTheEnd;
    s.gauss_markov_sigma = kBiasInstabilityFactor * s.bias_instability.value / kGaussMarkovPeakDeviation;
    const double dt = 1.0 / s.sample_rate_hz;
    s.discrete_white_sigma = s.white_noise_density.value / std::sqrt(dt);
    s.discrete_random_walk_sigma = s.random_walk_density.value * std::sqrt(dt);
    s.discrete_gauss_markov_phi = std::exp(-dt / s.gauss_markov_correlation_time_s);
    s.discrete_gauss_markov_sigma =
        s.gauss_markov_sigma * std::sqrt(1.0 - s.discrete_gauss_markov_phi * s.discrete_gauss_markov_phi);
    sensors.push_back(s);
  }
  return sensors;
}

FilterFormat parse_filter_format(std::string_view text) {
  if (text == "kalibr") return FilterFormat::kKalibr;
  if (text == "matlab") return FilterFormat::kMatlab;
  if (text == "gnss-ins-sim") return FilterFormat::kGnssInsSim;
  if (text == "json") return FilterFormat::kJson;
  throw Error("unknown export format '" + std::string(text) + "' (expected kalibr, matlab, gnss-ins-sim or json)");
}

nlohmann::json filter_parameters_json(const std::vector<SensorNoiseParameters>& sensors) {
  nlohmann::json json = nlohmann::json::object();
  for (const SensorNoiseParameters& s : sensors) {
    const SiUnits units = si_units(s.kind);
    const auto figure = [](const NoiseDensity& d, const char* unit) {
      nlohmann::json f = {{"value", d.value}, {"unit", unit}, {"identified", d.identified}};
      f["uncertainty"] = d.identified ? nlohmann::json(d.uncertainty) : nlohmann::json(nullptr);
      if (d.identified && !d.significant) {
        f["significant"] = false;
        f["upper_bound"] = d.upper_bound;
      }
      return f;
    };
    json[s.channel] = {
        {"sensor", s.kind == SensorKind::kGyro ? "gyro" : "accelerometer"},
        {"sample_rate_hz", s.sample_rate_hz},
        {"white_noise_density", figure(s.white_noise_density, units.white)},
        {"random_walk_density", figure(s.random_walk_density, units.walk)},
        {"bias_instability", figure(s.bias_instability, units.bias)},
        {"gauss_markov", {{"sigma", {{"value", s.gauss_markov_sigma}, {"unit", units.bias}}},
                          {"correlation_time",
                           {{"value", s.gauss_markov_correlation_time_s}, {"unit", "s"},
                            {"identified", s.gauss_markov_identified}}}}},
        {"discrete",
         {{"sample_interval_s", 1.0 / s.sample_rate_hz},
          {"white_sigma", {{"value", s.discrete_white_sigma}, {"unit", units.bias}}},
          {"random_walk_step_sigma", {{"value", s.discrete_random_walk_sigma}, {"unit", units.bias}}},
          {"gauss_markov_phi", s.discrete_gauss_markov_phi},
          {"gauss_markov_driving_sigma", {{"value", s.discrete_gauss_markov_sigma}, {"unit", units.bias}}}}}};
  }
  return {{"how", kHow}, {"sensors", json}};
}

std::string format_filter_parameters(const std::vector<SensorNoiseParameters>& sensors, FilterFormat format,
                                     const std::string& command) {
  if (sensors.empty()) throw Error("no sensor to export");
  check_target(sensors, format);
  switch (format) {
    case FilterFormat::kKalibr: return kalibr(sensors, command);
    case FilterFormat::kMatlab: return matlab(sensors, command);
    case FilterFormat::kGnssInsSim: return gnss_ins_sim(sensors, command);
    case FilterFormat::kJson: break;
  }
  nlohmann::json json = filter_parameters_json(sensors);
  json["command"] = command;
  return json_text(json, 2) + "\n";
}

}  // namespace inertest
