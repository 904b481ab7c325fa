// The simulated fiber optic gyro: a single-axis rate gyro whose parameters are given in the units
// of a data sheet, and which turns the stimulus of a rig (angular rate and specific force in its
// own IA/OA/SA frame, its temperature) into the integer pulse counts a test station records.
//
// Output model, in input-equivalent units (deg/s), before the dynamics:
//   x(t) = [1 + k_T·(T − T0)]·g(ω_IA(t − d)) + D(f, T, t)
//   ω_IA = u·ω                 u = IA tilted by the two input-axis misalignment angles
//   g(Ω)  = (1 ± a/2)·[Ω + Ω_max·Σ_n c_n·(Ω/Ω_max)^n]   a: asymmetry (+ for Ω > 0), c_n in ppm
//   D     = DF + b_T·(T − T0) + b_on·e^(−t/τ_on) + DI·fI + DO·fO + DS·fS + DII·fI² + DOO·fO² + DSS·fS²
//           + DIO·fI·fO + DIS·fI·fS + DOS·fO·fS          (reference section 1, eq. 2; °/h and g)
// then a first-order low-pass of bandwidth f_c (time constant 1/(2π f_c)) and the pure delay d,
// then the noise of IEEE Std 952 (noise.h), then the pulse counter: the angle K0·∫(y + noise)dt
// is accumulated and each sample emits the whole pulses, keeping the remainder.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/sim/geometry.h"
#include "inertest/sim/noise.h"
#include "inertest/sim/random.h"

namespace inertest::sim {

// Acceleration-sensitive drift coefficients of reference section 1, eq. (2), except DF (which is
// the bias of GyroParameters).
struct DriftCoefficients {
  double DI = 0.0, DO = 0.0, DS = 0.0;                              // deg/h/g
  double DII = 0.0, DOO = 0.0, DSS = 0.0, DIO = 0.0, DIS = 0.0, DOS = 0.0;  // deg/h/g^2
};

struct GyroParameters {
  std::string id = "FOG-SIM";
  std::string output_unit = "pulse/s";
  double sample_rate_hz = 100.0;
  double scale_factor = 36000.0;        // K0, output unit per deg/s, at the reference temperature
  double maximum_rate_deg_s = 300.0;    // Ω_max of the nonlinearity polynomial
  std::vector<double> nonlinearity_ppm; // c_2, c_3, ...: coefficient of (Ω/Ω_max)^n, ppm of Ω_max
  double asymmetry_ppm = 0.0;           // a: K(+) = K(1 + a/2), K(-) = K(1 - a/2)
  double scale_factor_temperature_ppm_per_c = 0.0;  // k_T
  double bias_deg_h = 0.0;              // DF at the reference temperature
  double bias_temperature_deg_h_per_c = 0.0;        // b_T
  double reference_temperature_c = 20.0;            // T0
  double turn_on_bias_deg_h = 0.0;      // b_on: extra bias at power-on ...
  double turn_on_time_constant_s = 0.0; // τ_on: ... decaying with this time constant
  double quantization_arcsec = 0.0;             // Q
  double angle_random_walk_deg_rt_h = 0.0;      // N, deg/sqrt(h)
  double bias_instability_deg_h = 0.0;          // B
  double rate_random_walk_deg_h_rt_h = 0.0;     // K, deg/h/sqrt(h)
  double rate_ramp_deg_h_h = 0.0;               // R, deg/h/h
  std::array<double, 2> flicker_correlation_s = {1.0, 1.0e5};  // range of B's correlation times
  double bandwidth_hz = 0.0;            // f_c of the first-order response; 0: none
  double delay_ms = 0.0;                // d
  std::array<double, 2> input_axis_misalignment_arcsec{};  // IA tilt toward OA, toward SA
  DriftCoefficients drift;

  // Throws Error saying which parameter is out of range.
  void validate() const;
  // The noise terms in SI units.
  NoiseParameters noise() const;
  nlohmann::json to_json() const;
};

// What a rig applies to the gyro at one instant.
struct Stimulus {
  Vector3 rate{};            // angular rate relative to inertial space, rad/s, in IA/OA/SA
  Vector3 specific_force{};  // g (9.80665 m/s²), in IA/OA/SA
  double temperature_c = 20.0;
};

// A rig: the stimulus at time t, seconds since the gyro was powered on.
using Rig = std::function<Stimulus(double t)>;

class GyroModel {
 public:
  // power_on_age_s: how long the gyro has been on when the record starts (0: the record starts
  // at power-on and shows the turn-on transient).
  GyroModel(const GyroParameters& parameters, Random random, double power_on_age_s = 0.0);

  // Records `samples` samples at the sample rate, continuing from the previous call; returns the
  // pulse count of each sample interval. oversampling: internal steps per sample (the input is
  // taken as piecewise linear between steps and the low-pass is integrated exactly over each).
  std::vector<std::int64_t> record(const Rig& rig, std::size_t samples, unsigned oversampling = 4);

  // Time since power-on at the end of the last recorded sample.
  double time_s() const { return time_s_; }
  const GyroParameters& parameters() const { return parameters_; }

  // The noise-free output (input-equivalent deg/s) for a stimulus at temperature T after the
  // turn-on transient, before the dynamics. For the truth of the simulator only.
  double static_output_deg_s(const Stimulus& stimulus, double time_since_power_on_s) const;

 private:
  GyroParameters parameters_;
  NoiseGenerator noise_;
  Vector3 input_axis_{};
  double time_s_;
  double filter_state_ = 0.0;  // y, deg/s
  double previous_input_ = 0.0;
  bool started_ = false;
  double pulse_remainder_ = 0.0;
};

}  // namespace inertest::sim
