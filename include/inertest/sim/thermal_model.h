// The simulated gyro in a temperature chamber (issue 20): a chamber with soaks and ramps, heating and
// cooling; a fiber coil that follows the chamber air through a first-order lag; and a bias in the
// coil's temperature, its rate of change and the direction of the change, the model equation of
// IEEE Std 952-1997 (Annex B) with the Shupe term (Shupe, Appl. Opt. 19 (1980) 654):
//   B = D_0 + Σ_k D_Tk ΔT^k + D_dT Ṫ + D_TdT ΔT Ṫ + D_H h,   ΔT = T_coil − T_ref, Ṫ = dT_coil/dt,
// h = +1/2 while |Ṫ| > soak rate and heating, −1/2 cooling, 0 otherwise. The gyro rests with IA east
// (no Earth rate on IA); its output is K·B plus white noise (angle random walk). Sensors read the
// coil and the chamber air, quantised.
#pragma once

#include <string>
#include <vector>

#include "inertest/sim/random.h"

namespace inertest::sim {

// The chamber: from start_degC, for each set point in turn a ramp at ramp_degC_per_min (its
// magnitude) to it, then a soak of soak_s; an initial soak of soak_s at the start.
struct ChamberProfile {
  double start_degC = 20.0;
  std::vector<double> set_points_degC = {60.0, -20.0, 20.0};
  std::vector<double> ramps_degC_per_min = {1.0, 2.0, 0.5};  // one per set point
  double soak_s = 1800.0;

  double duration_s() const;
  // The air temperature at time t (s from the start).
  double air_degC(double t) const;
};

struct ThermalGyroParameters {
  double scale_factor = 36000.0;  // K, output units per deg/s
  double reference_temperature_degC = 20.0;
  std::vector<double> bias_polynomial_deg_h = {0.02, 0.003, 4e-5};  // D_0, D_T, D_T2, ... (deg/h/degC^k)
  double rate_deg_h_per_degC_min = 0.03;                             // D_dT, deg/h/(degC/min)
  double temperature_rate_deg_h_per_degC2_min = 4e-4;                // D_TdT, deg/h/degC/(degC/min)
  double hysteresis_deg_h = 0.005;                                   // D_H: heating minus cooling
  double soak_rate_degC_per_min = 0.05;
  double coil_time_constant_s = 300.0;                               // the lag of coil behind the air
  double angle_random_walk_deg_rt_h = 0.0005;
  double sensor_quantum_degC = 0.0625;                            // both sensors' resolution
  double sample_rate_hz = 1.0;

  // The 1-sigma of one sample's mean rate, deg/h: N / sqrt(1/fs) with N in deg/sqrt(h) (IEEE 952 C.2).
  double sample_noise_deg_h() const;
  // The bias (deg/h) at coil temperature T and rate Ṫ (degC/min).
  double bias_deg_h(double coil_degC, double rate_degC_per_min) const;
};

struct ThermalRecordSamples {
  std::vector<double> time_s;
  std::vector<double> output;
  std::vector<double> coil_degC;     // the sensor's reading
  std::vector<double> chamber_degC;  // the sensor's reading
};

// Simulates the chamber run: one sample per 1/fs interval, stamped at its centre (as a test station
// exports), the output the bias at the centre plus white noise, the sensors read at the centre.
ThermalRecordSamples simulate_thermal_record(const ChamberProfile& chamber, const ThermalGyroParameters& gyro,
                                             Random& random);

// The record as CSV with the header time,output,coil,chamber.
std::string thermal_record_csv(const ThermalRecordSamples& samples);

}  // namespace inertest::sim
