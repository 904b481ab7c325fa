// Bias temperature sensitivity: GJB 2426A-2004 5.12.4, eq. (22).
//
//   Bt = max_i | (B0i − B0m) / (Ti − Tm) |                                                 (22)
//
// B0m is the bias at room temperature Tm, B0i the bias at each test temperature Ti, each by
// eq. (19) in deg/h. The room-temperature run is the one at room_temperature_degC when given
// (exactly one run must be at that temperature), else the first run: 5.12.4.3 a) measures room
// temperature first, so that run must lie in the standard atmosphere's 15-35 degC (4.1.1.1 a).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"

namespace inertest {

struct TemperatureRunBias {
  double temperature_degC = 0.0;
  double bias_deg_h = 0.0;
};

struct BiasTemperatureOptions {
  std::optional<double> room_temperature_degC;
};

struct BiasTemperatureSensitivityResult {
  Figure bias_temperature_sensitivity;  // Bt, deg/h/degC
  Figure room_temperature;              // Tm, degC
  Figure room_temperature_bias;         // B0m, deg/h
  Figure worst_temperature;             // the Ti that gives the maximum, degC
  std::vector<TemperatureRunBias> runs;
  std::vector<double> sensitivities;    // |B0i − B0m| / |Ti − Tm| per run (0 for the room run)
};

// Throws Error for fewer than 2 runs, no run (or more than one) at the room temperature given, a
// first run outside 15-35 degC without one, another run at the room temperature (division by zero
// in eq. 22), a temperature below absolute zero or above 200 degC (kelvin), or a non-finite value.
BiasTemperatureSensitivityResult bias_temperature_sensitivity(std::span<const TemperatureRunBias> runs,
                                                              const BiasTemperatureOptions& options = {});

// The procedure's spec (src/procedures/bias_temperature_spec.cc): CLI, plan step, JSON and text; each
// run's bias by eq. (19) from its output record.
ProcedureSpec bias_temperature_spec();

}  // namespace inertest
