// The temperature model (issue 20) on records whose truth follows from how they were made: the
// simulator's chamber ramps over many seeds (every coefficient within its reported uncertainty as
// often as a normal error is, the compensated residual at the simulated noise floor, a model
// without dT/dt failing on the same data), the smoothed rate of a quantised ramp, the export's round
// trip and temperature-apply through the declared command.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <regex>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "inertest/campaign/campaign.h"
#include "inertest/procedures/temperature_model.h"
#include "inertest/sim/thermal_model.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;

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
  // Its hysteresis D_H takes up the Shupe term (heating and cooling differ in the sign of dT/dt): far
  // outside its own sigma. (D_0 shifts too, by 0.65 of its sigma on seed 7: the Shupe term left in
  // the residuals is a persistent error, which the covariance counts as one, least_squares.cc.)
  const std::map<std::string, double> truth = true_coefficients(gyro);
  for (const ThermalCoefficient& c : static_only.coefficients) {
    if (c.name == "D_H") {
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
    // Applied with another K, the record's bias is in another scale: said (it was silent).
    const testing::CliRun other_k = testing::run_cli(
        {"temperature-apply", record, "--coefficients", coefficients, "--scale-factor", "1", "--json"});
    ASSERT_EQ(other_k.exit_code, 0) << other_k.err;
    EXPECT_EQ(applied.at("warnings"), nlohmann::json::array());
    EXPECT_EQ(nlohmann::json::parse(other_k.out).at("warnings"),
              (nlohmann::json{"the coefficients were fitted with a scale factor K of 36000, and are applied with 1 "
                              "(output units per deg/s): the bias is read in another scale"}));
    if (std::string(name) != "coefficients.csv") continue;
    // The settings of a .csv in the units their rows state (they were read as degC, s and degC/min
    // whatever the row said: 293.15 K as 293.15 degC made the residual 0.55 deg/h for 0.0098).
    const std::string exported = testing::read_file(coefficients);
    const ThermalCompensation restated = read_thermal_compensation(scratch.write(
        "restated.csv", std::regex_replace(std::regex_replace(std::regex_replace(exported,
                            std::regex("reference_temperature,([0-9.]+),degC,"), "reference_temperature,293.15,K,"),
                            std::regex("rate_window,([0-9.]+),s,"), "rate_window,2,min,"),
                            std::regex("soak_rate,([0-9.]+),degC/min,"), "soak_rate,0.5,K/s,")));
    EXPECT_NEAR(restated.reference_temperature_degC, 20.0, 1e-12);
    EXPECT_EQ(restated.rate_window_s, 120.0);
    EXPECT_EQ(restated.soak_rate_degC_per_min, 30.0);
    // A unit cell left blank (a file written by hand): the export's unit.
    const ThermalCompensation blank = read_thermal_compensation(scratch.write(
        "blank.csv", std::regex_replace(exported, std::regex("rate_window,([0-9.]+),s,"), "rate_window,90,,")));
    EXPECT_EQ(blank.rate_window_s, 90.0);
    const std::string banana = scratch.write(
        "banana.csv", std::regex_replace(exported, std::regex("rate_window,([0-9.]+),s,"), "rate_window,2,banana,"));
    try {
      read_thermal_compensation(banana);
      ADD_FAILURE() << "expected an error";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr(banana + ":5:15: rate_window: unknown unit 'banana'"));
    }
  }
}

// A logger's gap (300 s lost in the first ramp) is said with its size; the fit bridges it, and D_0 stays
// within its sigma of the gapless record's (the samples lost are 5 % of the record).
TEST(TemperatureModel, AGapInTheRecordIsSaid) {
  const sim::ThermalGyroParameters gyro;
  sim::Random random(5);
  const ThermalRecord whole = thermal_record(sim::simulate_thermal_record(short_chamber(), gyro, random));
  ThermalRecord gapped = whole;
  gapped.time_s.clear();
  gapped.output.clear();
  for (auto& sensor : gapped.temperature_degC) sensor.clear();
  std::size_t missing = 0;
  for (std::size_t i = 0; i < whole.time_s.size(); ++i) {
    if (whole.time_s[i] >= 1200.0 && whole.time_s[i] < 1500.0) {
      ++missing;
      continue;
    }
    gapped.time_s.push_back(whole.time_s[i]);
    gapped.output.push_back(whole.output[i]);
    for (std::size_t s = 0; s < whole.temperature_degC.size(); ++s) {
      gapped.temperature_degC[s].push_back(whole.temperature_degC[s][i]);
    }
  }
  TemperatureModelOptions options;
  options.scale_factor = gyro.scale_factor;
  const TemperatureModelResult full = temperature_model(whole, options);
  const TemperatureModelResult result = temperature_model(gapped, options);
  const auto gap_warning = [](const TemperatureModelResult& r) {
    return std::find_if(r.warnings.begin(), r.warnings.end(),
                        [](const std::string& w) { return w.find("gap(s) in the time stamps") != std::string::npos; });
  };
  EXPECT_EQ(gap_warning(full), full.warnings.end());
  ASSERT_NE(gap_warning(result), result.warnings.end());
  EXPECT_THAT(*gap_warning(result), HasSubstr(fmt::format("1 gap(s) in the time stamps, {} sample(s) of", missing)));
  ASSERT_EQ(result.coefficients.front().name, "D_0");
  EXPECT_NEAR(result.coefficients.front().value.value, full.coefficients.front().value.value,
              *full.coefficients.front().value.uncertainty);
  // temperature-apply on the same record says it too.
  ThermalCompensation compensation;
  compensation.sensor = full.sensor;
  compensation.coefficients = full.coefficients;
  const TemperatureApplyResult applied = apply_thermal_compensation(gapped, compensation, options);
  EXPECT_THAT(applied.warnings, ::testing::Contains(*gap_warning(result)));
}

// A temperature column whose name states kelvin ("coil_K", "chamber [K]") is read in kelvin: the
// same record in K gives the same model (it was read as degC: T_ref at 20 K, D_0 2.14 for 0.02 deg/h).
TEST(TemperatureModel, ATemperatureColumnInKelvinIsReadSo) {
  const sim::ThermalGyroParameters gyro;
  sim::Random random(5);
  const sim::ThermalRecordSamples samples = sim::simulate_thermal_record(short_chamber(), gyro, random);
  const testing::ScratchDirectory scratch;
  const std::string celsius = sim::thermal_record_csv(samples);
  // The same record with its coil temperature in kelvin, named so.
  std::string kelvin = "time,output,coil [K],chamber\n";
  for (std::size_t i = 0; i < samples.time_s.size(); ++i) {
    kelvin += fmt::format("{},{},{},{}\n", samples.time_s[i], samples.output[i], samples.coil_degC[i] + 273.15,
                          samples.chamber_degC[i]);
  }
  const auto model = [&](const std::string& name, const std::string& text, const std::string& column) {
    const testing::CliRun run = testing::run_cli({"temperature-model", scratch.write(name, text), "--temperature-column",
                                                  column, "--scale-factor", "36000", "--json"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(run.out);
  };
  const nlohmann::json in_celsius = model("c.csv", celsius, "coil");
  const nlohmann::json in_kelvin = model("k.csv", kelvin, "coil [K]");
  std::string spelt = kelvin;
  spelt.replace(spelt.find("coil [K]"), 8, "coil (kelvin)");
  EXPECT_EQ(model("spelt.csv", spelt, "coil (kelvin)").at("bias_coefficients"), in_kelvin.at("bias_coefficients"));
  // Kelvin in a column not named so is no degC: an error at the first cell above 200 degC.
  std::string unnamed = kelvin;
  unnamed.replace(unnamed.find("coil [K]"), 8, "coil");
  const testing::CliRun run = testing::run_cli({"temperature-model", scratch.write("unnamed.csv", unnamed),
                                                "--temperature-column", "coil", "--scale-factor", "36000"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, ::testing::HasSubstr("unnamed.csv:2:"));
  EXPECT_THAT(run.err, ::testing::HasSubstr("degC is above 200 degC: is the column in kelvin? name it with its unit "
                                            "(coil_K, \"coil [K]\")"));
  // T_ref outside the record's temperatures is said to be an extrapolation.
  const testing::CliRun hot = testing::run_cli({"temperature-model", scratch.write("hot.csv", celsius), "--temperature-column",
                                                "coil", "--scale-factor", "36000", "--reference-temperature", "150", "--json"});
  ASSERT_EQ(hot.exit_code, 0) << hot.err;
  EXPECT_THAT(nlohmann::json::parse(hot.out).at("warnings").dump(),
              ::testing::HasSubstr("the reference temperature 150 degC lies outside the record's"));
  for (const auto& [name, figure] : in_celsius.at("bias_coefficients").items()) {
    EXPECT_NEAR(in_kelvin.at("bias_coefficients").at(name).at("value").get<double>(), figure.at("value").get<double>(),
                1e-6 * std::abs(figure.at("value").get<double>()) + 1e-12)
        << name;
  }
}

// A sensor's fault code in one row (-999) bent the model silently; it is an error at its cell.
TEST(TemperatureModel, ATemperatureBelowAbsoluteZeroIsAnErrorAtItsCell) {
  const testing::ScratchDirectory scratch;
  const std::string record =
      scratch.write("ramp.csv", "time,output,coil\n0,1,20\n1,1,20.1\n2,1,-999\n3,1,20.3\n");
  const testing::CliRun model =
      testing::run_cli({"temperature-model", record, "--temperature-column", "coil", "--scale-factor", "36000"});
  EXPECT_EQ(model.exit_code, 2);
  EXPECT_THAT(model.err, ::testing::HasSubstr(record + ":4:5: -999 degC is below absolute zero"));
}

// An exported model of order 2 with the rate terms and the hysteresis, in either form; `edit` changes
// the coefficient rows (name, value, unit) before they are written.
struct CoefficientRow {
  std::string name;
  double value;
  std::string unit;
};

std::vector<CoefficientRow> order_two_rows() {
  return {{"D_0", 0.02, "deg/h"},           {"D_T", 0.003, "deg/h/degC"},
          {"D_T2", 4e-5, "deg/h/degC^2"},   {"D_dT", 0.03, "deg/h/(degC/min)"},
          {"D_TdT", 4e-4, "deg/h/degC/(degC/min)"}, {"D_H", 0.003, "deg/h"}};
}

std::string coefficients_json(const std::vector<CoefficientRow>& rows, bool with_order = true) {
  nlohmann::json coefficients = nlohmann::json::object();
  for (const auto& row : rows) coefficients[row.name] = {{"value", row.value}, {"unit", row.unit}, {"uncertainty", 1e-6}};
  nlohmann::json json{{"model", "inertest temperature model"}, {"sensor", "coil"}, {"reference_temperature_degC", 20.0},
                      {"rate_window_s", 600.0}, {"soak_rate_degC_per_min", 0.05}, {"coefficients", coefficients}};
  if (with_order) json["order"] = 2;
  return json.dump(2);
}

std::string coefficients_csv(const std::vector<CoefficientRow>& rows, bool with_order = true) {
  std::string text = "name,value,unit,uncertainty\nsensor,coil,,\n";
  if (with_order) text += "order,2,,\n";
  text += "reference_temperature,20,degC,\nrate_window,600,s,\nsoak_rate,0.05,degC/min,\n";
  for (const auto& row : rows) text += fmt::format("{},{},{},1e-6\n", row.name, row.value, row.unit);
  return text;
}

std::string read_error(const std::string& path) {
  try {
    read_thermal_compensation(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(TemperatureModel, CoefficientsOfAnotherNameAreAnErrorNamingTheFile) {
  const testing::ScratchDirectory scratch;
  std::vector<CoefficientRow> rows = order_two_rows();
  rows.back().name = "D_X";
  const std::string json = scratch.write("typo.json", coefficients_json(rows));
  EXPECT_EQ(read_error(json), json + ": coefficients.D_X: unknown coefficient 'D_X' (the model's are D_0, D_T, "
                                     "D_T2 ... D_T6, D_dT, D_TdT and D_H)");
  const std::string csv = scratch.write("typo.csv", coefficients_csv(rows));
  EXPECT_THAT(read_error(csv), HasSubstr(csv + ":12:1: coefficient D_X: unknown coefficient 'D_X'"));
  // Names the old reader took apart by their digits (std::stod threw or read a power it was not given).
  for (const char* name : {"D_T2x", "D_T7", "D_Tx"}) {
    rows.back().name = name;
    EXPECT_THAT(read_error(scratch.write("typo.json", coefficients_json(rows))), HasSubstr("unknown coefficient"));
  }
  rows.back().name = "D_T";
  const std::string twice = scratch.write("twice.csv", coefficients_csv(rows));
  EXPECT_EQ(read_error(twice), twice + ":12:1: coefficient 'D_T' is given twice");
  const std::vector<ThermalCoefficient> unknown{{"D_X", {1.0, "deg/h", std::nullopt}}};
  EXPECT_THROW(thermal_bias_deg_h(unknown, 20.0, 30.0, 0.0, 0), Error);
}

TEST(TemperatureModel, CoefficientsAreConvertedFromTheirUnits) {
  const testing::ScratchDirectory scratch;
  std::vector<CoefficientRow> rows = order_two_rows();
  rows[1] = {"D_T", 0.003 / 3600.0, "deg/s/degC"};     // the same D_T in deg/s/degC
  rows[2] = {"D_T2", 4e-5, "deg/h/K^2"};              // a kelvin of difference is a degC: no change
  rows[3] = {"D_dT", 0.03 * 60.0, "deg/h/(degC/s)"};  // per degC/s: 60 times the value per degC/min
  for (const std::string& path : {scratch.write("units.json", coefficients_json(rows)),
                                  scratch.write("units.csv", coefficients_csv(rows))}) {
    const ThermalCompensation read = read_thermal_compensation(path);
    std::map<std::string, Figure> by_name;
    for (const ThermalCoefficient& c : read.coefficients) by_name[c.name] = c.value;
    EXPECT_NEAR(by_name.at("D_T").value, 0.003, 1e-15) << path;
    EXPECT_EQ(by_name.at("D_T").unit, "deg/h/degC");
    EXPECT_NEAR(*by_name.at("D_T").uncertainty, 3600e-6, 1e-15);
    EXPECT_NEAR(by_name.at("D_T2").value, 4e-5, 1e-18);
    EXPECT_NEAR(by_name.at("D_dT").value, 0.03, 1e-15);
    EXPECT_NEAR(*by_name.at("D_dT").uncertainty, 1e-6 / 60.0, 1e-18);
  }
  rows[1] = {"D_T", 0.003, "deg/h"};  // not per degree
  const std::string json = scratch.write("wrong.json", coefficients_json(rows));
  EXPECT_THAT(read_error(json), HasSubstr(json + ": coefficients.D_T: the unit 'deg/h' of D_T is not one of deg/h/degC: "
                                                 "cannot convert"));
  const std::string csv = scratch.write("wrong.csv", coefficients_csv(rows));
  EXPECT_THAT(read_error(csv), HasSubstr(csv + ":8:11: coefficient D_T: the unit 'deg/h' of D_T"));
  rows[1] = {"D_T", 0.003, "furlong"};
  EXPECT_THAT(read_error(scratch.write("wrong.json", coefficients_json(rows))), HasSubstr("the unit 'furlong' of D_T"));
  rows[1] = {"D_T", 0.003, ""};
  const std::string no_unit = scratch.write("no_unit.csv", coefficients_csv(rows));
  EXPECT_EQ(read_error(no_unit), no_unit + ":8:11: coefficient D_T: no unit (the model takes D_T in deg/h/degC)");
}

TEST(TemperatureModel, AMissingCoefficientIsAnError) {
  const testing::ScratchDirectory scratch;
  std::vector<CoefficientRow> rows = order_two_rows();
  rows.erase(rows.begin() + 2);  // D_T2 of the order 2 the file states
  for (const std::string& path : {scratch.write("missing.json", coefficients_json(rows)),
                                  scratch.write("missing.csv", coefficients_csv(rows))}) {
    EXPECT_EQ(read_error(path), path + ": coefficients: D_T2 is missing (a model of order 2 has D_0, D_T ... D_T2)");
  }
  // Without a stated order (an older export) a gap in the powers still shows.
  rows = order_two_rows();
  rows.erase(rows.begin() + 1);  // D_T, with D_T2 given
  const std::string gap = scratch.write("gap.json", coefficients_json(rows, false));
  EXPECT_EQ(read_error(gap), gap + ": coefficients: D_T is missing (a model of order 2 has D_0, D_T ... D_T2)");
  rows = order_two_rows();
  rows.erase(rows.begin());
  EXPECT_THAT(read_error(scratch.write("no_constant.csv", coefficients_csv(rows, false))), HasSubstr("D_0 is missing"));
  rows = order_two_rows();
  rows.erase(rows.begin() + 4);  // D_TdT without D_dT
  EXPECT_THAT(read_error(scratch.write("half_rate.json", coefficients_json(rows))),
              HasSubstr("coefficients: D_TdT is missing (the rate terms D_dT and D_TdT come together)"));
  rows = order_two_rows();
  rows.push_back({"D_T3", 1e-7, "deg/h/degC^3"});
  EXPECT_THAT(read_error(scratch.write("beyond.json", coefficients_json(rows))),
              HasSubstr("coefficients: D_T3 is beyond the model's order 2"));
  // The complete file reads, with or without its order.
  EXPECT_EQ(read_thermal_compensation(scratch.write("whole.json", coefficients_json(order_two_rows(), false)))
                .coefficients.size(),
            6u);
  EXPECT_EQ(read_thermal_compensation(scratch.write("whole.csv", coefficients_csv(order_two_rows()))).coefficients.size(),
            6u);
}

TEST(TemperatureModel, ANonFiniteReferenceTemperatureIsAParameterError) {
  TemperatureModelOptions options;
  options.scale_factor = 36000.0;
  for (const double reference : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    options.reference_temperature_degC = reference;
    try {
      options.validate();
      ADD_FAILURE() << "accepted " << reference;
    } catch (const ParameterError& e) {
      EXPECT_EQ(e.parameter, "reference_temperature");
      EXPECT_EQ(e.message_naming("--reference-temperature"), "--reference-temperature must be finite");
    }
  }
  // In a plan, at its key, before anything runs.
  const testing::ScratchDirectory scratch;
  const std::string plan = scratch.write("plan.toml", R"([instrument]
id = "FOG-7"
output_unit = "pulse/s"

[[procedure]]
kind = "temperature_model"
file = "plan.toml"
scale_factor = 36000
temperature_column = ["coil"]
reference_temperature = nan
)");
  try {
    validate_plan(plan);
    ADD_FAILURE() << "the plan was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(plan + ":10:"));
    EXPECT_THAT(e.what(), HasSubstr("'reference_temperature' must be a finite number (not nan or inf)"));
  }
}

// [instrument] output_unit = "pulse": the chamber record's outputs are counts per sample interval
// (4 Hz), which both steps read as pulse/s at the record's mean rate, so counts a quarter of the
// rates give the rates' figures (K = nominal_scale_factor, pulse/s per deg/s).
TEST(TemperatureModel, PulseCountsOfTheInstrumentInAPlan) {
  sim::ThermalGyroParameters gyro;
  gyro.sample_rate_hz = 4.0;
  sim::Random random(5);
  sim::ThermalRecordSamples samples = sim::simulate_thermal_record(short_chamber(), gyro, random);
  const testing::ScratchDirectory scratch;
  scratch.write("rates.csv", sim::thermal_record_csv(samples));
  for (double& output : samples.output) output /= gyro.sample_rate_hz;
  scratch.write("counts.csv", sim::thermal_record_csv(samples));
  const auto results = [&](const std::string& unit, const std::string& records) {
    const std::string plan =
        scratch.write(records + ".toml",
                      fmt::format(R"([instrument]
id = "FOG-7"
output_unit = "{0}"
nominal_scale_factor = 36000

[[procedure]]
kind = "temperature_model"
file = "{1}.csv"
temperature_column = ["coil"]

[[procedure]]
kind = "temperature_apply"
file = "{1}.csv"
coefficients = "{2}"
)",
                                  unit, records, testing::source_path("examples/temperature_model/coefficients.json")));
    return run_campaign(plan, scratch.path() + "/" + records).results.at("procedures");
  };
  const nlohmann::json of_rates = results("pulse/s", "rates");
  const nlohmann::json of_counts = results("pulse", "counts");
  for (std::size_t step = 0; step < 2; ++step) {
    for (const char* figure : {"residual_bias_stability", "raw_bias_stability"}) {
      const double rates = of_rates.at(step).at("result").at(figure).at("value").get<double>();
      EXPECT_NEAR(of_counts.at(step).at("result").at(figure).at("value").get<double>(), rates, 1e-9 * rates)
          << step << " " << figure;
    }
  }
  const nlohmann::json& coefficients = of_rates.at(0).at("result").at("bias_coefficients");
  for (const auto& [name, coefficient] : coefficients.items()) {
    const double rates = coefficient.at("value").get<double>();
    EXPECT_NEAR(of_counts.at(0).at("result").at("bias_coefficients").at(name).at("value").get<double>(), rates,
                1e-9 * std::abs(rates))
        << name;
  }
  // Taken as pulse/s, the counts are a bias four times smaller.
  const double raw = of_rates.at(0).at("result").at("raw_bias_stability").at("value").get<double>();
  EXPECT_NEAR(results("pulse/s", "counts").at(0).at("result").at("raw_bias_stability").at("value").get<double>(),
              raw / 4.0, 1e-9 * raw);
}

// A bias that changes with temperature by less than the record resolves (D_T = 3e-5 deg/h/degC
// under 0.002 deg/sqrt(h) of noise): cross-validation chooses order 0 on these seeds, and the
// sensitivity is the order-1 fit's |D_T| with its 1-sigma (it was reported as 0 +- 0), within 3
// sigma of the truth (1.0e-4, 3.0e-6, 1.5e-5, 4.4e-5, 3.4e-5 +- 6.2e-5 .. 6.5e-5), with a warning
// saying the dependence is not resolved.
TEST(TemperatureModel, AnUnresolvedSensitivityIsTheOrderOneSlopeWithItsUncertainty) {
  sim::ThermalGyroParameters gyro;
  gyro.bias_polynomial_deg_h = {0.02, 3e-5};
  gyro.rate_deg_h_per_degC_min = 0.0;
  gyro.temperature_rate_deg_h_per_degC2_min = 0.0;
  gyro.hysteresis_deg_h = 0.0;
  gyro.angle_random_walk_deg_rt_h = 0.002;
  TemperatureModelOptions options;
  options.scale_factor = gyro.scale_factor;
  options.rate_terms = false;
  int order_zero = 0;
  for (int seed = 1; seed <= 5; ++seed) {
    sim::Random random(static_cast<std::uint64_t>(seed));
    const TemperatureModelResult result =
        temperature_model(thermal_record(sim::simulate_thermal_record(short_chamber(), gyro, random)), options);
    const Figure& sensitivity = result.bias_temperature_sensitivity;
    if (result.order != 0) continue;
    ++order_zero;
    ASSERT_TRUE(sensitivity.uncertainty.has_value());
    EXPECT_GT(*sensitivity.uncertainty, 0.0) << "seed " << seed;
    EXPECT_NEAR(sensitivity.value, 3e-5, 3.0 * *sensitivity.uncertainty) << "seed " << seed;
    ASSERT_FALSE(result.warnings.empty());
    EXPECT_THAT(result.warnings.back(), HasSubstr("cross-validation chose order 0"));
  }
  EXPECT_EQ(order_zero, 5);
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
  // Without the rate terms too: at one temperature D_0 is the bias there, not at T_ref (it ran with exit
  // 0, no warning, and gave the bias at 20 degC of a record held at 25 degC).
  for (double& t : record.temperature_degC[0]) t = 25.0;
  options.rate_terms = false;
  try {
    temperature_model(record, options);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("temperature sensor 'coil' reads 25 degC throughout the record"));
  }
}

}  // namespace
}  // namespace inertest
