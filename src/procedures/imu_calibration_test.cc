#include "inertest/procedures/imu_calibration.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/sim/imu_tumble.h"
#include "procedures/imu_calibration_internal.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

// A simulated hand-held tumble (sim/imu_tumble.h): 20 s still, then `orientations` rotations each
// followed by `still_s` still, at 100 Hz, in counts with offsets of 32768.
ImuRecord tumble(std::uint64_t seed, std::size_t orientations, double still_s = 6.0) {
  sim::ImuTumbleOptions options;
  options.orientations = orientations;
  options.still_s = still_s;
  return sim::simulate_imu_tumble(options, seed);
}

TEST(ImuCalibration, FindsTheStaticIntervalsOfATumble) {
  const ImuRecord record = tumble(1, 12);
  const StaticDetection detection = detect_static_intervals(record, {});
  const std::vector<StaticInterval>& intervals = detection.intervals;
  // 3 and 4 counts of white noise on each of three axes, rounded: 3 (9 + 1/12) and 3 (16 + 1/12).
  EXPECT_NEAR(detection.accelerometer_noise_variance, 27.25, 4.0);
  EXPECT_NEAR(detection.gyro_noise_variance, 48.25, 6.0);
  ASSERT_EQ(intervals.size(), 13u);
  for (const StaticInterval& interval : intervals) EXPECT_TRUE(interval.accepted) << interval.reason;
  // The windows' centres: half a window (0.5 s) inside the still 20 s.
  EXPECT_NEAR(intervals.front().start_s, 0.5, 1e-9);
  EXPECT_NEAR(intervals.front().end_s, 19.5, 0.1);
}

// A quiet IMU quantised to whole counts (0.2 counts of noise) has still windows of no variance at
// all: the noise is taken as at least the rounding's, 3 x 1/12 count^2, and the statics are found
// (a threshold multiple of 0 found none).
TEST(ImuCalibration, AQuietQuantisedRecordHasItsRoundingAsItsNoise) {
  sim::ImuTumbleOptions options;
  options.orientations = 12;
  options.accelerometer.noise = 0.2;
  options.gyro.noise = 0.2;
  const ImuRecord record = sim::simulate_imu_tumble(options, 3);
  const StaticDetection detection = detect_static_intervals(record, {});
  EXPECT_GE(detection.accelerometer_noise_variance, 0.25);
  EXPECT_GE(detection.gyro_noise_variance, 0.25);
  ASSERT_EQ(detection.intervals.size(), 13u);
  for (const StaticInterval& interval : detection.intervals) EXPECT_TRUE(interval.accepted) << interval.reason;
}

TEST(ImuCalibration, RefusesAShortStillAndSaysWhy) {
  ImuCalibrationOptions options;
  options.static_minimum_s = 7.0;
  const std::vector<StaticInterval> intervals = detect_static_intervals(tumble(2, 10), options).intervals;
  ASSERT_EQ(intervals.size(), 11u);
  EXPECT_TRUE(intervals.front().accepted);
  EXPECT_FALSE(intervals.back().accepted);
  EXPECT_NE(intervals.back().reason.find("shorter than the minimum 7 s"), std::string::npos) << intervals.back().reason;
}

// A static whose mean is off (the IMU touched while still: 200 counts, ~0.5 m/s^2, on x) is refused
// by the fit without it, says why, and the rest calibrate as without it.
TEST(ImuCalibration, RefusesATouchedStaticAndSaysWhy) {
  ImuRecord record = tumble(4, 20);
  const StaticInterval touched = detect_static_intervals(record, {}).intervals.at(5);
  for (std::size_t i = touched.first; i < touched.last; ++i) record.accelerometer[0][i] += 200.0;
  const ImuCalibrationResult result = calibrate_imu(record, {});
  const StaticInterval& refused = result.static_intervals.at(5);
  EXPECT_FALSE(refused.accepted);
  EXPECT_NE(refused.reason.find("the IMU moved or was touched"), std::string::npos) << refused.reason;
  std::size_t accepted = 0;
  for (const StaticInterval& interval : result.static_intervals) accepted += interval.accepted ? 1 : 0;
  EXPECT_EQ(accepted, result.static_intervals.size() - 1);
  const sim::ImuTumbleOptions made;
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(result.accelerometer.scale_factor[j], made.accelerometer.scale_factor[j],
                4.5 * result.accelerometer.scale_factor_uncertainty[j]);
  }
}

// The gyro's integration is fourth order: a coning motion R(t) = Rz(a(t)) Rx(b(t)) with smooth a and
// b (body rate (b', a' sin b, a' cos b), its axis moving), sampled at N steps over 2 s, is turned
// through with an error that falls 16 times when N doubles (2^4: 9.1e-5, 6.5e-6, 4.3e-7 rad at N = 20,
// 40, 80). The rate interpolated linearly to the steps' middles fell 4 times (second order: 6.8e-3,
// 1.7e-3, 4.2e-4 rad).
TEST(ImuCalibration, TheGyroIntegrationIsFourthOrder) {
  const auto a = [](double t) { return 1.2 * std::sin(1.3 * t); };
  const auto a_rate = [](double t) { return 1.2 * 1.3 * std::cos(1.3 * t); };
  const auto b = [](double t) { return 0.8 * t + 0.3 * t * t; };
  const auto b_rate = [](double t) { return 0.8 + 0.6 * t; };
  const auto error_with = [&](std::size_t steps) {
    ImuRecord record;
    for (std::size_t k = 0; k <= steps; ++k) {
      const double t = 2.0 * static_cast<double>(k) / static_cast<double>(steps);
      record.time_s.push_back(t);
      record.gyro[0].push_back(b_rate(t));
      record.gyro[1].push_back(a_rate(t) * std::sin(b(t)));
      record.gyro[2].push_back(a_rate(t) * std::cos(b(t)));
    }
    const Matrix3 identity{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    const Quaternion q = attitude_change(record, 0, steps, identity, {0.0, 0.0, 0.0});
    // The truth qz(a) (x) qx(b) at t = 2 s; the error is the angle of truth^-1 (x) q.
    const double ca = std::cos(a(2.0) / 2), sa = std::sin(a(2.0) / 2), cb = std::cos(b(2.0) / 2), sb = std::sin(b(2.0) / 2);
    const Quaternion truth{ca * cb, ca * sb, sa * sb, sa * cb};
    const double x = truth[0] * q[1] - truth[1] * q[0] - truth[2] * q[3] + truth[3] * q[2];
    const double y = truth[0] * q[2] + truth[1] * q[3] - truth[2] * q[0] - truth[3] * q[1];
    const double z = truth[0] * q[3] - truth[1] * q[2] + truth[2] * q[1] - truth[3] * q[0];
    return 2.0 * std::hypot(x, y, z);
  };
  const double e20 = error_with(20), e40 = error_with(40), e80 = error_with(80);
  RecordProperty("errors_rad", fmt::format("{:.3g} {:.3g} {:.3g}", e20, e40, e80));
  EXPECT_LT(e80, 1e-6);
  EXPECT_NEAR(e20 / e40, 16.0, 3.0);
  EXPECT_NEAR(e40 / e80, 16.0, 3.0);
}

// A calibration file states its units: a gyro scale factor in count/(deg/s) and a misalignment in mrad
// are converted to the count/(rad/s) and rad the model applies (imu-apply read the numbers as
// count/(rad/s) and rad: rates 57.3 times too large), and a unit of another kind is refused, naming it.
TEST(ImuCalibration, TheCalibrationFileIsReadInTheUnitsItStates) {
  const testing::ScratchDirectory scratch;
  const double degree = std::numbers::pi / 180.0;
  const auto file = [&](const std::string& gyro_scale_factor_unit) {
    return scratch.write("calibration.json", fmt::format(R"json({{
  "accelerometer": {{"bias": {{"value": [1, 2, 3], "unit": "count", "uncertainty": [0, 0, 0]}},
    "scale_factor": {{"value": [400, 410, 420], "unit": "count/(m/s^2)", "uncertainty": [0.1, 0.1, 0.1]}},
    "misalignment": {{"value": [[0, 0.004, 0], [0, 0, 0], [0, 0, 0]], "unit": "rad", "uncertainty": [[0, 0, 0], [0, 0, 0], [0, 0, 0]]}}}},
  "gyro": {{"bias": {{"value": [10, 20, 30], "unit": "count", "uncertainty": [0, 0, 0]}},
    "scale_factor": {{"value": [{}, 100, 100], "unit": "{}", "uncertainty": [0.5, 0.5, 0.5]}},
    "misalignment": {{"value": [[0, 12, 0], [0, 0, 0], [0, 0, 0]], "unit": "mrad", "uncertainty": [[0, 1, 0], [0, 0, 0], [0, 0, 0]]}}}}
}})json",
                                                         6258.0 * degree, gyro_scale_factor_unit));
  };
  const std::array<TriadCalibration, 2> triads = read_imu_calibration(file("count/(deg/s)")).triads;
  EXPECT_EQ(triads[0].scale_factor[1], 410.0);
  EXPECT_EQ(triads[0].misalignment[0][1], 0.004);
  const TriadCalibration& gyro = triads[1];
  EXPECT_NEAR(gyro.scale_factor[0], 6258.0, 1e-9);
  EXPECT_NEAR(gyro.scale_factor[1], 100.0 / degree, 1e-9);
  EXPECT_NEAR(gyro.scale_factor_uncertainty[1], 0.5 / degree, 1e-12);
  EXPECT_NEAR(gyro.misalignment[0][1], 0.012, 1e-15);
  EXPECT_NEAR(gyro.misalignment_uncertainty[0][1], 0.001, 1e-15);
  // 6258 counts above the bias on x: 1 rad/s, whatever unit the file gave the scale factor in.
  EXPECT_NEAR(gyro.apply({10.0 + 6258.0, 20.0, 30.0})[0], 1.0, 1e-12);
  try {
    read_imu_calibration(file("count/(m/s^2)"));
    FAIL() << "expected an Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("gyro.scale_factor: the unit 'count/(m/s^2)' does not convert to count/(rad/s)"),
              std::string::npos)
        << error.what();
  }
}

TEST(ImuCalibration, TooFewOrientationsIsAnErrorThatSaysSo) {
  try {
    calibrate_imu(tumble(3, 6), {});
    FAIL() << "expected an Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("7 static intervals accepted"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("at least 9 orientations"), std::string::npos) << error.what();
  }
}

// Nine orientations fit the accelerometer's nine parameters exactly: its uncertainties are not
// known, and neither the result nor the exported file states them (they said ±0). Ten leave one
// degree of freedom, and the warning says how seldom its sigma holds the truth (Student's t: 50 %).
TEST(ImuCalibration, AnExactFitStatesNoUncertainty) {
  const ImuCalibrationResult exact = calibrate_imu(tumble(3, 8), {});  // the first still and 8 more
  EXPECT_FALSE(exact.accelerometer.uncertainty_known);
  EXPECT_TRUE(exact.gyro.uncertainty_known);
  const nlohmann::json file = calibration_file_json(exact);
  EXPECT_FALSE(file.at("accelerometer").at("bias").contains("uncertainty"));
  EXPECT_FALSE(file.at("accelerometer").at("misalignment").contains("uncertainty"));
  EXPECT_TRUE(file.at("gyro").at("bias").contains("uncertainty"));
  EXPECT_THAT(nlohmann::json(exact.warnings).dump(),
              ::testing::HasSubstr("the accelerometer fit has as many observations as parameters"));
  const ImuCalibrationResult one = calibrate_imu(tumble(3, 9), {});
  EXPECT_TRUE(one.accelerometer.uncertainty_known);
  EXPECT_THAT(nlohmann::json(one.warnings).dump(),
              ::testing::HasSubstr("the accelerometer fit has 1 degree of freedom: its 1-sigma uncertainties, estimated "
                                   "from so few residuals, hold the truth in about 50 % of calibrations"));
}

// The coverage test: over several seeds every parameter of both triads is recovered within its
// reported uncertainty as often as a normal error would be.
TEST(ImuCalibration, RecoversEveryParameterWithinItsUncertainty) {
  std::vector<double> z;
  const auto check = [&](double estimate, double uncertainty, double truth, const std::string& what) {
    ASSERT_GT(uncertainty, 0.0) << what;
    z.push_back((estimate - truth) / uncertainty);
    EXPECT_LT(std::abs(z.back()), 4.5) << what << " " << estimate << " +- " << uncertainty << " truth " << truth;
  };
  for (unsigned seed = 10; seed < 18; ++seed) {
    const ImuCalibrationResult result = calibrate_imu(tumble(seed, 20), {});
    EXPECT_LT(result.accelerometer_residual_rms_m_s2, 0.003);
    const sim::ImuTumbleOptions made;
    for (const auto& [triad, truth, name, off_diagonal] :
         {std::tuple{&result.accelerometer, &made.accelerometer, "accelerometer", std::vector<std::pair<int, int>>{{0, 1}, {0, 2}, {1, 2}}},
          std::tuple{&result.gyro, &made.gyro, "gyro", std::vector<std::pair<int, int>>{{0, 1}, {0, 2}, {1, 0}, {1, 2}, {2, 0}, {2, 1}}}}) {
      for (int j = 0; j < 3; ++j) {
        check(triad->bias[j], triad->bias_uncertainty[j], truth->bias[j] + made.offset, fmt::format("{} seed {} bias {}", name, seed, j));
        check(triad->scale_factor[j], triad->scale_factor_uncertainty[j], truth->scale_factor[j],
              fmt::format("{} seed {} scale factor {}", name, seed, j));
      }
      for (const auto& [i, j] : off_diagonal) {
        check(triad->misalignment[i][j], triad->misalignment_uncertainty[i][j], truth->misalignment[i][j],
              fmt::format("{} seed {} misalignment {}{}", name, seed, i, j));
      }
    }
  }
  double squares = 0.0;
  std::size_t within = 0;
  for (double v : z) {
    squares += v * v;
    within += std::abs(v) <= 2.0 ? 1 : 0;
  }
  const double rms = std::sqrt(squares / static_cast<double>(z.size()));
  RecordProperty("z_rms", std::to_string(rms));
  RecordProperty("within_2_sigma", std::to_string(static_cast<double>(within) / static_cast<double>(z.size())));
  // 8 seeds x 21 parameters: the rms of z near 1 and about 95 % within 2 sigma.
  EXPECT_GT(rms, 0.6);
  EXPECT_LT(rms, 1.5);
  EXPECT_GT(static_cast<double>(within) / static_cast<double>(z.size()), 0.88);
}

// A gyro axis of reversed polarity, and an analog gyro (0.0143 V per rad/s): each scale factor with
// its sign (GJB 2426A 5.7). The search over positive scales of 0.1 to 1e8 per rad/s gave 3.6 count
// per rad/s and 0.45 rad of misalignment for the first, and nonsense for the second, silently.
TEST(ImuCalibration, AReversedAxisAndAnAnalogGyroAreFoundWithTheirSigns) {
  for (const auto& [name, scale_factor, noise] :
       {std::tuple{"reversed x", Vector3{-6258.0, 6190.0, 6320.0}, 4.0},
        std::tuple{"analog", Vector3{0.0143, -0.0139, 0.0151}, 1e-5}}) {
    sim::ImuTumbleOptions options;
    options.gyro.scale_factor = scale_factor;
    options.gyro.noise = noise;
    options.gyro.bias = {0.0, 0.0, 0.0};
    options.offset = 0.0;
    options.quantised = false;
    const ImuCalibrationResult result = calibrate_imu(sim::simulate_imu_tumble(options, 21), {});
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(result.gyro.scale_factor[j], scale_factor[j], 5.0 * result.gyro.scale_factor_uncertainty[j])
          << name << " axis " << j;
    }
    EXPECT_LT(result.gyro_residual_rms_rad, 1e-3) << name;
    EXPECT_TRUE(result.warnings.empty()) << name;
  }
  // Two reversed gyro axes: the same record as a reversed accelerometer axis, and the result says so.
  sim::ImuTumbleOptions two;
  two.gyro.scale_factor = {6258.0, -6190.0, -6320.0};
  const ImuCalibrationResult mirrored = calibrate_imu(sim::simulate_imu_tumble(two, 21), {});
  EXPECT_LT(mirrored.gyro.scale_factor[1], 0.0);
  EXPECT_TRUE(std::any_of(mirrored.warnings.begin(), mirrored.warnings.end(), [](const std::string& w) {
    return w.find("the accelerometer's x axis is reversed (gravity cannot tell)") != std::string::npos;
  }));
  // Gyro columns swapped (y read as x): no calibration describes the record, and the result says so.
  ImuRecord swapped = tumble(22, 20);
  std::swap(swapped.gyro[0], swapped.gyro[1]);
  const ImuCalibrationResult result = calibrate_imu(swapped, {});
  EXPECT_GT(result.gyro_residual_rms_rad, 0.05);
  EXPECT_TRUE(std::any_of(result.warnings.begin(), result.warnings.end(),
                          [](const std::string& w) { return w.find("does not describe this record") != std::string::npos; }));
}

// The record as h5py writes it: a dataset per column, each with its `units` (a variable-length string).
void write_hdf5(const std::string& path, const ImuRecord& record, const std::array<const char*, 7>& units) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const std::array<const std::vector<double>*, 7> columns = {&record.time_s,      &record.accelerometer[0],
                                                             &record.accelerometer[1], &record.accelerometer[2],
                                                             &record.gyro[0],     &record.gyro[1], &record.gyro[2]};
  const std::array<const char*, 7> names = {"time", "ax", "ay", "az", "gx", "gy", "gz"};
  const hid_t text = H5Tcopy(H5T_C_S1);
  H5Tset_size(text, static_cast<std::size_t>(-1));  // H5T_VARIABLE
  H5Tset_cset(text, H5T_CSET_UTF8);
  for (std::size_t c = 0; c < 7; ++c) {
    const hsize_t count = columns[c]->size();
    const hid_t space = H5Screate_simple(1, &count, nullptr);
    const hid_t dataset = H5Dcreate2(file, names[c], H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(dataset, H5T_NATIVE_DOUBLE, 0, 0, H5P_DEFAULT, columns[c]->data());  // 0: H5S_ALL
    const hid_t scalar = H5Screate(H5S_SCALAR);
    const hid_t attribute = H5Acreate2(dataset, "units", text, scalar, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attribute, text, &units[c]);
    H5Aclose(attribute);
    H5Sclose(scalar);
    H5Dclose(dataset);
    H5Sclose(space);
  }
  H5Tclose(text);
  H5Fclose(file);
}

// An IMU that logs m/s^2 and deg/s and says so in its file: the calibration is in those units (it
// reported 57.3 count/(rad/s)), and a unit given that contradicts them is an error naming both.
TEST(ImuCalibration, TheUnitsARecordStoresAreItsOutputUnits) {
  sim::ImuTumbleOptions options;
  options.accelerometer.scale_factor = {1.0, 1.0, 1.0};
  options.accelerometer.bias = {0.01, -0.02, 0.03};
  options.accelerometer.noise = 0.002;
  options.gyro.scale_factor = {180.0 / std::numbers::pi, 180.0 / std::numbers::pi, 180.0 / std::numbers::pi};
  options.gyro.bias = {0.1, -0.05, 0.02};
  options.gyro.noise = 0.01;
  options.offset = 0.0;
  options.quantised = false;
  const testing::ScratchDirectory scratch;
  const std::string path = scratch.path() + "/imu.h5";
  write_hdf5(path, sim::simulate_imu_tumble(options, 23), {"s", "m/s^2", "m/s^2", "m/s^2", "deg/s", "deg/s", "deg/s"});
  const std::vector<std::string> command = {"imu-calibration", path, "--columns", "time,ax,ay,az,gx,gy,gz", "--json"};
  const testing::CliRun run = testing::run_cli(command);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json gyro = nlohmann::json::parse(run.out).at("gyro").at("scale_factor");
  EXPECT_EQ(gyro.at("unit"), "deg/s/(rad/s)");
  EXPECT_NEAR(gyro.at("value").at(0).get<double>(), 180.0 / std::numbers::pi, 0.05);
  EXPECT_EQ(nlohmann::json::parse(run.out).at("accelerometer").at("scale_factor").at("unit"), "m/s^2/(m/s^2)");
  // count, given, contradicts too: it is the default only of a record that stores no unit.
  for (const char* given : {"rad/s", "count"}) {
    std::vector<std::string> contradicting = command;
    contradicting.insert(contradicting.end(), {"--gyro-unit", given});
    const testing::CliRun refused = testing::run_cli(contradicting);
    EXPECT_EQ(refused.exit_code, 2);
    EXPECT_THAT(refused.err, ::testing::HasSubstr(fmt::format("{}: the gyro unit given, {}, contradicts the unit deg/s "
                                                              "the record stores for its channels",
                                                              path, given)));
  }
  // A calibration labelled count (made before records' units were read) applies, and says so.
  const testing::CliRun applied = testing::run_cli({"imu-apply", testing::source_path("examples/imu_calibration/calibration.json"),
                                                    path, "--columns", "time,ax,ay,az,gx,gy,gz", "--json"});
  ASSERT_EQ(applied.exit_code, 0) << applied.err;
  EXPECT_THAT(nlohmann::json::parse(applied.out).at("warnings").dump(),
              ::testing::HasSubstr("the calibration's gyro output unit is count, the record's deg/s"));
  // One unit spelled two ways, or stated on one channel only, is the triad's; two units are an error.
  write_hdf5(path, sim::simulate_imu_tumble(options, 23), {"s", "m/s^2", "", "", "deg/s", "°/s", "deg/s"});
  const testing::CliRun spelled = testing::run_cli(command);
  ASSERT_EQ(spelled.exit_code, 0) << spelled.err;
  EXPECT_EQ(nlohmann::json::parse(spelled.out).at("accelerometer").at("scale_factor").at("unit"), "m/s^2/(m/s^2)");
  write_hdf5(path, sim::simulate_imu_tumble(options, 23), {"s", "m/s^2", "m/s^2", "m/s^2", "deg/s", "rad/s", "deg/s"});
  EXPECT_THAT(testing::run_cli(command).err,
              ::testing::HasSubstr("the gyro channels store different units (deg/s, rad/s, deg/s)"));
}

TEST(ImuCalibration, AnUnknownOutputUnitIsAParameterError) {
  for (const auto& [parameter, member] : {std::pair{"accelerometer_unit", &ImuCalibrationOptions::accelerometer_unit},
                                          std::pair{"gyro_unit", &ImuCalibrationOptions::gyro_unit}}) {
    ImuCalibrationOptions options;
    options.*member = "furlong";
    try {
      options.validate();
      ADD_FAILURE() << parameter << " accepted 'furlong'";
    } catch (const ParameterError& e) {
      EXPECT_EQ(e.parameter, parameter);
      EXPECT_THAT(e.message(), ::testing::StartsWith("unknown unit 'furlong' in 'furlong'"));
    }
    options.*member = "mV";
    EXPECT_NO_THROW(options.validate());
  }
}

// The record without samples [first, last), as a logger that dropped them leaves it.
ImuRecord without(ImuRecord record, std::size_t first, std::size_t last) {
  const auto cut = [&](auto& column) {
    column.erase(column.begin() + static_cast<std::ptrdiff_t>(first), column.begin() + static_cast<std::ptrdiff_t>(last));
  };
  cut(record.time_s);
  cut(record.lines);
  for (int j = 0; j < 3; ++j) {
    cut(record.accelerometer[j]);
    cut(record.gyro[j]);
  }
  return record;
}

TEST(ImuCalibration, AGapInARotationIsAnErrorAtItsLineAndElsewhereAWarning) {
  ImuRecord record = tumble(12, 12);
  record.source = "tumble.csv";
  for (std::size_t i = 0; i < record.time_s.size(); ++i) record.lines.push_back(i + 2);  // under a header line
  const StaticDetection detection = detect_static_intervals(record, {});
  ASSERT_GE(detection.intervals.size(), 3u);
  // 20 samples (0.2 s) dropped in the middle of the first rotation: the turn made then is lost.
  const std::size_t middle = (detection.intervals[0].last + detection.intervals[1].first) / 2;
  const ImuRecord rotation_gap = without(record, middle, middle + 20);
  try {
    calibrate_imu(rotation_gap, {});
    ADD_FAILURE() << "a gap inside a rotation was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.location()->to_string(), fmt::format("tumble.csv:{}", middle + 22));
    EXPECT_THAT(e.message(), ::testing::HasSubstr(fmt::format(
                                 "a gap in the time stamps: {:.6g} s to {:.6g} s, 20 sample(s) of 0.01 s missing, inside "
                                 "the rotation from the static interval ending at",
                                 record.time_s[middle - 1], record.time_s[middle + 20])));
  }
  // The same gap in a static interval changes no rotation: the calibration stands, with a warning.
  const StaticInterval& still = detection.intervals[2];
  const std::size_t inside = (still.first + still.last) / 2;
  const ImuCalibrationResult result = calibrate_imu(without(record, inside, inside + 20), {});
  const ImuCalibrationResult whole = calibrate_imu(record, {});
  EXPECT_THAT(result.warnings,
              ::testing::Contains(fmt::format("a gap in the time stamps: {:.6g} s to {:.6g} s, 20 sample(s) of 0.01 s missing before line {}, "
                        "outside the rotations the gyro's fit integrates",
                        record.time_s[inside - 1], record.time_s[inside + 20], inside + 22)));
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(result.gyro.scale_factor[j], whole.gyro.scale_factor[j], whole.gyro.scale_factor_uncertainty[j]);
  }
}

// Samples [first, last) of a record.
ImuRecord slice(const ImuRecord& record, std::size_t first, std::size_t last) {
  ImuRecord part;
  part.source = record.source;
  const auto cut = [&](const std::vector<double>& column) {
    return std::vector<double>(column.begin() + static_cast<std::ptrdiff_t>(first),
                               column.begin() + static_cast<std::ptrdiff_t>(last));
  };
  part.time_s = cut(record.time_s);
  for (int j = 0; j < 3; ++j) {
    part.accelerometer[j] = cut(record.accelerometer[j]);
    part.gyro[j] = cut(record.gyro[j]);
  }
  return part;
}

// The Xsens MTi tumble published with the method's paper (data/imu_tumble/README.md), in raw counts,
// against this unit's calibration by its maker as the authors' MATLAB scripts give it: gains 415,
// 413, 415 count/(m/s^2) and 4778, 4758, 4766 count/(rad/s) (to three figures, +-0.12 %), and the
// accelerometer offsets 33123, 33276, 32360 counts. The biases are also held to an independent fit
// of the accelerometer (scipy's least_squares on the same static means: 33123.8, 33275.2, 32364.5
// counts), and the two halves of the record must calibrate alike within their uncertainties.
TEST(ImuCalibration, RealXsensMtiRecord) {
  const std::string path = testing::source_path("data/imu_tumble/xsens_mti_tumble.mat");
  ImuCalibrationOptions options;
  options.gravity_m_s2 = 9.81744;  // the authors' setting for this record
  const ImuRecord record = read_imu_record(path, options.columns);
  ASSERT_EQ(record.time_s.size(), 51175u);
  const ImuCalibrationResult result = calibrate_imu(record, options);
  std::size_t accepted = 0;
  for (const StaticInterval& interval : result.static_intervals) accepted += interval.accepted ? 1 : 0;
  EXPECT_GE(accepted, 30u);
  EXPECT_LT(result.accelerometer_residual_rms_m_s2, 0.002);  // 2e-4 of g
  const Vector3 maker_accelerometer{415.0, 413.0, 415.0}, maker_gyro{4778.0, 4758.0, 4766.0};
  const Vector3 bias{33123.8, 33275.2, 32364.5}, maker_offset{33123.0, 33276.0, 32360.0};
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR_RELATIVE(result.accelerometer.scale_factor[j], maker_accelerometer[j], 0.005);
    EXPECT_NEAR_RELATIVE(result.gyro.scale_factor[j], maker_gyro[j], 0.005);
    EXPECT_NEAR(result.accelerometer.bias[j], bias[j], 0.5) << j;
    EXPECT_NEAR(result.accelerometer.bias[j], maker_offset[j], 5.0) << j;  // 0.8, -0.8, 4.5 counts off
    EXPECT_LT(result.accelerometer.scale_factor_uncertainty[j], 0.05) << j;
    EXPECT_LT(result.accelerometer.bias_uncertainty[j], 0.5) << j;
  }
  const ImuCalibrationResult first = calibrate_imu(slice(record, 0, record.time_s.size() / 2), options);
  const ImuCalibrationResult second = calibrate_imu(slice(record, record.time_s.size() / 2, record.time_s.size()), options);
  for (int j = 0; j < 3; ++j) {
    const auto agree = [](double a, double sa, double b, double sb) { return std::abs(a - b) / std::hypot(sa, sb); };
    EXPECT_LT(agree(first.accelerometer.scale_factor[j], first.accelerometer.scale_factor_uncertainty[j],
                    second.accelerometer.scale_factor[j], second.accelerometer.scale_factor_uncertainty[j]),
              3.0)
        << j << ": " << first.accelerometer.scale_factor[j] << " " << second.accelerometer.scale_factor[j];
    EXPECT_LT(agree(first.accelerometer.bias[j], first.accelerometer.bias_uncertainty[j], second.accelerometer.bias[j],
                    second.accelerometer.bias_uncertainty[j]),
              3.0)
        << j << ": " << first.accelerometer.bias[j] << " " << second.accelerometer.bias[j];
    EXPECT_LT(agree(first.gyro.scale_factor[j], first.gyro.scale_factor_uncertainty[j], second.gyro.scale_factor[j],
                    second.gyro.scale_factor_uncertainty[j]),
              3.0)
        << j << ": " << first.gyro.scale_factor[j] << " " << second.gyro.scale_factor[j];
  }
}

}  // namespace
}  // namespace inertest
