#include "inertest/sim/thermal_model.h"

#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "inertest/core/error.h"

namespace inertest::sim {
namespace {

constexpr double kSecondsPerMinute = 60.0;

// The ramp of set point k: its start time and length (s) and start temperature.
struct Ramp {
  double start_s;
  double length_s;
  double from_degC;
  double to_degC;
};

std::vector<Ramp> ramps_of(const ChamberProfile& chamber) {
  if (chamber.ramps_degC_per_min.size() != chamber.set_points_degC.size()) {
    throw Error("the chamber needs one ramp rate per set point");
  }
  std::vector<Ramp> ramps;
  double t = chamber.soak_s, from = chamber.start_degC;
  for (std::size_t k = 0; k < chamber.set_points_degC.size(); ++k) {
    const double rate = std::abs(chamber.ramps_degC_per_min[k]) / kSecondsPerMinute;
    if (!(rate > 0.0)) throw Error("a chamber ramp rate must be positive");
    const double length = std::abs(chamber.set_points_degC[k] - from) / rate;
    ramps.push_back({t, length, from, chamber.set_points_degC[k]});
    t += length + chamber.soak_s;
    from = chamber.set_points_degC[k];
  }
  return ramps;
}

}  // namespace

double ChamberProfile::duration_s() const {
  const Ramp last = ramps_of(*this).back();
  return last.start_s + last.length_s + soak_s;
}

double ChamberProfile::air_degC(double t) const {
  double temperature = start_degC;
  for (const Ramp& ramp : ramps_of(*this)) {
    if (t < ramp.start_s) break;
    temperature = t >= ramp.start_s + ramp.length_s
                      ? ramp.to_degC
                      : ramp.from_degC + (ramp.to_degC - ramp.from_degC) * (t - ramp.start_s) / ramp.length_s;
  }
  return temperature;
}

double ThermalGyroParameters::sample_noise_deg_h() const {
  return angle_random_walk_deg_rt_h * kSecondsPerMinute * std::sqrt(sample_rate_hz);
}

double ThermalGyroParameters::bias_deg_h(double coil_degC, double rate_degC_per_min) const {
  const double dt = coil_degC - reference_temperature_degC;
  double bias = 0.0, power = 1.0;
  for (const double d : bias_polynomial_deg_h) {
    bias += d * power;
    power *= dt;
  }
  const double leg = rate_degC_per_min > soak_rate_degC_per_min ? 0.5 : rate_degC_per_min < -soak_rate_degC_per_min ? -0.5 : 0.0;
  return bias + (rate_deg_h_per_degC_min + temperature_rate_deg_h_per_degC2_min * dt) * rate_degC_per_min +
         hysteresis_deg_h * leg;
}

ThermalRecordSamples simulate_thermal_record(const ChamberProfile& chamber, const ThermalGyroParameters& gyro,
                                             Random& random) {
  if (!(gyro.coil_time_constant_s > 0.0 && gyro.sample_rate_hz > 0.0 && gyro.sensor_quantum_degC >= 0.0)) {
    throw Error("the coil time constant and the sample rate must be positive, the sensor quantum not negative");
  }
  const double period = 1.0 / gyro.sample_rate_hz;
  const std::size_t samples = static_cast<std::size_t>(chamber.duration_s() * gyro.sample_rate_hz);
  const double tau = gyro.coil_time_constant_s;
  const double sigma = gyro.sample_noise_deg_h();
  const auto quantise = [&](double t) {
    return gyro.sensor_quantum_degC > 0.0 ? std::round(t / gyro.sensor_quantum_degC) * gyro.sensor_quantum_degC : t;
  };
  ThermalRecordSamples record;
  // The coil: dT_c/dt = (T_air − T_c)/τ, integrated exactly for an air temperature linear over each
  // step of h: T_c(t+h) = A(t+h) − sτ + (T_c(t) − A(t) + sτ)·e^(−h/τ), s the air's slope.
  constexpr int kSteps = 10;  // per half sample
  const double h = 0.5 * period / kSteps;
  const double decay = std::exp(-h / tau);
  double t = 0.0, coil = chamber.start_degC;
  const auto advance = [&] {
    for (int k = 0; k < kSteps; ++k) {
      const double a0 = chamber.air_degC(t), a1 = chamber.air_degC(t + h);
      const double slope = (a1 - a0) / h;
      coil = a1 - slope * tau + (coil - a0 + slope * tau) * decay;
      t += h;
    }
  };
  for (std::size_t i = 0; i < samples; ++i) {
    advance();  // to the sample's centre
    const double rate = (chamber.air_degC(t) - coil) / tau * kSecondsPerMinute;
    const double bias = gyro.bias_deg_h(coil, rate) + sigma * random.normal();
    record.time_s.push_back(t);
    record.output.push_back(gyro.scale_factor * bias / 3600.0);
    record.coil_degC.push_back(quantise(coil));
    record.chamber_degC.push_back(quantise(chamber.air_degC(t)));
    advance();
  }
  return record;
}

std::string thermal_record_csv(const ThermalRecordSamples& samples) {
  std::string text = "time,output,coil,chamber\n";
  for (std::size_t i = 0; i < samples.time_s.size(); ++i) {
    fmt::format_to(std::back_inserter(text), "{},{},{},{}\n", samples.time_s[i], samples.output[i], samples.coil_degC[i],
                   samples.chamber_degC[i]);
  }
  return text;
}

}  // namespace inertest::sim
