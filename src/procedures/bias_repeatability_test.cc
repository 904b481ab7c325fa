#include "inertest/procedures/bias_repeatability.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <limits>

#include "inertest/core/error.h"
#include "inertest/procedures/bias_temperature_sensitivity.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

TEST(BiasRepeatabilityTest, HandComputed) {
  const std::vector<double> biases = {1, 2, 3, 4, 5, 6};
  const auto result = bias_repeatability(biases);
  EXPECT_NEAR(result.bias_repeatability.value, std::sqrt(17.5 / 5.0), 1e-14);  // eq. (21)
  EXPECT_DOUBLE_EQ(result.mean_bias.value, 3.5);
  EXPECT_TRUE(result.warnings.empty());
  EXPECT_EQ(find_procedure_spec("bias_repeatability")->fields_of(&result).at("bias_repeatability").at("unit"), "deg/h");
}

TEST(BiasRepeatabilityTest, FewerThanSixRunsWarnsFewerThanTwoFails) {
  EXPECT_EQ(bias_repeatability(std::vector<double>{1.0, 2.0}).warnings.size(), 1u);
  EXPECT_THROW(bias_repeatability(std::vector<double>{1.0}), Error);
  EXPECT_THROW(bias_repeatability(std::vector<double>{}), Error);
  EXPECT_THROW(bias_repeatability(std::vector<double>{1.0, std::numeric_limits<double>::quiet_NaN()}), Error);
}

TEST(BiasTemperatureSensitivityTest, HandComputedFirstRunIsRoom) {
  const std::vector<TemperatureRunBias> runs = {{20.0, 1.0}, {-40.0, 2.2}, {60.0, 0.0}};
  const auto result = bias_temperature_sensitivity(runs);
  // |2.2 - 1| / 60 = 0.02, |0 - 1| / 40 = 0.025 (eq. 22).
  EXPECT_NEAR(result.bias_temperature_sensitivity.value, 0.025, 1e-15);
  EXPECT_EQ(result.bias_temperature_sensitivity.unit, "deg/h/degC");
  EXPECT_DOUBLE_EQ(result.worst_temperature.value, 60.0);
  EXPECT_DOUBLE_EQ(result.room_temperature.value, 20.0);
}

TEST(BiasTemperatureSensitivityTest, RoomTemperatureChosenByValue) {
  const std::vector<TemperatureRunBias> runs = {{-40.0, 2.2}, {20.0, 1.0}, {60.0, 0.0}};
  const auto result = bias_temperature_sensitivity(runs, {20.0});
  EXPECT_NEAR(result.bias_temperature_sensitivity.value, 0.025, 1e-15);
  EXPECT_DOUBLE_EQ(result.room_temperature_bias.value, 1.0);
}

TEST(BiasTemperatureSensitivityTest, BadInputIsAnError) {
  EXPECT_THROW(bias_temperature_sensitivity(std::vector<TemperatureRunBias>{{20.0, 1.0}}), Error);
  EXPECT_THROW(bias_temperature_sensitivity(std::vector<TemperatureRunBias>{{20.0, 1.0}, {20.0, 2.0}}), Error);
  EXPECT_THROW(bias_temperature_sensitivity(std::vector<TemperatureRunBias>{{20.0, 1.0}, {30.0, 2.0}}, {25.0}), Error);
  // -400 for -40 degC: Bt was computed over 420 degC.
  try {
    bias_temperature_sensitivity(std::vector<TemperatureRunBias>{{20.0, 1.0}, {-400.0, 2.0}});
    ADD_FAILURE() << "a run below absolute zero was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.message(), "bias temperature sensitivity: run 2: -400 degC is below absolute zero");
  }
}

// Runs listed cold to hot made the coldest one the room-temperature run, Bt 2.2 times too small; a
// run in kelvin beside runs in degC divided Bt by up to 9. Both are errors saying what to give.
TEST(BiasTemperatureSensitivityTest, AFirstRunOutsideRoomTemperatureOrKelvinIsAnError) {
  const std::vector<TemperatureRunBias> cold_first = {{-40.0, 2.2}, {20.0, 1.0}, {60.0, 0.0}};
  try {
    bias_temperature_sensitivity(cold_first);
    ADD_FAILURE() << "the -40 degC run was taken as the room-temperature run";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), ::testing::HasSubstr("the first run, taken as the room-temperature run (5.12.4.3 a), is at "
                                                  "-40 degC, outside the standard atmosphere's 15-35 degC (4.1.1.1)"));
  }
  EXPECT_NO_THROW(bias_temperature_sensitivity(std::vector<TemperatureRunBias>{{15.0, 1.0}, {60.0, 0.0}}));
  EXPECT_NO_THROW(bias_temperature_sensitivity(std::vector<TemperatureRunBias>{{35.0, 1.0}, {-40.0, 0.0}}));
  try {
    bias_temperature_sensitivity(std::vector<TemperatureRunBias>{{25.0, 1.0}, {333.15, 2.0}});
    ADD_FAILURE() << "a run in kelvin was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.message(), "bias temperature sensitivity: run 2: 333.15 degC is above 200 degC; is it in kelvin? "
                           "temperatures are in degC");
  }
}

}  // namespace
}  // namespace inertest
