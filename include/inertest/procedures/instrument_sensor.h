// The sensor a plan's [instrument] is, for ParameterSpec::instrument_gives_if. Its
// nominal_scale_factor means output units per deg/s for a gyro and per g for an accelerometer, and
// its output_unit is that sensor's: a procedure takes them only from an instrument of its own
// sensor (a gyro's 36000 pulse/s per deg/s was an accelerometer step's kI, per g).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "inertest/core/procedure_spec.h"

namespace inertest {

inline bool instrument_is_gyro(const ProcedureCall&, const nlohmann::json& instrument) {
  return instrument.value("type", std::string("gyro")) == "gyro";
}

inline bool instrument_is_accelerometer(const ProcedureCall&, const nlohmann::json& instrument) {
  return instrument.value("type", std::string("gyro")) == "accelerometer";
}

}  // namespace inertest
