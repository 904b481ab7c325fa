// The built-in demo simulation plan: a copy of examples/demo/simulation.toml (the test
// DemoPlan.BuiltInPlanMatchesTheExample keeps the two identical).
#include "inertest/demo/demo.h"

namespace inertest {

const std::string& demo_simulation_plan() {
  static const std::string plan = R"toml(# The demo campaign: a navigation-grade fiber optic gyro (and an accelerometer for the 4-position
# test) through every test of the virtual lab that has a processing method.
# `inertest demo` runs exactly this plan (it is compiled in); `inertest simulate` takes it too:
#   inertest simulate examples/demo/simulation.toml --out lab && inertest run lab/plan.toml --out results
seed = 20040601

[plan]
title = "Demo: navigation-grade FOG, complete GJB 2426A / IEEE 952 campaign (simulated)"

[site]
name = "Harbin test hall 2 (virtual)"
latitude_deg = 45.75

[gyro]
id = "FOG-SIM-NAV"
output_unit = "pulse/s"
sample_rate_hz = 100
scale_factor = 36000            # pulse/s per deg/s (0.1 arcsec per pulse)
maximum_rate_deg_s = 300
nonlinearity_ppm = [0, 8]       # cubic term: 8 ppm of full scale at full scale
asymmetry_ppm = 6
scale_factor_temperature_ppm_per_c = 1.5
scale_factor_repeatability_ppm = 5
bias_deg_h = 0.02
bias_temperature_deg_h_per_c = 0.003
bias_repeatability_deg_h = 0.03
reference_temperature_c = 20
turn_on_bias_deg_h = 3          # thermal transient after power-on ...
turn_on_time_constant_s = 150   # ... decaying with this time constant
angle_random_walk_deg_rt_h = 0.0005
bias_instability_deg_h = 0.005
rate_random_walk_deg_h_rt_h = 0.003
flicker_correlation_s = [0.1, 1e6]  # the flicker floor of B holds from seconds to days
bandwidth_hz = 300
delay_ms = 0.8
input_axis_misalignment_arcsec = [25, -15]

[gyro.drift]
DI = 0.010
DO = -0.006
DS = 0.004
DII = 2.0e-4
DOO = -1.5e-4
DSS = 1.0e-4
DIO = 5.0e-5
DIS = -4.0e-5
DOS = 3.0e-5

[accelerometer]
id = "QA-SIM"
output_unit = "V"
sample_rate_hz = 10
scale_factor = 1.3              # V/g
bias_mg = 0.5
misalignment_arcsec = [20, -5]  # IA toward PA, toward OA
noise_ug_rt_hz = 20
output_resolution = 1e-6        # voltmeter quantum, V

[rate_table]
rate_error_ppm = 0.5
tilt_arcsec = [2, -1]
wobble_arcsec = 1
face_arcsec = [5, 3]
fixture_arcsec = -50            # the misalignment fixture's vertical face

[dividing_head]
tilt_arcsec = 6
fixture_arcsec = -3

[centrifuge]
radius_m = 1.0
perpendicularity_arcsec = [4, -4]
platform_rate_error_rad_s = 1e-5

# Specification limits ([test.limits], copied into the processing plan as [procedure.limits]): a
# navigation-grade FOG as the usual grade convention has it (bias stability and bias instability of
# order 0.01 deg/h, angle random walk below about 0.005 deg/sqrt(h), scale-factor errors of order
# 10 ppm; e.g. P. D. Groves, Principles of GNSS, Inertial, and Multisensor Integrated Navigation
# Systems, 2nd ed., Artech House 2013, chapter 4), on the figures an IEEE Std 952-1997
# specification lists. The simulated gyro meets all but two: its scale-factor temperature
# sensitivity (1.5 ppm/degC) and its bias repeatability (0.03 deg/h, 1 sigma) exceed their limits,
# so the report shows PASS and FAIL per limit.

[[test]]
kind = "scale_factor"
name = "scale_factor"
seconds_per_rate = 30
static_seconds = 30
[test.limits]
nonlinearity = { max = 10, unit = "ppm" }
asymmetry = { max = 10, unit = "ppm" }

[[test]]
kind = "scale_factor_repeatability"
name = "scale_factor_repeatability"
runs = 6
[test.limits]
scale_factor_repeatability = { max = 10, unit = "ppm" }

[[test]]
kind = "scale_factor_temperature"
name = "scale_factor_temperature"
temperatures_c = [20, -40, 60]
[test.limits]
scale_factor_temperature_sensitivity = { max = 1, unit = "ppm/degC" }  # the simulated gyro has 1.5: FAIL

[[test]]
kind = "maximum_input_rate"
name = "maximum_input_rate"
rates_deg_s = [1, 10, 50, 100, 200, 300, 400, 500]
nonlinearity_limit_ppm = 5
[test.limits]
maximum_input_rate = { min = 200, unit = "deg/s" }

[[test]]
kind = "bias"
name = "bias_static"
seconds = 3600
[test.limits]
bias = { min = -0.05, max = 0.05, unit = "deg/h" }
"/bias_stability/1" = { max = 0.05, unit = "deg/h" }   # 10 s smoothing
"/bias_stability/2" = { max = 0.02, unit = "deg/h" }   # 100 s smoothing
random_walk_coefficient = { max = 0.005, unit = "deg/sqrt(h)" }

[[test]]
kind = "bias_repeatability"
name = "bias_repeatability"
runs = 6
seconds = 300
[test.limits]
bias_repeatability = { max = 0.01, unit = "deg/h" }  # the simulated gyro has 0.03 (1 sigma): FAIL

[[test]]
kind = "bias_temperature"
name = "bias_temperature"
temperatures_c = [20, -40, 60]
seconds = 600
[test.limits]
bias_temperature_sensitivity = { max = 0.005, unit = "deg/h/degC" }

[[test]]
kind = "temperature_model"
name = "temperature_model"      # a chamber ramp: soaks, heating and cooling at 1, 2 and 0.5 degC/min
set_points_c = [60, -20, 20]
ramps_c_per_min = [1, 2, 0.5]
soak_s = 1800
[test.limits]
residual_bias_stability = { max = 0.005, unit = "deg/h" }

[[test]]
kind = "turn_on_time"
name = "turn_on_time"
seconds = 1200
rest_band_deg_h = 0.2
smoothing_s = 60
[test.limits]
turn_on_time = { max = 600, unit = "s" }

[[test]]
kind = "polarity"
name = "polarity"

[[test]]
kind = "threshold"
name = "threshold"
[test.limits]
threshold = { max = 0.5, unit = "deg/h" }

[[test]]
kind = "resolution"
name = "resolution"
[test.limits]
resolution = { max = 0.5, unit = "deg/h" }

[[test]]
kind = "bandwidth"
name = "bandwidth"
[test.limits]
bandwidth = { min = 200, unit = "Hz" }
delay = { max = 1, unit = "ms" }

[[test]]
kind = "input_axis_misalignment"
name = "input_axis_misalignment"
rate_deg_s = 100
[test.limits]
misalignment = { max = 60, unit = "arcsec" }

[[test]]
kind = "gyro_misalignment"
name = "gyro_misalignment"
rates_deg_s = [20, 30, 40]
[test.limits]
misalignment = { max = 60, unit = "arcsec" }

[[test]]
kind = "accelerometer_misalignment"
name = "accelerometer_misalignment"
runs = 3
[test.limits]
misalignment = { max = 60, unit = "arcsec" }

[[test]]
kind = "allan"
name = "allan_long_static"
hours = 60
sample_rate_hz = 5
[test.limits]
"/noise/angle_random_walk" = { max = 0.005, unit = "deg/sqrt(h)" }
"/noise/bias_instability" = { max = 0.01, unit = "deg/h" }

[[test]]
kind = "imu_noise"
name = "imu_noise"              # a six-axis MEMS IMU at rest: every axis in one pass, gyros and accelerometers
hours = 6
sample_rate_hz = 10

[[test]]
kind = "imu_tumble"
name = "imu_tumble"             # a MEMS IMU turned by hand, raw counts: both triads without a table
orientations = 36               # the method's paper asks for about 36 to 50

[[test]]
kind = "accelerometer_tumble"
name = "accelerometer_tumble"   # the accelerometer on the dividing head: 8 positions, two turns, mounted both ways
[test.limits]
misalignment_about_output_axis = { min = -120, max = 120, unit = "arcsec" }

[[test]]
kind = "centrifuge"
name = "centrifuge"
g_levels = [10, 20]
revolutions = 200
)toml";
  return plan;
}

}  // namespace inertest
