// inertest inspect: the time-stamp checks (--time-column, --gaps), the constant-channel warning, and
// the channel listing of .mat, HDF5 and TDMS records.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;

// 10 ms samples with 0.03 and 0.04 missing; gyro = 100 t + 1.
constexpr const char* kGap = "time,gyro\n0.00,1\n0.01,2\n0.02,3\n0.05,6\n0.06,7\n";

TEST(InspectCommand, SplitReportsTheGapAndTheSegments) {
  testing::ScratchDirectory dir;
  const std::string file = dir.write("gap.csv", kGap);
  const auto run = testing::run_cli({"inspect", file, "--time-column", "time", "--gaps", "split", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  const auto& time = json["time_stamps"];
  EXPECT_EQ(time["gap_policy"], "split");
  EXPECT_DOUBLE_EQ(time["sample_interval"].get<double>(), 0.01);
  ASSERT_EQ(time["gaps"].size(), 1u);
  EXPECT_EQ(time["gaps"][0]["line"], 5);
  EXPECT_EQ(time["gaps"][0]["missing_samples"], 2);
  EXPECT_DOUBLE_EQ(time["gaps"][0]["time_before"].get<double>(), 0.02);
  ASSERT_EQ(time["segments"].size(), 2u);
  EXPECT_EQ(time["segments"][0], (nlohmann::json{{"first_line", 2}, {"last_line", 4}, {"samples", 3}}));
  EXPECT_EQ(time["segments"][1], (nlohmann::json{{"first_line", 5}, {"last_line", 6}, {"samples", 2}}));
  EXPECT_EQ(json["rows"], 5);
}

TEST(InspectCommand, InterpolateCountsTheFilledSamples) {
  testing::ScratchDirectory dir;
  const std::string file = dir.write("gap.csv", kGap);
  const auto run = testing::run_cli({"inspect", file, "--time-column", "1", "--gaps", "interpolate", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["time_stamps"]["interpolated_samples"], 2);
  EXPECT_EQ(json["rows"], 7);
  // gyro = 100 t + 1 at t = 0 .. 0.06: mean 4.
  EXPECT_NEAR(json["columns"][1]["mean"].get<double>(), 4.0, 1e-12);
}

TEST(InspectCommand, ReadableReportNamesTheGap) {
  testing::ScratchDirectory dir;
  const std::string file = dir.write("gap.csv", kGap);
  const auto run = testing::run_cli({"inspect", file, "--time-column", "time", "--gaps", "split"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("gap before line 5: 0.02 to 0.05, 2 sample(s) missing"));
}

TEST(InspectCommand, GivenSampleIntervalAndBadPolicy) {
  testing::ScratchDirectory dir;
  const std::string file = dir.write("gap.csv", kGap);
  // At a nominal 20 ms the 30 ms step is no gap.
  auto run = testing::run_cli({"inspect", file, "--time-column", "time", "--sample-interval", "0.02", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(nlohmann::json::parse(run.out)["time_stamps"]["gaps"].empty());
  run = testing::run_cli({"inspect", file, "--time-column", "time", "--gaps", "ignore", "--json"});
  EXPECT_NE(run.exit_code, 0);
  EXPECT_EQ(run.out, "");
}

TEST(InspectCommand, ConstantChannelIsAWarningInTheJson) {
  testing::ScratchDirectory dir;
  const std::string file = dir.write("c.csv", "a,b\n1,2\n1,3\n");
  const auto run = testing::run_cli({"inspect", file, "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.err, HasSubstr("column 'a' is constant: all 2 samples equal 1"));
  EXPECT_EQ(nlohmann::json::parse(run.out)["warnings"].size(), 1u);
}

// A binary record of no channels is no record: an error, not "0 rows, 0 columns" and exit 0.
TEST(InspectCommand, ZeroChannelsOfABinaryRecordIsAnError) {
  testing::ScratchDirectory dir;
  const std::string file = dir.write("r.f64", testing::f64_bytes({1.0, 2.0}));
  const auto run = testing::run_cli({"inspect", file, "--format", "f64", "--channels", "0"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  EXPECT_THAT(run.err, HasSubstr("--channels is 0: a binary record holds at least one channel"));
}

// Every format lists its channels with the stored type, length, unit and rate (found by magic bytes).
TEST(InspectCommand, ListsTheChannelsOfMatHdf5AndTdmsRecords) {
  const auto tdms = nlohmann::json::parse(
      testing::run_cli({"inspect", testing::source_path("data/tdms/raw1.tdms"), "--json"}).out);
  EXPECT_EQ(tdms["format"], "tdms");
  EXPECT_EQ(tdms["columns"].size(), 7u);
  const auto& first = tdms["columns"][0];
  EXPECT_EQ(first["name"], "Layer Data/First  Channel");
  EXPECT_EQ(first["type"], "daqmx i16");
  EXPECT_EQ(first["count"], 2000);
  EXPECT_EQ(first["unit"], "Volts");
  EXPECT_DOUBLE_EQ(first["sample_rate_hz"].get<double>(), 50000.0);  // 1 / wf_increment (2e-5 s)
  const auto hdf5 = nlohmann::json::parse(
      testing::run_cli({"inspect", testing::source_path("data/lab_formats/record.h5"), "--json"}).out);
  EXPECT_EQ(hdf5["format"], "hdf5");
  EXPECT_EQ(hdf5["columns"][0]["unit"], "deg/h");
  EXPECT_EQ(hdf5["columns"][2]["type"], "f64 2x3");  // listed, not read as samples
  EXPECT_FALSE(hdf5["columns"][2].contains("mean"));
  const testing::CliRun mat = testing::run_cli({"inspect", testing::source_path("data/lab_formats/record_v7.mat")});
  EXPECT_EQ(mat.exit_code, 0);
  EXPECT_THAT(mat.out, HasSubstr("mat record, 5 channels"));
  EXPECT_THAT(mat.out, HasSubstr("imu.gyro_x"));
}

}  // namespace
}  // namespace inertest
