#include "inertest/procedures/bias_temperature_sensitivity.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/test_temperature.h"
#include "inertest/core/units.h"

namespace inertest {
namespace {

constexpr double kStandardAtmosphereDegC[2] = {15.0, 35.0};  // GJB 2426A-2004 4.1.1.1 a)

}  // namespace

BiasTemperatureSensitivityResult bias_temperature_sensitivity(std::span<const TemperatureRunBias> runs,
                                                              const BiasTemperatureOptions& options) {
  if (runs.size() < 2) {
    throw Error(fmt::format("bias temperature sensitivity: {} run(s); eq. (22) needs the room-temperature run and "
                            "at least one other temperature",
                            runs.size()));
  }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!std::isfinite(runs[i].temperature_degC) || !std::isfinite(runs[i].bias_deg_h)) {
      throw Error("bias temperature sensitivity: a run's temperature or bias is not a finite number");
    }
    if (runs[i].temperature_degC < constants::kAbsoluteZeroDegC) {  // a typo (-400 for -40) moved Bt silently
      throw Error(fmt::format("bias temperature sensitivity: run {}: {} degC is below absolute zero", i + 1,
                              runs[i].temperature_degC));
    }
    // No gyro is tested above 200 degC: such a value is a temperature in kelvin (298.15 for 25), which
    // divided Bt by up to 9 when it stood beside runs in degC.
    if (runs[i].temperature_degC > kHottestTestDegC) {
      throw Error(fmt::format("bias temperature sensitivity: run {}: {} degC is above {} degC; is it in kelvin? "
                              "temperatures are in degC",
                              i + 1, runs[i].temperature_degC, kHottestTestDegC));
    }
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
  } else if (const double first = runs.front().temperature_degC;
             first < kStandardAtmosphereDegC[0] || first > kStandardAtmosphereDegC[1]) {
    // Runs listed cold to hot made the coldest one Tm, and Bt 2.2 times too small, without a word.
    throw Error(fmt::format("bias temperature sensitivity: the first run, taken as the room-temperature run "
                            "(5.12.4.3 a), is at {} degC, outside the standard atmosphere's {}-{} degC (4.1.1.1): "
                            "give the room temperature (--room-temperature; room_temperature_degC in a plan)",
                            first, kStandardAtmosphereDegC[0], kStandardAtmosphereDegC[1]));
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
