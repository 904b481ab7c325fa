// The test generators of the simulator, one file each (generate_<kind>.cc).
#pragma once

#include "sim/lab.h"

namespace inertest::sim {

void generate_scale_factor(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_static(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_allan(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_centrifuge(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_gyro_misalignment(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_input_axis_misalignment(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_accelerometer_misalignment(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_bandwidth(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_scale_factor_temperature(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_scale_factor_repeatability(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_maximum_input_rate(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_bias_temperature(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_bias_repeatability(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_turn_on_time(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_warm_up_time(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_polarity(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_threshold(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_resolution(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_temperature_model(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_imu_noise(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_imu_tumble(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_accelerometer_tumble(campaign::PlanTable& test, const std::string& name, Lab& lab);

}  // namespace inertest::sim
