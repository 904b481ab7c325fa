#include "inertest/procedures/scale_factor_temperature_sensitivity.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/test_temperature.h"
#include "inertest/core/units.h"

namespace inertest {

void ScaleFactorTemperatureOptions::validate() const {
  scale_factor.validate();
  if (reference_temperature_degC && !std::isfinite(*reference_temperature_degC)) {
    throw Error("scale factor temperature sensitivity: the reference temperature is not finite");
  }
}

ScaleFactorTemperatureResult scale_factor_temperature_sensitivity(std::span<const TemperatureRun> runs,
                                                                  const ScaleFactorTemperatureOptions& options) {
  options.validate();
  if (runs.size() < 2) {
    throw Error(fmt::format("scale factor temperature sensitivity: {} run(s); needs the room-temperature run and at "
                            "least one test temperature (GJB 2426A 5.8.5.3)",
                            runs.size()));
  }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    check_test_temperature("scale factor temperature sensitivity", i + 1, runs[i].temperature_degC);
    for (std::size_t j = 0; j < i; ++j) {
      if (runs[j].temperature_degC == runs[i].temperature_degC) {
        throw Error(fmt::format("scale factor temperature sensitivity: runs {} and {} are both at {} degC", j + 1,
                                i + 1, runs[i].temperature_degC));
      }
    }
  }
  std::size_t reference = 0;
  if (options.reference_temperature_degC) {
    const auto it = std::find_if(runs.begin(), runs.end(), [&](const TemperatureRun& run) {
      return std::abs(run.temperature_degC - *options.reference_temperature_degC) <= 1e-9;
    });
    if (it == runs.end()) {
      throw Error(fmt::format("scale factor temperature sensitivity: no run at the reference temperature {} degC",
                              *options.reference_temperature_degC));
    }
    reference = static_cast<std::size_t>(it - runs.begin());
  } else {
    check_first_run_is_room_temperature("scale factor temperature sensitivity", "5.8.5.3 a",
                                        runs.front().temperature_degC,
                                        "--reference-temperature; reference_temperature_degC in a plan");
  }

  std::vector<Figure> k(runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i) {
    try {
      k[i] = scale_factor(runs[i].points, options.scale_factor).scale_factor;
    } catch (const Error& e) {
      throw Error(fmt::format("scale factor temperature sensitivity: run {} ({} degC): {}", i + 1,
                              runs[i].temperature_degC, e.message()));
    }
  }
  const double km = k[reference].value;
  const double tm = runs[reference].temperature_degC;
  if (km == 0.0) throw Error("scale factor temperature sensitivity: the room-temperature scale factor is zero");

  ScaleFactorTemperatureResult result;
  double worst = -1.0;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (i == reference) continue;
    const double ti = runs[i].temperature_degC;
    const double kt = std::abs((k[i].value - km) / (km * (ti - tm)));  // eq. (13), one test temperature
    result.test_temperatures.push_back({ti, k[i], {kt * 1e6, "ppm/degC", std::nullopt}});
    if (kt > worst) {
      worst = kt;
      result.worst_temperature_degC = ti;
    }
  }
  result.scale_factor_temperature_sensitivity = {worst * 1e6, "ppm/degC", std::nullopt};  // eq. (13), the max
  result.reference_temperature = {tm, "degC", std::nullopt};
  result.reference_scale_factor = k[reference];
  return result;
}

}  // namespace inertest
