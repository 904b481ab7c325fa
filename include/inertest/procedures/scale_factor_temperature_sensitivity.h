// Scale factor temperature sensitivity: GJB 2426A-2004 5.8.5, eq. (13).
//
// The scale factor is measured at room temperature Tm (Km, 5.8.5.3 a) and at each test temperature
// Ti after a soak (Ki, 5.8.5.3 b). Eq. (13) is printed as Kt = |(Ki − Km)/(Km·(Ti − Tm))|max; we
// read it as eq. (22) for the bias, which prints the max over the test temperatures explicitly:
// Kt = max_i |(Ki − Km)/(Km·(Ti − Tm))|, the largest relative change of K per degree, in ppm/degC.
// The sensitivity at every test temperature is reported too.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "inertest/core/figure.h"
#include "inertest/procedures/scale_factor.h"

namespace inertest {

struct TemperatureRun {
  double temperature_degC = 0.0;
  std::vector<ScaleFactorPoint> points;  // the scale-factor test points at that temperature
};

struct ScaleFactorTemperatureOptions {
  ScaleFactorOptions scale_factor;
  // Tm: the run at this temperature is the room-temperature run. Unset: the first run (5.8.5.3 a
  // measures room temperature first), which must then lie in 15-35 degC (4.1.1.1 a).
  std::optional<double> reference_temperature_degC;

  void validate() const;
};

struct TemperaturePointSensitivity {
  double temperature_degC = 0.0;
  Figure scale_factor;   // Ki
  Figure sensitivity;    // |(Ki − Km)/(Km·(Ti − Tm))|, ppm/degC
};

struct ScaleFactorTemperatureResult {
  Figure scale_factor_temperature_sensitivity;  // Kt, eq. (13), ppm/degC
  Figure reference_temperature;                  // Tm, degC
  Figure reference_scale_factor;                 // Km
  double worst_temperature_degC = 0.0;           // Ti where the max of eq. (13) is reached
  std::vector<TemperaturePointSensitivity> test_temperatures;  // every Ti ≠ Tm, in the order given
  std::vector<std::string> warnings;
};

// Throws Error when fewer than two runs are given, two runs share a temperature, no run (or more
// than one) is at the reference temperature, or a run's scale factor cannot be computed (named).
ScaleFactorTemperatureResult scale_factor_temperature_sensitivity(std::span<const TemperatureRun> runs,
                                                                  const ScaleFactorTemperatureOptions& options = {});

// The declaration of the procedure (core/procedure_spec.h): `inertest scale-factor-temperature`
// with a CSV listing of the runs, plan kind "scale_factor_temperature".
ProcedureSpec scale_factor_temperature_spec();

}  // namespace inertest
