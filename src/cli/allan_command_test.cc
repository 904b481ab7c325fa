// The allan command's contract: `inertest allan FILE --rate HZ ... --json`.
#include <gtest/gtest.h>

#include <bit>
#include <cstdio>
#include <fmt/format.h>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <tuple>

#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;
using testing::run_cli;

std::string white_record(double scale) {
  std::mt19937_64 random(3);
  std::normal_distribution<double> white(0.0, 1.0);
  std::string text;
  for (int i = 0; i < 4000; ++i) text += std::to_string(scale * (5.0 + white(random))) + "\n";
  return text;
}

// Raw output in units per deg/s, divided by K and reported in deg/h: the same as the record
// already converted to deg/h (K = 250 output/(deg/s): deg/h = raw * 3600 / 250).
TEST(AllanCommand, ScaleFactorTurnsRawOutputIntoDegreesPerHour) {
  testing::ScratchDirectory dir;
  const std::string raw = dir.write("raw.csv", white_record(250.0 / 3600.0));
  const std::string converted = dir.write("deg_h.csv", white_record(1.0));
  const auto scaled = run_cli({"allan", raw, "--rate", "100", "--scale-factor", "250", "--json"});
  const auto plain = run_cli({"allan", converted, "--rate", "100", "--input-unit", "deg/h", "--json"});
  ASSERT_EQ(scaled.exit_code, 0) << scaled.err;
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const auto a = nlohmann::json::parse(scaled.out);
  const auto b = nlohmann::json::parse(plain.out);
  EXPECT_EQ(a["input_unit"], "deg/h");
  ASSERT_EQ(a["oadev"]["values"].size(), b["oadev"]["values"].size());
  for (std::size_t i = 0; i < a["oadev"]["values"].size(); ++i) {
    // The text holds 6 decimals of each sample, so the two records differ in the last digits.
    EXPECT_NEAR_RELATIVE(a["oadev"]["values"][i].get<double>(), b["oadev"]["values"][i].get<double>(), 1e-4);
  }
  EXPECT_NEAR_RELATIVE(a["mean"]["value"].get<double>(), b["mean"]["value"].get<double>(), 1e-6);
  EXPECT_EQ(a["noise"]["angle_random_walk"]["unit"], "deg/sqrt(h)");
}

// Pulses counted per sample interval (--output-unit pulse) are pulse/s times the interval: at
// 100 Hz the counts of a record are a hundredth of its pulse/s, and give the same figures.
TEST(AllanCommand, PulseCountsPerSampleIntervalWithTheScaleFactor) {
  testing::ScratchDirectory dir;
  const std::string rates = dir.write("rates.csv", white_record(250.0 / 3600.0));
  const std::string counts = dir.write("counts.csv", white_record(250.0 / 3600.0 / 100.0));
  const auto of_rates = run_cli({"allan", rates, "--rate", "100", "--scale-factor", "250", "--json"});
  const auto of_counts =
      run_cli({"allan", counts, "--rate", "100", "--scale-factor", "250", "--output-unit", "pulse", "--json"});
  ASSERT_EQ(of_rates.exit_code, 0) << of_rates.err;
  ASSERT_EQ(of_counts.exit_code, 0) << of_counts.err;
  const auto a = nlohmann::json::parse(of_rates.out);
  const auto b = nlohmann::json::parse(of_counts.out);
  EXPECT_NEAR_RELATIVE(b["mean"]["value"].get<double>(), a["mean"]["value"].get<double>(), 1e-4);
  EXPECT_NEAR_RELATIVE(b["noise"]["angle_random_walk"]["value"].get<double>(),
                       a["noise"]["angle_random_walk"]["value"].get<double>(), 1e-3);  // 6 decimals of each count
  const auto without_k = run_cli({"allan", counts, "--rate", "100", "--output-unit", "pulse"});
  EXPECT_EQ(without_k.exit_code, 2);
  EXPECT_THAT(without_k.err, HasSubstr("--output-unit is the unit of the raw output that scale_factor divides"));
  const auto unknown = run_cli({"allan", counts, "--rate", "100", "--scale-factor", "250", "--output-unit", "pulsse"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_THAT(unknown.err, HasSubstr("pulsse"));
}

TEST(AllanCommand, ScaleFactorAndInputUnitExcludeEachOther) {
  testing::ScratchDirectory dir;
  const std::string raw = dir.write("raw.csv", white_record(1.0));
  const auto both = run_cli({"allan", raw, "--rate", "100", "--scale-factor", "250", "--input-unit", "deg/s"});
  EXPECT_NE(both.exit_code, 0);
  EXPECT_THAT(both.err, HasSubstr("--input-unit and scale_factor exclude each other"));
  const auto zero = run_cli({"allan", raw, "--rate", "100", "--scale-factor", "0", "--json"});
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_EQ(zero.out, "");
  EXPECT_THAT(zero.err, HasSubstr("--scale-factor must be finite and nonzero"));
}

TEST(AllanCommand, JsonHoldsEveryEstimatorWithItsEdfMethod) {
  testing::ScratchDirectory dir;
  const auto run = run_cli({"allan", dir.write("rate.csv", white_record(1.0)), "--rate", "10", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  for (const char* name : {"adev", "oadev", "mdev", "hdev", "ohdev", "totdev"}) {
    ASSERT_TRUE(json.contains(name)) << name;
    EXPECT_EQ(json[name]["values"].size(), json["tau"].size()) << name;
    EXPECT_FALSE(json[name]["edf_method"].get<std::string>().empty()) << name;
  }
  EXPECT_THAT(json["mdev"]["edf_method"].get<std::string>(), HasSubstr("Greenhall"));
}

// --estimators picks the curves; without OADEV, ADEV or TOTDEV there is no noise fit, and "noise"
// is null.
TEST(AllanCommand, EstimatorsPickTheCurvesAndNoiseIsNullWithoutAFit) {
  testing::ScratchDirectory dir;
  const auto run = run_cli({"allan", dir.write("rate.csv", white_record(1.0)), "--rate", "10", "--estimators",
                            "mdev,hdev", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_TRUE(json.contains("mdev") && json.contains("hdev"));
  EXPECT_FALSE(json.contains("oadev") || json.contains("adev") || json.contains("totdev"));
  ASSERT_TRUE(json.contains("noise"));
  EXPECT_TRUE(json["noise"].is_null());
}

TEST(AllanCommand, JsonOfAnF64Record) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("w.f64", testing::f64_bytes(testing::uniform_noise(10.0, 4096)));
  const auto run = testing::run_cli({"allan", path, "--rate", "100", "--format", "f64", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["tau"].size(), 11u);  // m = 1 .. 1024 <= 4096/3
  EXPECT_DOUBLE_EQ(json["tau"][0].get<double>(), 0.01);
  for (const char* name : {"adev", "oadev", "mdev", "hdev", "ohdev", "totdev"}) {
    ASSERT_TRUE(json.contains(name)) << name;
    EXPECT_EQ(json[name]["values"].size(), json["tau"].size());
    EXPECT_EQ(json[name]["lower"].size(), json["tau"].size());
    EXPECT_EQ(json[name]["upper"].size(), json["tau"].size());
    EXPECT_EQ(json[name]["unit"], "deg/h");
  }
  for (const char* name : {"quantization", "angle_random_walk", "bias_instability", "rate_random_walk", "rate_ramp"}) {
    EXPECT_TRUE(json["noise"][name].contains("unit")) << name;
  }
  EXPECT_EQ(json["noise"]["angle_random_walk"]["unit"], "deg/sqrt(h)");
  EXPECT_TRUE(json["noise"]["slope_method"].contains("angle_random_walk"));
}

// A counter logged as raw integers (pulse counts, i32 or i16, either byte order, named as the other
// commands name them), or the values as big-endian floats: the same figures as the same values
// stored as f64, bit for bit; a format no reader knows is an error at --format.
TEST(AllanCommand, IntegerRecordsOfEitherByteOrder) {
  testing::ScratchDirectory dir;
  std::vector<double> counts;
  std::string i32be;
  std::string i16;
  std::string f64be;
  std::string f32be;
  std::mt19937_64 random(3);
  std::uniform_int_distribution<int> count(-20000, 20000);
  for (int i = 0; i < 4096; ++i) {
    const int v = count(random);
    counts.push_back(v);
    for (int b = 3; b >= 0; --b) i32be += static_cast<char>((static_cast<std::uint32_t>(v) >> (8 * b)) & 0xFF);
    i16 += static_cast<char>(static_cast<std::uint16_t>(v) & 0xFF);
    i16 += static_cast<char>((static_cast<std::uint16_t>(v) >> 8) & 0xFF);
    const auto wide = std::bit_cast<std::uint64_t>(static_cast<double>(v));
    const auto narrow = std::bit_cast<std::uint32_t>(static_cast<float>(v));  // |v| <= 20000: exact
    for (int b = 7; b >= 0; --b) f64be += static_cast<char>((wide >> (8 * b)) & 0xFF);
    for (int b = 3; b >= 0; --b) f32be += static_cast<char>((narrow >> (8 * b)) & 0xFF);
  }
  const auto as_f64 = testing::run_cli({"allan", dir.write("c.f64", testing::f64_bytes(counts)), "--rate", "100",
                                        "--format", "f64", "--input-unit", "count", "--json"});
  ASSERT_EQ(as_f64.exit_code, 0) << as_f64.err;
  for (const auto& [name, bytes, format] : {std::tuple{"c.i32", i32be, "i32be"}, std::tuple{"c.i16", i16, "i16le"},
                                            std::tuple{"c2.i16", i16, "i16"}, std::tuple{"c.f64be", f64be, "f64be"},
                                            std::tuple{"c.f32be", f32be, "f32be"}}) {
    const auto run = testing::run_cli({"allan", dir.write(name, bytes), "--rate", "100", "--format", format,
                                       "--input-unit", "count", "--json"});
    ASSERT_EQ(run.exit_code, 0) << format << ": " << run.err;
    EXPECT_EQ(nlohmann::json::parse(run.out)["oadev"], nlohmann::json::parse(as_f64.out)["oadev"]) << format;
  }
  const auto unknown = testing::run_cli({"allan", dir.path() + "/c.i16", "--rate", "100", "--format", "u16"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_THAT(unknown.err, HasSubstr("--format: unknown record format 'u16' (expected auto, csv, mat, hdf5, tdms, or f64, "
                                     "f32, i32 or i16, optionally with le or be)"));
}

// --fit-range sets the taus of the eq. (30) fit; the JSON says who chose them, and the verdict.
TEST(AllanCommand, FitRangeIsTakenAndReported) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("rate.csv", white_record(1.0));
  auto run = run_cli({"allan", path, "--rate", "10", "--fit-range", "0.2:50", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  const auto& range = json["noise"]["fit"]["fit_range"];
  EXPECT_EQ(range["chosen_by"], "user");
  EXPECT_DOUBLE_EQ(range["tau_min_s"].get<double>(), 0.2);
  EXPECT_DOUBLE_EQ(range["tau_max_s"].get<double>(), 25.6);
  EXPECT_TRUE(json["noise"]["fit"]["reduced_chi_squared"].is_number());
  EXPECT_TRUE(json["noise"]["fit"]["verdict"].is_string());
  run = run_cli({"allan", path, "--rate", "10", "--json"});
  EXPECT_EQ(nlohmann::json::parse(run.out)["noise"]["fit"]["fit_range"]["chosen_by"], "automatic");
  run = run_cli({"allan", path, "--rate", "10", "--fit-range", "50"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("TMIN:TMAX"));
  run = run_cli({"allan", path, "--rate", "10", "--fit-range", "1000:2000"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("the fit needs at least 2"));
}

TEST(AllanCommand, ClearErrors) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("w.f64", testing::f64_bytes(testing::uniform_noise(10.0, 64)));
  auto run = testing::run_cli({"allan", path, "--rate", "0", "--format", "f64", "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("sample rate"));
  run = testing::run_cli({"allan", path, "--rate", "1", "--format", "f64", "--taus", "fortnightly"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("tau specification"));
  const std::string tiny = dir.write("tiny.f64", testing::f64_bytes(testing::uniform_noise(10.0, 2)));
  run = testing::run_cli({"allan", tiny, "--rate", "1", "--format", "f64"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("too few samples"));
}

// An IMU record: time and six channels, all streamed once; each channel's object is the
// single-channel JSON of that column, and an acceleration unit gives the accelerometer's terms.
std::string imu_record() {
  std::mt19937_64 random(7);
  std::normal_distribution<double> white(0.0, 1.0);
  std::string text = "time_s,gx,gy,gz,ax,ay,az\n";
  for (int i = 0; i < 3000; ++i) {
    text += fmt::format("{:.2f}", i / 100.0);
    for (int c = 0; c < 6; ++c) text += fmt::format(",{:.6f}", 0.1 * (c + 1) + white(random));
    text += "\n";
  }
  return text;
}

TEST(AllanCommand, ColumnsAnalyseEveryChannelInOnePassWithItsOwnUnit) {
  testing::ScratchDirectory dir;
  const std::string record = dir.write("imu.csv", imu_record());
  const auto all = run_cli({"allan", record, "--rate", "100", "--columns", "gx,gy,gz,ax,ay,az", "--input-unit",
                            "gx=deg/s,gy=deg/s,gz=deg/s,ax=m/s^2,ay=m/s^2,az=m/s^2", "--json"});
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const auto json = nlohmann::json::parse(all.out);
  ASSERT_EQ(json.at("channels").size(), 6u);
  const auto one = run_cli({"allan", record, "--rate", "100", "--column", "ay", "--input-unit", "m/s^2", "--json"});
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_EQ(json.at("channels").at("ay"), nlohmann::json::parse(one.out));
  EXPECT_EQ(json.at("channels").at("gz").at("input_unit"), "deg/s");
  EXPECT_TRUE(json.at("channels").at("ax").at("noise").contains("velocity_random_walk"));
  // By index, and the text report names each channel.
  const auto text = run_cli({"allan", record, "--rate", "100", "--columns", "2,5", "--input-unit", "deg/s,5=m/s^2"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("== channel gx =="));
  EXPECT_THAT(text.out, HasSubstr("velocity random walk N"));
}

// The README's IMU command on a record logged at 10 Hz: --rate 100 put every tau ten times short,
// without a word. The record's time column says 10 Hz, so the rate is refused, naming both; the
// rate the column shows is accepted, and without --rate the error says what the column shows.
TEST(AllanCommand, ARateTheTimeColumnContradictsIsAnError) {
  testing::ScratchDirectory dir;
  const std::string record = dir.write("imu.csv", imu_record());  // 100 Hz stamps
  const auto wrong = run_cli({"allan", record, "--rate", "10", "--columns", "gx,gy", "--json"});
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_THAT(wrong.err, HasSubstr("imu.csv:1: sample_rate_hz (--rate) 10 Hz contradicts the record's time column "
                                   "'time_s': its first 3000 stamps step 0.01 s (100 Hz)"));
  EXPECT_EQ(wrong.out, "");
  const auto one = run_cli({"allan", record, "--rate", "1000", "--column", "gx"});
  EXPECT_EQ(one.exit_code, 2);
  EXPECT_THAT(one.err, HasSubstr("contradicts the record's time column 'time_s'"));
  // Without --rate, the column named with its unit gives the rate, as bias takes it; a column
  // whose name does not state seconds does not, and the error says what it shows.
  const auto given = run_cli({"allan", record, "--rate", "100", "--column", "gx", "--json"});
  const auto stamped = run_cli({"allan", record, "--column", "gx", "--json"});
  ASSERT_EQ(stamped.exit_code, 0) << stamped.err;
  EXPECT_EQ(nlohmann::json::parse(stamped.out)["oadev"], nlohmann::json::parse(given.out)["oadev"]);
  EXPECT_EQ(nlohmann::json::parse(stamped.out)["sample_rate_hz"].get<double>(), 100.0);  // not 100.00000000000001
  std::string unstated = imu_record();
  unstated.replace(0, unstated.find(','), "time");
  const std::string ticks = dir.write("ticks.csv", unstated);
  const auto none = run_cli({"allan", ticks, "--column", "gx"});
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_THAT(none.err, HasSubstr("ticks.csv: the record stores no sample rate: give sample_rate_hz (--rate); its "
                                  "time column 'time' steps 0.01 s (100 Hz) if in s"));
}

TEST(AllanCommand, ExportWritesTheFilterParametersOrNothing) {
  testing::ScratchDirectory dir;
  const std::string record = dir.write("imu.csv", imu_record());
  const std::string yaml = dir.path() + "/imu.yaml";
  const auto kalibr = run_cli({"allan", record, "--rate", "100", "--columns", "gx,gy,gz,ax,ay,az", "--input-unit",
                               "deg/s,ax=m/s^2,ay=m/s^2,az=m/s^2", "--export", "kalibr", yaml, "--json"});
  ASSERT_EQ(kalibr.exit_code, 0) << kalibr.err;
  std::ifstream in(yaml);
  const std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_THAT(written, HasSubstr("gyroscope_noise_density: "));
  EXPECT_THAT(written, HasSubstr("accelerometer_random_walk: "));
  EXPECT_THAT(written, HasSubstr("update_rate: 100"));
  // The header's command gives the same file again: every parameter that made the numbers is in it.
  const std::string marker = "written by inertest: inertest ";
  const auto begin = written.find(marker);
  ASSERT_NE(begin, std::string::npos) << written;
  const std::string command = written.substr(begin + marker.size(), written.find('\n', begin) - begin - marker.size());
  EXPECT_THAT(command, HasSubstr("--input-unit deg/s,ax=m/s^2,ay=m/s^2,az=m/s^2"));
  std::vector<std::string> words;
  for (std::size_t at = 0; at <= command.size();) {
    const std::size_t end = std::min(command.find(' ', at), command.size());
    words.push_back(command.substr(at, end - at));
    at = end + 1;
  }
  ASSERT_EQ(run_cli(words).exit_code, 0) << command;
  std::ifstream again(yaml);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>()), written);
  // Channels in counts have no SI density: an error, and neither the file nor the JSON.
  const std::string refused = dir.path() + "/refused.yaml";
  const auto counts = run_cli({"allan", record, "--rate", "100", "--columns", "gx,ax", "--input-unit", "count",
                               "--export", "kalibr", refused, "--json"});
  EXPECT_EQ(counts.exit_code, 2);
  EXPECT_EQ(counts.out, "");
  EXPECT_THAT(counts.err, HasSubstr("channel gx: its unit count is neither an angular rate nor a specific force"));
  EXPECT_FALSE(std::ifstream(refused).good());
  const auto format = run_cli({"allan", record, "--rate", "100", "--column", "gx", "--export", "yaml", refused});
  EXPECT_EQ(format.exit_code, 2);
  EXPECT_THAT(format.err, HasSubstr("unknown export format 'yaml'"));
}

// An export onto the record it is made from (a slip of the shell's completion, or another path to
// the same file) is an error before anything is written: the record was replaced by the JSON.
TEST(AllanCommand, AnExportOntoItsOwnRecordIsRefused) {
  testing::ScratchDirectory dir;
  const std::string record = dir.write("imu.csv", imu_record());
  std::filesystem::create_directories(dir.path() + "/sub");
  for (const std::string& target : {record, dir.path() + "/sub/../imu.csv"}) {
    const auto over = run_cli({"allan", record, "--rate", "100", "--column", "gx", "--export", "json", target});
    EXPECT_EQ(over.exit_code, 2);
    EXPECT_THAT(over.err, HasSubstr("the export '" + target + "' would replace the input file"));
    EXPECT_EQ(over.out, "");
    EXPECT_EQ(testing::read_file(record), imu_record());
  }
}

TEST(AllanCommand, ColumnsReportAMissingChannelOrUnitByName) {
  testing::ScratchDirectory dir;
  const std::string record = dir.write("imu.csv", imu_record());
  const auto missing = run_cli({"allan", record, "--rate", "100", "--columns", "gx,mx", "--json"});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("mx"));
  const auto unit = run_cli({"allan", record, "--rate", "100", "--columns", "gx,ax", "--input-unit", "gz=deg/s"});
  EXPECT_EQ(unit.exit_code, 2);
  EXPECT_THAT(unit.err, HasSubstr("--input-unit names 'gz', which is not a channel asked for (gx, ax)"));
  const auto raw = dir.write("raw.f64", std::string(64, '\0'));
  const auto binary = run_cli({"allan", raw, "--format", "f64", "--rate", "100", "--columns", "1,2"});
  EXPECT_EQ(binary.exit_code, 2);
  EXPECT_THAT(binary.err, HasSubstr("holds one channel"));
  // A channel asked for twice would hide the first one's result under the same name.
  for (const char* twice : {"gx,gx", "2,gx"}) {
    const auto repeated = run_cli({"allan", record, "--rate", "100", "--columns", twice, "--json"});
    EXPECT_EQ(repeated.exit_code, 2) << twice;
    EXPECT_THAT(repeated.err, HasSubstr("channel 'gx' is asked for twice")) << twice;
  }
  // Units per channel need --columns; a raw record has no column to choose and is no text.
  const auto per_channel = run_cli({"allan", record, "--rate", "100", "--column", "gx", "--input-unit", "deg/s,ax=m/s^2"});
  EXPECT_EQ(per_channel.exit_code, 2);
  EXPECT_THAT(per_channel.err, HasSubstr("units per channel (deg/s,ax=m/s^2) need columns"));
  const auto column = run_cli({"allan", raw, "--format", "f64", "--rate", "100", "--column", "2"});
  EXPECT_EQ(column.exit_code, 2);
  EXPECT_THAT(column.err, HasSubstr("a raw binary record holds one channel: column does not apply"));
  const auto as_text = run_cli({"allan", raw, "--rate", "100"});
  EXPECT_EQ(as_text.exit_code, 2);
  EXPECT_THAT(as_text.err, HasSubstr("not text: a NUL byte at offset 0 (a binary record? give its format"));
}

// A list option takes one word (or --export its two), so FILE may come after it.
// A record of named channels (HDF5) stores each channel's rate and unit: allan takes them, for one
// channel and for several (which failed without --rate, and took deg/s samples for deg/h).
TEST(AllanCommand, ChannelsOfAnHdf5RecordAtTheirStoredRateAndUnit) {
  const std::string record = testing::source_path("data/lab_formats/record.h5");
  const auto one = run_cli({"allan", record, "--column", "imu/gyro_x", "--taus", "decade", "--json"});
  ASSERT_EQ(one.exit_code, 0) << one.err;
  // A stored rate is no raw output: a scale factor would divide its deg/h by K once more.
  const auto scaled = run_cli({"allan", record, "--column", "imu/gyro_x", "--scale-factor", "2"});
  EXPECT_EQ(scaled.exit_code, 2);
  EXPECT_THAT(scaled.err, HasSubstr("the record stores its samples in deg/h, not a raw output: scale_factor divides"));
  const auto single = nlohmann::json::parse(one.out);
  EXPECT_EQ(single["input_unit"], "deg/h");
  EXPECT_EQ(single["sample_rate_hz"], 200.0);
  const auto several = run_cli({"allan", record, "--columns", "imu/gyro_x", "--taus", "decade", "--json"});
  ASSERT_EQ(several.exit_code, 0) << several.err;
  EXPECT_EQ(nlohmann::json::parse(several.out)["channels"]["imu/gyro_x"], single);
  const auto contradicted = run_cli({"allan", record, "--columns", "imu/gyro_x", "--input-unit", "deg/s"});
  EXPECT_EQ(contradicted.exit_code, 2);
  EXPECT_THAT(contradicted.err,
              HasSubstr(record + ": the unit given, deg/s, contradicts the unit deg/h stored for channel 'imu/gyro_x'"));
  // The temperature channel stores no rate: one must be given, and then agree with the gyro's.
  const auto no_rate = run_cli({"allan", record, "--columns", "imu/gyro_x,imu/temperature"});
  EXPECT_EQ(no_rate.exit_code, 2);
  EXPECT_THAT(no_rate.err, HasSubstr("channel 'imu/temperature' stores no sample rate: give it"));
  const auto given = run_cli({"allan", record, "--columns", "imu/gyro_x,imu/temperature", "--rate", "200",
                              "--input-unit", "imu/temperature=degC", "--taus", "decade", "--json"});
  ASSERT_EQ(given.exit_code, 0) << given.err;
  EXPECT_EQ(nlohmann::json::parse(given.out)["channels"]["imu/temperature"]["input_unit"], "degC");
}

TEST(AllanCommand, ListOptionsLeaveTheFileAfterThem) {
  testing::ScratchDirectory dir;
  const std::string record = dir.write("imu.csv", imu_record());
  const auto fit = run_cli({"allan", "--fit-range", "0.1:10", record, "--column", "gx", "--rate", "100", "--json"});
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_EQ(nlohmann::json::parse(fit.out).at("noise").at("fit").at("fit_range").at("chosen_by"), "user");
  const std::string yaml = dir.path() + "/imu.yaml";
  const auto columns = run_cli({"allan", "--columns", "gx,ax", "--export", "kalibr", yaml, record, "--rate", "100",
                                "--input-unit", "deg/s,ax=m/s^2", "--json"});
  ASSERT_EQ(columns.exit_code, 0) << columns.err;
  EXPECT_EQ(nlohmann::json::parse(columns.out).at("channels").size(), 2U);
  EXPECT_TRUE(std::ifstream(yaml).good());
}

}  // namespace
}  // namespace inertest
