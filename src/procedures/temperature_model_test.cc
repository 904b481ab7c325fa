// The temperature model (issue 20) on records whose truth follows from how they were made: the
// simulator's chamber ramps over many seeds (every coefficient within its reported uncertainty as
// often as a normal error is, the compensated residual at the simulated noise floor, a model
// without dT/dt failing on the same data), the smoothed rate of a quantised ramp, the export's round
// trip and temperature-apply through the declared command.
#include <cmath>
#include <map>

#include <nlohmann/json.hpp>

#include "inertest/procedures/temperature_model.h"
#include "inertest/sim/thermal_model.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

// A short chamber run: soaks of 900 s, 20 -> 50 -> -10 -> 20 degC at 1, 2 and 0.5 degC/min.
sim::ChamberProfile short_chamber() {
  sim::ChamberProfile chamber;
  chamber.set_points_degC = {50.0, -10.0, 20.0};
  chamber.ramps_degC_per_min = {1.0, 2.0, 0.5};
  chamber.soak_s = 900.0;
  return chamber;
}

ThermalRecord thermal_record(const sim::ThermalRecordSamples& samples) {
  return {samples.time_s, samples.output, {"coil", "chamber"}, {samples.coil_degC, samples.chamber_degC}};
}

std::map<std::string, double> true_coefficients(const sim::ThermalGyroParameters& gyro) {
  return {{"D_0", gyro.bias_polynomial_deg_h[0]},
          {"D_T", gyro.bias_polynomial_deg_h[1]},
          {"D_T2", gyro.bias_polynomial_deg_h[2]},
          {"D_dT", gyro.rate_deg_h_per_degC_min},
          {"D_TdT", gyro.temperature_rate_deg_h_per_degC2_min},
          {"D_H", gyro.hysteresis_deg_h}};
}

// The white noise's window means over the stability window: the floor a perfect model reaches.
double noise_floor_deg_h(const sim::ThermalGyroParameters& gyro, double window_s) {
  return gyro.sample_noise_deg_h() / std::sqrt(window_s * gyro.sample_rate_hz);
}

TEST(TemperatureModel, SmoothedRateOfAQuantisedRamp) {
  // 1.5 degC/min read by a 0.0625 degC sensor at 1 Hz: the local linear slope over 120 s recovers it to
  // the quantisation's q/sqrt(12)·sqrt(12/N³) per sample window, far below 1 %.
  std::vector<double> time, temperature;
  for (int i = 0; i < 1200; ++i) {
    time.push_back(i);
    temperature.push_back(std::round((20.0 + 1.5 / 60.0 * i) / 0.0625) * 0.0625);
  }
  const std::vector<double> rate = smoothed_rate_degC_per_min(time, temperature, 120.0);
  for (std::size_t i = 60; i + 60 < rate.size(); ++i) EXPECT_NEAR(rate[i], 1.5, 0.01) << i;
}

// Over 30 seeds, each coefficient's error in units of its reported sigma behaves as a standard
// normal's: at least 80 % within 2 sigma (expected 95 %) and an rms between 0.6 and 1.5. The
// compensated residual stability is within 4 of its sigmas of the noise floor on every seed and 1 %
// of it on the average; without the dT/dt terms the residual stays far above the floor.
TEST(TemperatureModel, RecoversEveryCoefficientOverSeeds) {
  const sim::ChamberProfile chamber = short_chamber();
  const sim::ThermalGyroParameters gyro;
  const std::map<std::string, double> truth = true_coefficients(gyro);
  TemperatureModelOptions options;
  options.scale_factor = gyro.scale_factor;
  options.reference_temperature_degC = gyro.reference_temperature_degC;
  const double floor = noise_floor_deg_h(gyro, options.stability_window_s);
  constexpr int kSeeds = 30;
  std::map<std::string, int> within_two_sigma;
  std::map<std::string, double> squared_z;
  std::map<std::string, int> fitted;
  double residual_ratio = 0.0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    sim::Random random(static_cast<std::uint64_t>(seed));
    const ThermalRecord record = thermal_record(sim::simulate_thermal_record(chamber, gyro, random));
    const TemperatureModelResult result = temperature_model(record, options);
    EXPECT_EQ(result.sensor, "coil") << "seed " << seed;
    EXPECT_GE(result.order, 2u) << "seed " << seed;
    for (const ThermalCoefficient& c : result.coefficients) {
      const double true_value = truth.contains(c.name) ? truth.at(c.name) : 0.0;
      const double z = (c.value.value - true_value) / *c.value.uncertainty;
      ++fitted[c.name];
      squared_z[c.name] += z * z;
      if (std::abs(z) <= 2.0) ++within_two_sigma[c.name];
    }
    EXPECT_NEAR(result.residual_bias_stability.value, floor, 4.0 * *result.residual_bias_stability.uncertainty)
        << "seed " << seed;
    residual_ratio += result.residual_bias_stability.value / floor / kSeeds;
    // The raw bias moves with temperature: its stability is many times the floor.
    EXPECT_GT(result.raw_bias_stability.value, 20.0 * floor);
  }
  for (const auto& [name, value] : truth) {
    ASSERT_EQ(fitted[name], kSeeds) << name;
    EXPECT_GE(within_two_sigma[name], 0.8 * kSeeds) << name;
    const double rms_z = std::sqrt(squared_z[name] / kSeeds);
    EXPECT_GT(rms_z, 0.6) << name;
    EXPECT_LT(rms_z, 1.5) << name;
  }
  EXPECT_NEAR(residual_ratio, 1.0, 0.05);
}

TEST(TemperatureModel, AModelWithoutTheRateFailsOnTheSameData) {
  const sim::ThermalGyroParameters gyro;
  sim::Random random(7);
  const ThermalRecord record = thermal_record(sim::simulate_thermal_record(short_chamber(), gyro, random));
  TemperatureModelOptions options;
  options.scale_factor = gyro.scale_factor;
  const double floor = noise_floor_deg_h(gyro, options.stability_window_s);
  const TemperatureModelResult full = temperature_model(record, options);
  options.rate_terms = false;
  const TemperatureModelResult static_only = temperature_model(record, options);
  EXPECT_LT(full.residual_bias_stability.value, 1.2 * floor);
  // Without D_dT and D_TdT the ramps leave their Shupe bias in the residual: several times the floor,
  // and a residual stability far outside the full model's uncertainty.
  EXPECT_GT(static_only.residual_bias_stability.value, 3.0 * floor);
  EXPECT_GT(static_only.residual_bias_stability.value - full.residual_bias_stability.value,
            10.0 * *full.residual_bias_stability.uncertainty);
  // Its hysteresis D_H takes up the Shupe term (heating and cooling differ in the sign of dT/dt), and
  // D_0 shifts: both far outside their own sigmas (about 45 and 15 on seed 7).
  const std::map<std::string, double> truth = true_coefficients(gyro);
  for (const ThermalCoefficient& c : static_only.coefficients) {
    if (c.name == "D_H" || c.name == "D_0") {
      EXPECT_GT(std::abs(c.value.value - truth.at(c.name)), 4.0 * *c.value.uncertainty) << c.name;
    }
  }
}

TEST(TemperatureModel, ExportAppliesToTheRecord) {
  const sim::ThermalGyroParameters gyro;
  sim::Random random(3);
  const sim::ThermalRecordSamples samples = sim::simulate_thermal_record(short_chamber(), gyro, random);
  const testing::ScratchDirectory scratch;
  const std::string record = scratch.write("ramp.csv", sim::thermal_record_csv(samples));
  for (const char* name : {"coefficients.json", "coefficients.csv"}) {
    const std::string coefficients = scratch.path() + "/" + name;
    const testing::CliRun model = testing::run_cli({"temperature-model", record, "--temperature-column", "coil",
                                                    "--scale-factor", "36000", "--export", coefficients, "--json"});
    ASSERT_EQ(model.exit_code, 0) << model.err;
    const ThermalCompensation read = read_thermal_compensation(coefficients);
    EXPECT_EQ(read.sensor, "coil");
    const nlohmann::json fitted = nlohmann::json::parse(model.out).at("bias_coefficients");
    ASSERT_EQ(read.coefficients.size(), fitted.size());
    for (const ThermalCoefficient& c : read.coefficients) {
      EXPECT_NEAR(c.value.value, fitted.at(c.name).at("value").get<double>(),
                  1e-6 * std::abs(fitted.at(c.name).at("value").get<double>()))
          << c.name;
    }
    const testing::CliRun apply = testing::run_cli(
        {"temperature-apply", record, "--coefficients", coefficients, "--scale-factor", "36000", "--json"});
    ASSERT_EQ(apply.exit_code, 0) << apply.err;
    const nlohmann::json applied = nlohmann::json::parse(apply.out);
    EXPECT_EQ(applied.at("temperature_sensor"), "coil");
    // The same record and windows: the residual stability temperature-model reported.
    EXPECT_NEAR(applied.at("residual_bias_stability").at("value").get<double>(),
                nlohmann::json::parse(model.out).at("residual_bias_stability").at("value").get<double>(), 1e-6);
  }
}

TEST(TemperatureModel, RefusesARecordWithoutRamps) {
  ThermalRecord record{{}, {}, {"coil"}, {{}}};
  for (int i = 0; i < 4000; ++i) {
    record.time_s.push_back(i);
    record.output.push_back(std::sin(i * 0.1));
    record.temperature_degC[0].push_back(20.0);
  }
  TemperatureModelOptions options;
  options.scale_factor = 36000.0;
  EXPECT_THROW(temperature_model(record, options), Error);
}

}  // namespace
}  // namespace inertest
