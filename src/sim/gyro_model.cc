#include "inertest/sim/gyro_model.h"

#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/units.h"

namespace inertest::sim {
namespace {

constexpr double kDegPerHourInDegPerSecond = 1.0 / 3600.0;
constexpr double kRadPerDeg = constants::kDegree;
constexpr double kPpm = 1e-6;

}  // namespace

void GyroParameters::validate() const {
  auto positive = [](double value, const char* name) {
    if (!(value > 0.0)) throw Error(fmt::format("gyro: {} must be positive (got {})", name, value));
  };
  auto not_negative = [](double value, const char* name) {
    if (!(value >= 0.0)) throw Error(fmt::format("gyro: {} must not be negative (got {})", name, value));
  };
  positive(sample_rate_hz, "sample_rate_hz");
  if (scale_factor == 0.0 || !std::isfinite(scale_factor)) throw Error("gyro: scale_factor must be nonzero");
  positive(maximum_rate_deg_s, "maximum_rate_deg_s");
  not_negative(turn_on_time_constant_s, "turn_on_time_constant_s");
  if (turn_on_bias_deg_h != 0.0 && turn_on_time_constant_s == 0.0) {
    throw Error("gyro: turn_on_bias_deg_h needs a positive turn_on_time_constant_s");
  }
  not_negative(quantization_arcsec, "quantization_arcsec");
  not_negative(angle_random_walk_deg_rt_h, "angle_random_walk_deg_rt_h");
  not_negative(bias_instability_deg_h, "bias_instability_deg_h");
  not_negative(rate_random_walk_deg_h_rt_h, "rate_random_walk_deg_h_rt_h");
  not_negative(bandwidth_hz, "bandwidth_hz");
  not_negative(delay_ms, "delay_ms");
  if (!(flicker_correlation_s[0] > 0.0 && flicker_correlation_s[1] > flicker_correlation_s[0])) {
    throw Error("gyro: flicker_correlation_s must be two increasing positive times");
  }
  Unit::parse(output_unit);
}

NoiseParameters GyroParameters::noise() const {
  NoiseParameters n;
  n.quantization = quantization_arcsec * constants::kArcsecond;
  n.angle_random_walk = angle_random_walk_deg_rt_h * kRadPerDeg / 60.0;  // deg/√h → rad/√s
  n.bias_instability = bias_instability_deg_h * kRadPerDeg / 3600.0;
  n.rate_random_walk = rate_random_walk_deg_h_rt_h * kRadPerDeg / 3600.0 / 60.0;  // deg/h/√h → rad/s/√s
  n.rate_ramp = rate_ramp_deg_h_h * kRadPerDeg / 3600.0 / 3600.0;
  n.flicker_shortest_s = flicker_correlation_s[0];
  n.flicker_longest_s = flicker_correlation_s[1];
  return n;
}

nlohmann::json GyroParameters::to_json() const {
  return {
      {"id", id},
      {"output_unit", output_unit},
      {"sample_rate_hz", sample_rate_hz},
      {"scale_factor", scale_factor},
      {"maximum_rate_deg_s", maximum_rate_deg_s},
      {"nonlinearity_ppm", nonlinearity_ppm},
      {"asymmetry_ppm", asymmetry_ppm},
      {"scale_factor_temperature_ppm_per_c", scale_factor_temperature_ppm_per_c},
      {"bias_deg_h", bias_deg_h},
      {"bias_temperature_deg_h_per_c", bias_temperature_deg_h_per_c},
      {"reference_temperature_c", reference_temperature_c},
      {"turn_on_bias_deg_h", turn_on_bias_deg_h},
      {"turn_on_time_constant_s", turn_on_time_constant_s},
      {"quantization_arcsec", quantization_arcsec},
      {"angle_random_walk_deg_rt_h", angle_random_walk_deg_rt_h},
      {"bias_instability_deg_h", bias_instability_deg_h},
      {"rate_random_walk_deg_h_rt_h", rate_random_walk_deg_h_rt_h},
      {"rate_ramp_deg_h_h", rate_ramp_deg_h_h},
      {"flicker_correlation_s", flicker_correlation_s},
      {"bandwidth_hz", bandwidth_hz},
      {"delay_ms", delay_ms},
      {"input_axis_misalignment_arcsec", input_axis_misalignment_arcsec},
      {"drift",
       {{"DI", drift.DI}, {"DO", drift.DO}, {"DS", drift.DS}, {"DII", drift.DII}, {"DOO", drift.DOO},
        {"DSS", drift.DSS}, {"DIO", drift.DIO}, {"DIS", drift.DIS}, {"DOS", drift.DOS}}},
  };
}

GyroModel::GyroModel(const GyroParameters& parameters, Random random, double power_on_age_s)
    : parameters_(parameters),
      noise_((parameters.validate(), parameters.noise()), 1.0 / parameters.sample_rate_hz, random),
      time_s_(power_on_age_s) {
  noise_.set_time(power_on_age_s);
  // IA unit vector tilted toward OA and SA by the two misalignment angles (small rotations about
  // SA and OA respectively): u = (cos a·cos b, sin a·cos b, sin b).
  const double a = parameters_.input_axis_misalignment_arcsec[0] * constants::kArcsecond;
  const double b = parameters_.input_axis_misalignment_arcsec[1] * constants::kArcsecond;
  input_axis_ = {std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b)};
}

double GyroModel::static_output_deg_s(const Stimulus& stimulus, double t) const {
  const GyroParameters& p = parameters_;
  const double omega = dot(input_axis_, stimulus.rate) / kRadPerDeg;  // ω_IA, deg/s
  double polynomial = omega;
  const double x = omega / p.maximum_rate_deg_s;
  double power = x;
  for (const double c : p.nonlinearity_ppm) {
    power *= x;
    polynomial += p.maximum_rate_deg_s * c * kPpm * power;
  }
  const double asymmetry = omega >= 0.0 ? 1.0 + 0.5 * p.asymmetry_ppm * kPpm : 1.0 - 0.5 * p.asymmetry_ppm * kPpm;
  const double dT = stimulus.temperature_c - p.reference_temperature_c;
  const double scale = 1.0 + p.scale_factor_temperature_ppm_per_c * kPpm * dT;
  const auto& f = stimulus.specific_force;
  const auto& d = p.drift;
  // Reference section 1, eq. (2), in deg/h with f in g.
  double drift = p.bias_deg_h + p.bias_temperature_deg_h_per_c * dT + d.DI * f[0] + d.DO * f[1] + d.DS * f[2] +
                 d.DII * f[0] * f[0] + d.DOO * f[1] * f[1] + d.DSS * f[2] * f[2] + d.DIO * f[0] * f[1] +
                 d.DIS * f[0] * f[2] + d.DOS * f[1] * f[2];
  if (p.turn_on_time_constant_s > 0.0) drift += p.turn_on_bias_deg_h * std::exp(-t / p.turn_on_time_constant_s);
  return scale * asymmetry * polynomial + drift * kDegPerHourInDegPerSecond;
}

std::vector<std::int64_t> GyroModel::record(const Rig& rig, std::size_t samples, unsigned oversampling) {
  if (oversampling == 0) throw Error("gyro: oversampling must be at least 1");
  const double dt = 1.0 / parameters_.sample_rate_hz;
  const double h = dt / oversampling;
  const double delay = parameters_.delay_ms * 1e-3;
  const double time_constant = parameters_.bandwidth_hz > 0.0 ? 1.0 / (2.0 * constants::kPi * parameters_.bandwidth_hz) : 0.0;
  const double phi = time_constant > 0.0 ? std::exp(-h / time_constant) : 0.0;
  auto input = [&](double t) { return static_output_deg_s(rig(t - delay), t); };
  if (!started_) {
    previous_input_ = input(time_s_);
    filter_state_ = previous_input_;  // the output has settled on the input when recording starts
    started_ = true;
  }
  std::vector<std::int64_t> pulses(samples);
  const double k0 = parameters_.scale_factor;
  const double start = time_s_;
  for (std::size_t i = 0; i < samples; ++i) {
    double angle = 0.0;  // ∫ y dt over the sample, deg
    for (unsigned j = 1; j <= oversampling; ++j) {
      const double t = start + (static_cast<double>(i) + static_cast<double>(j) / oversampling) * dt;
      const double x = input(t);
      if (time_constant > 0.0) {
        // Exact response of T·ẏ + y = x to x linear over the step: y = x − T·s + C·e^(−t/T).
        const double slope = (x - previous_input_) / h;
        const double c = filter_state_ - previous_input_ + time_constant * slope;
        angle += 0.5 * h * (previous_input_ + x) - time_constant * slope * h + c * time_constant * (1.0 - phi);
        filter_state_ = x - time_constant * slope + c * phi;
      } else {
        angle += 0.5 * h * (previous_input_ + x);
      }
      previous_input_ = x;
    }
    angle += noise_.next() / kRadPerDeg * dt;
    // The pulse counter: whole pulses out, the remainder carried to the next sample.
    const double total = k0 * angle + pulse_remainder_;
    const double whole = std::floor(total);
    pulse_remainder_ = total - whole;
    pulses[i] = static_cast<std::int64_t>(whole);
  }
  time_s_ = start + static_cast<double>(samples) * dt;
  return pulses;
}

}  // namespace inertest::sim
