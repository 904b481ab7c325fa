#include "inertest/procedures/bias_temperature_sensitivity.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/test_temperature.h"
#include "inertest/core/units.h"

namespace inertest {
BiasTemperatureSensitivityResult bias_temperature_sensitivity(std::span<const TemperatureRunBias> runs,
                                                              const BiasTemperatureOptions& options) {
  if (runs.size() < 2) {
    throw Error(fmt::format("bias temperature sensitivity: {} run(s); eq. (22) needs the room-temperature run and "
                            "at least one other temperature",
                            runs.size()));
  }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!std::isfinite(runs[i].bias_deg_h)) throw Error("bias temperature sensitivity: a run's bias is not a finite number");
    check_test_temperature("bias temperature sensitivity", i + 1, runs[i].temperature_degC);
  }
  std::size_t room = 0;
  if (options.room_temperature_degC) {
    std::size_t found = 0;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      if (runs[i].temperature_degC == *options.room_temperature_degC) {
        room = i;
        ++found;
      }
    }
    if (found != 1) {
      throw Error(fmt::format("bias temperature sensitivity: {} runs at the room temperature {} degC; exactly one "
                              "is needed",
                              found, *options.room_temperature_degC));
    }
  } else {
    check_first_run_is_room_temperature("bias temperature sensitivity", "5.12.4.3 a", runs.front().temperature_degC,
                                        "--room-temperature; room_temperature_degC in a plan");
  }
  BiasTemperatureSensitivityResult result;
  result.runs.assign(runs.begin(), runs.end());
  const TemperatureRunBias& reference = runs[room];
  double worst = -1.0;
  std::size_t worst_index = room;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (i == room) {
      result.sensitivities.push_back(0.0);
      continue;
    }
    const double dt = runs[i].temperature_degC - reference.temperature_degC;
    if (dt == 0.0) {
      throw Error(fmt::format("bias temperature sensitivity: run {} is at the room temperature {} degC too; eq. (22) "
                              "divides by Ti − Tm",
                              i + 1, reference.temperature_degC));
    }
    const double s = std::abs((runs[i].bias_deg_h - reference.bias_deg_h) / dt);  // eq. (22)
    result.sensitivities.push_back(s);
    if (s > worst) {
      worst = s;
      worst_index = i;
    }
  }
  result.bias_temperature_sensitivity = {worst, "deg/h/degC", std::nullopt};
  result.room_temperature = {reference.temperature_degC, "degC", std::nullopt};
  result.room_temperature_bias = {reference.bias_deg_h, "deg/h", std::nullopt};
  result.worst_temperature = {runs[worst_index].temperature_degC, "degC", std::nullopt};
  return result;
}

}  // namespace inertest
