#include "inertest/procedures/scale_factor_temperature_sensitivity.h"

#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "procedures/scale_factor_series_test_util.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;
using testing::linear_run;

std::vector<TemperatureRun> runs() {
  // Km = 100 at 20 degC; 100.1 at 40 degC: 0.1/(100·20) = 50 ppm/degC; 99.7 at −20 degC:
  // 0.3/(100·40) = 75 ppm/degC; 100.2 at 60 degC: 0.2/(100·40) = 50 ppm/degC. Max: 75 at −20.
  return {{20.0, linear_run(100.0)}, {40.0, linear_run(100.1)}, {-20.0, linear_run(99.7)}, {60.0, linear_run(100.2)}};
}

TEST(ScaleFactorTemperatureSensitivity, HandComputedMaximumOverTheTestTemperatures) {
  const auto result = scale_factor_temperature_sensitivity(runs());
  EXPECT_NEAR_RELATIVE(result.scale_factor_temperature_sensitivity.value, 75.0, 1e-9);
  EXPECT_EQ(result.scale_factor_temperature_sensitivity.unit, "ppm/degC");
  EXPECT_EQ(result.worst_temperature_degC, -20.0);
  EXPECT_EQ(result.reference_temperature.value, 20.0);
  ASSERT_EQ(result.test_temperatures.size(), 3u);
  EXPECT_NEAR_RELATIVE(result.test_temperatures[0].sensitivity.value, 50.0, 1e-9);
  EXPECT_NEAR_RELATIVE(result.test_temperatures[2].sensitivity.value, 50.0, 1e-9);
  EXPECT_EQ(scale_factor_temperature_spec().fields_of(&result).at("test_temperatures").size(), 3u);
}

TEST(ScaleFactorTemperatureSensitivity, ReferenceChosenByTemperature) {
  ScaleFactorTemperatureOptions options;
  options.reference_temperature_degC = 40.0;
  // Km = 100.1 at 40: 20 → 0.1/(100.1·20); −20 → 0.4/(100.1·60); 60 → 0.1/(100.1·20). Max 0.4/6006.
  const auto result = scale_factor_temperature_sensitivity(runs(), options);
  EXPECT_NEAR_RELATIVE(result.scale_factor_temperature_sensitivity.value, 0.4 / (100.1 * 60.0) * 1e6, 1e-9);
}

TEST(ScaleFactorTemperatureSensitivity, BadInputIsAnError) {
  auto all = runs();
  EXPECT_THROW(scale_factor_temperature_sensitivity(std::span(all.data(), 1)), Error);
  ScaleFactorTemperatureOptions options;
  options.reference_temperature_degC = 25.0;
  try {
    scale_factor_temperature_sensitivity(all, options);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("no run at the reference temperature"));
  }
  auto duplicate = runs();
  duplicate[2].temperature_degC = 40.0;
  EXPECT_THROW(scale_factor_temperature_sensitivity(duplicate), Error);
  auto typo = runs();
  typo[2].temperature_degC = -400.0;  // for -40: Kt over 420 degC
  try {
    scale_factor_temperature_sensitivity(typo);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.message(), "scale factor temperature sensitivity: run 3: -400 degC is below absolute zero");
  }
  // Runs listed cold to hot: the first is no room temperature (it was taken as Tm: Kt 3.00 for 3.50).
  auto cold_first = runs();
  std::swap(cold_first[0], cold_first[2]);
  try {
    scale_factor_temperature_sensitivity(cold_first);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.message(), "scale factor temperature sensitivity: the first run, taken as the room-temperature run "
                           "(5.8.5.3 a), is at -20 degC, outside the standard atmosphere's 15-35 degC (4.1.1.1): give "
                           "the room temperature (--reference-temperature; reference_temperature_degC in a plan)");
  }
  ScaleFactorTemperatureOptions named;
  named.reference_temperature_degC = 20.0;
  EXPECT_NEAR_RELATIVE(scale_factor_temperature_sensitivity(cold_first, named).scale_factor_temperature_sensitivity.value,
                       75.0, 1e-9);
  // A run in kelvin beside runs in degC (0.60 for 3.50 ppm/degC), or all of them (Tm 293.15 degC).
  auto kelvin = runs();
  kelvin[1].temperature_degC = 313.15;
  try {
    scale_factor_temperature_sensitivity(kelvin);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.message(), "scale factor temperature sensitivity: run 2: 313.15 degC is above 200 degC; is it in "
                           "kelvin? temperatures are in degC");
  }
  auto missing = runs();
  missing[1].points.pop_back();  // no static run at the end
  try {
    scale_factor_temperature_sensitivity(missing);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("run 2 (40 degC)"));
  }
}

}  // namespace
}  // namespace inertest
