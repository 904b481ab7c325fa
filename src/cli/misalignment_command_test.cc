// The misalignment command through the real executable: exact JSON keys, records mode, errors.
#include <fmt/format.h>
#include <cmath>
#include <nlohmann/json.hpp>

#include "inertest/core/units.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using testing::run_cli;
using testing::source_path;

const char* const kGyroKeys[] = {"delta_theta_y0", "delta_theta_x0", "delta_theta_y1",
                                 "delta_theta_y2", "delta_theta_z2", "misalignment"};

TEST(MisalignmentCommand, GyroTable1JsonHasTheExactKeys) {
  const auto run = run_cli({"misalignment", "gyro", source_path("data/misalignment/gyro_table1.csv"), "--scale-factor",
                            "-2.9222", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  for (const char* key : kGyroKeys) {
    ASSERT_TRUE(json.contains(key)) << key;
    EXPECT_EQ(json[key]["unit"], "arcsec");
    EXPECT_TRUE(json[key].contains("uncertainty")) << key;  // 15 equations over the three rates
  }
  ASSERT_EQ(json["by_rate"].size(), 3u);
  const std::array<double, 3> rates = {20, 30, 40};
  const std::array<double, 3> z2 = {55.4, 55.8, 56.3};  // Table 1 of the misalignment paper
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& entry = json["by_rate"][i];
    EXPECT_EQ(entry["rate_dps"].get<double>(), rates[i]);
    for (const char* key : kGyroKeys) EXPECT_EQ(entry[key]["unit"], "arcsec") << key;
    EXPECT_NEAR(entry["delta_theta_z2"]["value"].get<double>(), z2[i], 0.1);
  }
}

TEST(MisalignmentCommand, AccelerometerTable2JsonHasTheExactKeys) {
  const auto run = run_cli({"misalignment", "accelerometer", source_path("data/misalignment/accelerometer_table2.csv"),
                            "--scale-factor", "1.299", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_NEAR(json["delta_theta_y2"]["value"].get<double>(), -5.3, 0.1);
  EXPECT_NEAR(json["delta_theta_z2"]["value"].get<double>(), 20.5, 0.1);
  EXPECT_NEAR(json["misalignment"]["value"].get<double>(), 21.1, 0.1);
  EXPECT_EQ(json["misalignment"]["unit"], "arcsec");
  ASSERT_EQ(json["by_run"].size(), 3u);
  EXPECT_EQ(json["by_run"][0]["run"], 1);
  EXPECT_NEAR(json["by_run"][0]["misalignment"]["value"].get<double>(), 21.5, 0.1);
}

TEST(MisalignmentCommand, ReportWithoutJsonGoesToStdout) {
  const auto run = run_cli({"misalignment", "accelerometer", source_path("data/misalignment/accelerometer_table2.csv"),
                            "--scale-factor", "1.299"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // The mean over the runs, then the solution of each run.
  EXPECT_THAT(run.out, ::testing::HasSubstr("misalignment γ"));
  EXPECT_THAT(run.out, ::testing::HasSubstr("solution of each run"));
  EXPECT_THAT(run.out, ::testing::HasSubstr(", run 3\n"));
}

TEST(MisalignmentCommand, GyroRecordsModeAveragesWholeRevolutions) {
  // Synthetic records of the paper's five positions at ±20 deg/s, 50 Hz, 1000 samples (20 s, one
  // whole revolution of 18 s), with the Earth-rate terms; the odd ones give time, the even ones angle.
  testing::ScratchDirectory scratch;
  const double k = -2.9222;
  const double horizontal = 15.041067 / 3600.0 * std::cos(45.75 * constants::kDegree);  // deg/s
  const double y0 = -7.5, x0 = 2.4, y1 = -53.8, y2 = -162.0, z2 = 56.3;                 // arcsec
  const std::array<std::array<double, 2>, 5> positions = {{{0, 0}, {0, 180}, {180, 180}, {90, 180}, {0, 90}}};
  std::string listing = "# synthetic records\nalpha_deg,beta_deg,rate_dps,file\n";
  int index = 0;
  for (const auto& [alpha_deg, beta_deg] : positions) {
    for (double rate : {20.0, -20.0}) {
      const double a = alpha_deg * constants::kDegree;
      const double b = beta_deg * constants::kDegree;
      const double angles =
          (-y0 * std::cos(b) + x0 * std::sin(b) - y1 + z2 * std::sin(a) - y2 * std::cos(a)) * constants::kArcsecond;
      const bool by_time = index % 2 == 1;
      std::string record = by_time ? "time_s,output\n" : "table_angle_deg,output\n";
      for (int s = 0; s < 1000; ++s) {
        const double t = 0.02 * s;
        const double table = rate * t;  // deg
        const double input = horizontal * (std::sin(table * constants::kDegree) * std::cos(b) +
                                           std::cos(table * constants::kDegree) * std::sin(b)) +
                             rate * angles;
        const double first = by_time ? t : std::fmod(table + 720.0, 360.0);
        record += fmt::format("{:.17g},{:.17g}\n", first, 0.01 * (index / 2) + k * input);  // V0 per position
      }
      const std::string name = fmt::format("records/r{}.csv", index);
      scratch.write(name, record);
      listing += fmt::format("{},{},{},{}\n", alpha_deg, beta_deg, rate, name);
      ++index;
    }
  }
  const std::string listing_path = scratch.write("listing.csv", listing);
  const auto run = run_cli({"misalignment", "gyro", listing_path, "--records", "--scale-factor", "-2.9222", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_NEAR_RELATIVE(json["delta_theta_y0"]["value"].get<double>(), y0, 1e-9);
  EXPECT_NEAR_RELATIVE(json["delta_theta_x0"]["value"].get<double>(), x0, 1e-9);
  EXPECT_NEAR_RELATIVE(json["delta_theta_y1"]["value"].get<double>(), y1, 1e-9);
  EXPECT_NEAR_RELATIVE(json["delta_theta_y2"]["value"].get<double>(), y2, 1e-9);
  EXPECT_NEAR_RELATIVE(json["delta_theta_z2"]["value"].get<double>(), z2, 1e-9);

  // The same listing with its positions in radians: refused at the row (gamma came out 146 480 arcsec).
  std::string in_radians = "alpha_deg,beta_deg,rate_dps,file\n";
  index = 0;
  for (const auto& [alpha_deg, beta_deg] : positions) {
    for (double rate : {20.0, -20.0}) {
      in_radians += fmt::format("{:.6f},{:.6f},{},records/r{}.csv\n", alpha_deg * constants::kDegree,
                                beta_deg * constants::kDegree, rate, index++);
    }
  }
  const std::string radians_path = scratch.write("radians.csv", in_radians);
  const auto refused = run_cli({"misalignment", "gyro", radians_path, "--records", "--scale-factor", "-2.9222"});
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_TRUE(refused.out.empty());
  EXPECT_THAT(refused.err, ::testing::HasSubstr(radians_path + ":6: gyro misalignment: alpha_deg 3.141593: the column's "
                                                "angles all lie within 2 pi and are not all whole degrees: radians?"));
}

TEST(MisalignmentCommand, RecordsListingErrorsNameTheLine) {
  testing::ScratchDirectory scratch;
  const std::string listing = scratch.write("listing.csv", "alpha_deg,beta_deg,rate_dps,file\n0,0,20,missing.csv\n");
  const auto run = run_cli({"misalignment", "gyro", listing, "--records", "--scale-factor", "1"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, ::testing::HasSubstr("listing.csv:2:"));
  EXPECT_THAT(run.err, ::testing::HasSubstr("does not exist"));
  const std::string bad_number = scratch.write("bad.csv", "alpha_deg,beta_deg,rate_dps,file\n0,x0,20,r.csv\n");
  const auto bad = run_cli({"misalignment", "gyro", bad_number, "--records", "--scale-factor", "1"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, ::testing::HasSubstr("bad.csv:2:3: beta_deg 'x0' is not a number"));
}

TEST(MisalignmentCommand, ZeroScaleFactorIsAnError) {
  for (const char* method : {"gyro", "accelerometer"}) {
    const std::string file = std::string(method) == "gyro" ? "data/misalignment/gyro_table1.csv"
                                                           : "data/misalignment/accelerometer_table2.csv";
    const auto run = run_cli({"misalignment", method, source_path(file), "--scale-factor", "0", "--json"});
    EXPECT_EQ(run.exit_code, 2) << method;
    EXPECT_THAT(run.err, ::testing::HasSubstr("scale factor kI must be finite and nonzero")) << method;
    EXPECT_TRUE(run.out.empty());
  }
}

TEST(MisalignmentCommand, MissingDirectionIsAnErrorAtTheFileLine) {
  testing::ScratchDirectory scratch;
  const std::string file = scratch.write("positions.csv",
                                         "alpha_deg,beta_deg,rate_dps,output\n"
                                         "0,0,20,-0.0614\n0,0,-20,0.0654\n0,180,20,-0.0576\n");
  const auto run = run_cli({"misalignment", "gyro", file, "--scale-factor", "-2.9222", "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, ::testing::HasSubstr("positions.csv:4"));
  EXPECT_THAT(run.err, ::testing::HasSubstr("no row at -20 deg/s"));
}

TEST(MisalignmentCommand, PositionsThatCannotSeparateAreAnError) {
  testing::ScratchDirectory scratch;
  // Table 1 at 20 deg/s without V5 (0, 90): Δθx0 cannot be separated.
  const std::string file =
      scratch.write("positions.csv",
                    "alpha_deg,beta_deg,rate_dps,output\n"
                    "0,0,20,-0.0614\n0,0,-20,0.0654\n0,180,20,-0.0576\n0,180,-20,0.0606\n"
                    "180,180,20,0.0350\n180,180,-20,-0.0306\n90,180,20,-0.0290\n90,180,-20,0.0287\n");
  const auto run = run_cli({"misalignment", "gyro", file, "--scale-factor", "-2.9222", "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err,
              ::testing::HasSubstr("the positions at 20 deg/s (4 equation(s) for 5 unknowns) cannot separate"));
  EXPECT_THAT(run.err, ::testing::HasSubstr("delta_theta_x0"));
}

TEST(MisalignmentCommand, NeedsAMethodAndAScaleFactor) {
  EXPECT_NE(run_cli({"misalignment"}).exit_code, 0);
  const auto run = run_cli({"misalignment", "gyro", source_path("data/misalignment/gyro_table1.csv")});
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.err, ::testing::HasSubstr("--scale-factor"));
}

}  // namespace
}  // namespace inertest
