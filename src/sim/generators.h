// The test generators of the simulator, one file each (generate_<kind>.cc).
#pragma once

#include "sim/lab.h"

namespace inertest::sim {

void generate_scale_factor(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_static(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_allan(campaign::PlanTable& test, const std::string& name, Lab& lab);
void generate_centrifuge(campaign::PlanTable& test, const std::string& name, Lab& lab);

}  // namespace inertest::sim
