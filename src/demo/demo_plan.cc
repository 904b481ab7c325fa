// The built-in demo simulation plan: a copy of examples/demo/simulation.toml (the test
// DemoPlan.BuiltInPlanMatchesTheExample keeps the two identical).
#include "inertest/demo/demo.h"

namespace inertest {

const std::string& demo_simulation_plan() {
  static const std::string plan = R"toml(# The demo campaign: a navigation-grade fiber optic gyro through every test of the virtual lab.
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
bias_deg_h = 0.02
bias_temperature_deg_h_per_c = 0.0004
reference_temperature_c = 20
turn_on_bias_deg_h = 0.05
turn_on_time_constant_s = 120
angle_random_walk_deg_rt_h = 0.002
bias_instability_deg_h = 0.003
rate_random_walk_deg_h_rt_h = 0.004
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

[rate_table]
rate_error_ppm = 0.5
tilt_arcsec = [2, -1]
wobble_arcsec = 1
face_arcsec = [5, 3]

[centrifuge]
radius_m = 1.0
perpendicularity_arcsec = [4, -4]
platform_rate_error_rad_s = 1e-5

[[test]]
kind = "scale_factor"
name = "scale_factor"
seconds_per_rate = 60

[[test]]
kind = "bias"
name = "bias_static"
seconds = 7200

[[test]]
kind = "allan"
name = "allan_long_static"
hours = 30
sample_rate_hz = 10

[[test]]
kind = "centrifuge"
name = "centrifuge"
g_levels = [10, 20]
revolutions = 200
)toml";
  return plan;
}

}  // namespace inertest
