// imu-apply (procedures/imu_apply_spec.cc) through the command: what it writes.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "inertest/sim/imu_tumble.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

// imu-apply on a record too short for its check leaves no --output file (it wrote the calibrated
// record first, then failed).
TEST(ImuApply, AFailureWritesNoOutput) {
  const testing::ScratchDirectory scratch;
  const std::string tumble_csv = testing::read_file(testing::source_path("examples/imu_calibration/tumble.csv"));
  std::string head;
  for (std::size_t at = 0, lines = 0; lines < 31; ++lines) {
    const std::size_t end = tumble_csv.find('\n', at) + 1;
    head += tumble_csv.substr(at, end - at);
    at = end;
  }
  const std::string record = scratch.write("short.csv", head);
  const std::string output = scratch.path() + "/calibrated.csv";
  const testing::CliRun run = testing::run_cli({"imu-apply", testing::source_path("examples/imu_calibration/calibration.json"),
                                                record, "--output", output});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "inertest: error: " + record + ": 30 samples: too short for a 1 s moving-variance window of 25 samples\n");
  EXPECT_FALSE(std::filesystem::exists(output));
  // The whole record: the file is written.
  const testing::CliRun whole = testing::run_cli({"imu-apply", testing::source_path("examples/imu_calibration/calibration.json"),
                                                  testing::source_path("examples/imu_calibration/tumble.csv"), "--output",
                                                  output, "--json"});
  EXPECT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_TRUE(std::filesystem::exists(output));
}

// The calibrated record keeps its time stamps to a microsecond: epoch seconds (1.7e9 s) written to
// 9 digits were 100 s apart, 32 653 rows under 34 times.
TEST(ImuApply, TheOutputKeepsEveryTimeStamp) {
  const testing::ScratchDirectory scratch;
  const std::string tumble_csv = testing::read_file(testing::source_path("examples/imu_calibration/tumble.csv"));
  std::string epoch;
  std::vector<std::string> stamps;
  for (std::size_t at = 0; at < tumble_csv.size();) {
    const std::size_t end = tumble_csv.find('\n', at);
    const std::string line = tumble_csv.substr(at, end - at);
    at = end + 1;
    const std::size_t comma = line.find(',');
    if (stamps.empty() && epoch.empty()) {
      epoch += line + "\n";  // the header
      stamps.push_back("time_s");
      continue;
    }
    stamps.push_back(fmt::format("{}", 1732700000.0 + std::stod(line.substr(0, comma))));
    epoch += stamps.back() + line.substr(comma) + "\n";
  }
  const std::string output = scratch.path() + "/calibrated.csv";
  const testing::CliRun run = testing::run_cli({"imu-apply", testing::source_path("examples/imu_calibration/calibration.json"),
                                                scratch.write("epoch.csv", epoch), "--output", output});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string written = testing::read_file(output);
  std::size_t row = 0;
  for (std::size_t at = 0; at < written.size(); ++row) {
    const std::size_t end = written.find('\n', at);
    ASSERT_LT(row, stamps.size());
    const std::string stamp = written.substr(at, written.find(',', at) - at);
    if (row == 0) {
      EXPECT_EQ(stamp, stamps[row]);
    } else {
      EXPECT_NEAR(std::stod(stamp), std::stod(stamps[row]), 1e-6) << "row " << row;  // a microsecond
    }
    at = end + 1;
  }
  EXPECT_EQ(row, stamps.size());
}

// A record that is never still checks nothing: the check's figures are absent (a limit on them
// fails), not 0 (which passed every limit).
TEST(ImuApply, ARecordWithoutStaticsGivesNoCheckFigures) {
  const testing::ScratchDirectory scratch;
  sim::ImuTumbleOptions moving;  // rotation after rotation, never held still
  moving.first_still_s = 0.0;
  moving.still_s = 0.0;
  moving.sample_rate_hz = 25.0;
  const ImuRecord made = sim::simulate_imu_tumble(moving, 5);
  std::string record = "time_s,ax,ay,az,gx,gy,gz\n";
  for (std::size_t i = 0; i < made.time_s.size(); ++i) {
    record += fmt::format("{:.2f},{},{},{},{},{},{}\n", made.time_s[i], made.accelerometer[0][i], made.accelerometer[1][i],
                          made.accelerometer[2][i], made.gyro[0][i], made.gyro[1][i], made.gyro[2][i]);
  }
  const testing::CliRun run = testing::run_cli({"imu-apply", testing::source_path("examples/imu_calibration/calibration.json"),
                                                scratch.write("moving.csv", record), "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json result = nlohmann::json::parse(run.out);
  EXPECT_EQ(result.at("static_intervals"), 0);
  EXPECT_FALSE(result.contains("gravity_residual_rms"));
  EXPECT_FALSE(result.contains("rest_rate_rms"));
  EXPECT_THAT(result.at("warnings").dump(), ::testing::HasSubstr("no static interval in the record"));
}

// In a plan a relative --output goes beside results.json (staged with the campaign's other files: a
// failing later step leaves none), not in the working directory.
TEST(ImuApply, APlanWritesTheOutputBesideItsResults) {
  const testing::ScratchDirectory scratch;
  const std::string step = "[[procedure]]\nkind = \"imu_apply\"\ncalibration = \"" +
                           testing::source_path("examples/imu_calibration/calibration.json") + "\"\nfile = \"" +
                           testing::source_path("examples/imu_calibration/tumble.csv") +
                           "\"\noutput = \"calibrated/cal.csv\"\n";
  const std::string plan = scratch.write("plan.toml", "[instrument]\nid = \"IMU-1\"\n" + step);
  const testing::CliRun run = testing::run_cli({"run", plan, "--out", scratch.path() + "/out"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(std::filesystem::exists(scratch.path() + "/out/calibrated/cal.csv"));
  const std::string failing = scratch.write(
      "failing.toml", "[instrument]\nid = \"IMU-1\"\n" + step + "[[procedure]]\nkind = \"bias\"\nfile = \"" +
                          scratch.write("short.txt", "1\n") + "\"\nsample_rate_hz = 1\ninput = \"deg/h\"\n");
  EXPECT_EQ(testing::run_cli({"run", failing, "--out", scratch.path() + "/failed"}).exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(scratch.path() + "/failed"));
}

// A calibration states the gravity it was made at, and imu-apply checks at it: the example tumble (made at
// 9.80665 m/s^2) calibrated at 9.81744 has scale factors 0.11 % small, which its statics hold at 9.81744
// (checked at the default 9.80665, every static read the difference: a residual of 0.0108 m/s^2). Given
// another gravity, the check is at it, with a warning naming both.
TEST(ImuApply, ChecksAtTheGravityOfTheCalibration) {
  const testing::ScratchDirectory scratch;
  const std::string tumble = testing::source_path("examples/imu_calibration/tumble.csv");
  const std::string calibration = scratch.path() + "/calibration.json";
  ASSERT_EQ(testing::run_cli({"imu-calibration", tumble, "--gravity", "9.81744", "--export", calibration}).exit_code,
            0);
  EXPECT_EQ(nlohmann::json::parse(testing::read_file(calibration)).at("gravity"),
            (nlohmann::json{{"value", 9.81744}, {"unit", "m/s^2"}}));
  const auto applied = [&](std::vector<std::string> arguments) {
    arguments.insert(arguments.begin(), {"imu-apply", calibration, tumble, "--json"});
    const testing::CliRun run = testing::run_cli(arguments);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(run.out);
  };
  const nlohmann::json own = applied({});
  EXPECT_LT(own.at("gravity_residual_rms").at("value").get<double>(), 1e-3);
  EXPECT_EQ(own.at("warnings"), nlohmann::json::array());
  const nlohmann::json standard = applied({"--gravity", "9.80665"});
  EXPECT_NEAR(standard.at("gravity_residual_rms").at("value").get<double>(), 9.81744 - 9.80665, 5e-4);
  EXPECT_EQ(standard.at("warnings"),
            (nlohmann::json{"the calibration was made at a gravity of 9.81744 m/s^2, and is checked here at 9.80665 "
                            "m/s^2: the gravity residual holds the difference"}));
  // imu-calibration's --json output states no gravity: the standard one, said.
  const testing::CliRun printed = testing::run_cli({"imu-calibration", tumble, "--json"});
  ASSERT_EQ(printed.exit_code, 0) << printed.err;
  const testing::CliRun unstated =
      testing::run_cli({"imu-apply", scratch.write("printed.json", printed.out), tumble, "--json"});
  ASSERT_EQ(unstated.exit_code, 0) << unstated.err;
  EXPECT_THAT(nlohmann::json::parse(unstated.out).at("warnings").at(0).get<std::string>(),
              ::testing::StartsWith("the calibration states no gravity (imu-calibration's --json output"));
}

// Units of a calibration and of the record it is applied to. The example tumble (25 Hz) with its gyro
// as counts per sample interval (the samples / 25), calibrated with --gyro-unit pulse: the
// calibration is in pulse/s, and the record must say what it holds (its counts taken as pulse/s gave
// a rest rate of 8.7 rad/s). A calibration in count applies to samples in any unit as they are, one
// in pulse (made before pulses were read as pulse/s) to samples in pulse, each with a warning.
TEST(ImuApply, TheRecordsUnitsAgainstTheCalibrations) {
  const testing::ScratchDirectory scratch;
  const std::string counts = testing::write_example_with(scratch, "examples/imu_calibration/tumble.csv", "counts.csv",
                                                         {4, 5, 6}, [](double rate) { return rate / 25.0; });
  const std::string tumble = testing::source_path("examples/imu_calibration/tumble.csv");
  const std::string calibration = scratch.path() + "/calibration.json";
  const testing::CliRun made =
      testing::run_cli({"imu-calibration", counts, "--gyro-unit", "pulse", "--export", calibration, "--json"});
  ASSERT_EQ(made.exit_code, 0) << made.err;
  EXPECT_EQ(nlohmann::json::parse(made.out).at("gyro").at("bias").at("unit"), "pulse/s");
  const auto rest_rate = [](const testing::CliRun& run) {
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(run.out).at("rest_rate_rms").at("value").get<double>();
  };
  const double of_counts =
      rest_rate(testing::run_cli({"imu-apply", calibration, counts, "--gyro-unit", "pulse", "--json"}));
  EXPECT_LT(of_counts, 1e-3);  // rad/s: the tumble's statics are at rest
  EXPECT_NEAR(rest_rate(testing::run_cli({"imu-apply", calibration, tumble, "--gyro-unit", "pulse/s", "--json"})),
              of_counts, 1e-9);
  // imu-apply CALIB RECORD [ARGUMENTS] fails with `message` about RECORD.
  const auto refused = [](const std::string& calib, const std::string& record, std::vector<std::string> arguments,
                          const std::string& message) {
    arguments.insert(arguments.begin(), {"imu-apply", calib, record});
    const testing::CliRun run = testing::run_cli(arguments);
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "inertest: error: " + record + ": " + message + "\n");
  };
  refused(calibration, counts, {},
          "the calibration's gyro output unit is pulse/s and the record states none: give it (--gyro-unit pulse for "
          "counts per sample interval, pulse/s for rates; gyro_unit)");
  refused(calibration, counts, {"--gyro-unit", "deg/s"},
          "the record's gyro output unit is deg/s, the calibration's pulse/s: give the record's unit (--gyro-unit; "
          "gyro_unit) or a calibration made in it");
  // The example calibration in count (made before records' units were read) applies to a record in
  // any unit, as it is, and says so.
  const testing::CliRun count =
      testing::run_cli({"imu-apply", testing::source_path("examples/imu_calibration/calibration.json"), tumble,
                        "--gyro-unit", "pulse", "--json"});
  ASSERT_EQ(count.exit_code, 0) << count.err;
  EXPECT_NE(count.out.find("the calibration's gyro output unit is count, the record's pulse"), std::string::npos)
      << count.out;
  // The same calibration labelled pulse, as made before: applied to counts as they are, not to rates.
  nlohmann::json before = nlohmann::json::parse(testing::read_file(calibration));
  for (const auto& [key, unit] : {std::pair{"bias", "pulse"}, std::pair{"scale_factor", "pulse/(rad/s)"}}) {
    nlohmann::json& figure = before.at("gyro").at(key);
    figure.at("unit") = unit;
    for (auto& value : figure.at("value")) value = value.get<double>() / 25.0;
  }
  const std::string old = scratch.write("before.json", before.dump());
  const testing::CliRun legacy = testing::run_cli({"imu-apply", old, counts, "--json"});
  EXPECT_NEAR(rest_rate(legacy), of_counts, 1e-9);
  EXPECT_NE(legacy.out.find("the calibration's gyro output unit is pulse, counts per sample interval (made before "
                            "imu-calibration read them as pulse/s)"),
            std::string::npos)
      << legacy.out;
  refused(old, tumble, {"--gyro-unit", "pulse/s"},
          "the record's gyro output unit is pulse/s, the calibration's pulse: give the record's unit (--gyro-unit; "
          "gyro_unit) or a calibration made in it");
}

}  // namespace
}  // namespace inertest
