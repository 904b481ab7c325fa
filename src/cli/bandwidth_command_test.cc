#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "test_util/test_util.h"

namespace inertest {
namespace {

using testing::run_cli;
using testing::ScratchDirectory;
using ::testing::HasSubstr;

constexpr double kPi = 3.14159265358979323846;
constexpr double kBandwidth = 300.0;  // Hz
constexpr double kDelay = 2e-4;       // s

std::string gains_csv(std::size_t n) {
  const double t = 1.0 / (2 * kPi * kBandwidth);
  std::string text = "freq_hz,gain,phase_deg\n";
  for (std::size_t i = 0; i < n; ++i) {
    const double f = 10.0 * std::pow(100.0, static_cast<double>(i) / (n - 1));
    const double w = 2 * kPi * f;
    text += fmt::format("{:.17g},{:.17g},{:.17g}\n", f, 1.0 / std::sqrt(1 + w * w * t * t),
                        (-std::atan(w * t) - w * kDelay) * 180.0 / kPi);
  }
  return text;
}

TEST(BandwidthCommand, GainsTableJsonContract) {
  ScratchDirectory scratch;
  const auto run = run_cli({"bandwidth", scratch.write("gains.csv", gains_csv(12)), "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_NEAR(json.at("bandwidth").at("value").get<double>(), kBandwidth, kBandwidth * 1e-9);
  EXPECT_EQ(json.at("bandwidth").at("unit"), "Hz");
  EXPECT_TRUE(json.at("bandwidth").contains("uncertainty"));
  EXPECT_NEAR(json.at("delay").at("value").get<double>(), kDelay, kDelay * 1e-9);
  EXPECT_EQ(json.at("delay").at("unit"), "s");
  EXPECT_NEAR(json.at("dc_gain").at("value").get<double>(), 1.0, 1e-9);
  ASSERT_EQ(json.at("bode").size(), 12u);
  for (const char* key : {"frequency_hz", "gain", "fitted_gain", "phase_deg", "fitted_phase_deg"}) {
    EXPECT_TRUE(json.at("bode").at(0).contains(key)) << key;
  }
}

TEST(BandwidthCommand, ReadableReportWithoutJson) {
  ScratchDirectory scratch;
  const auto run = run_cli({"bandwidth", scratch.write("gains.csv", gains_csv(10))});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("bandwidth Bw"));
}

TEST(BandwidthCommand, FrequenciesOutOfOrderNameTheLine) {
  ScratchDirectory scratch;
  const auto path = scratch.write("gains.csv", "freq_hz,gain,phase_deg\n10,1,-1\n20,0.99,-2\n15,0.98,-3\n");
  const auto run = run_cli({"bandwidth", path, "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_TRUE(run.out.empty());
  EXPECT_THAT(run.err, HasSubstr(path + ":4"));
  EXPECT_THAT(run.err, HasSubstr("must increase"));
}

TEST(BandwidthCommand, TooFewFrequencies) {
  ScratchDirectory scratch;
  const auto run = run_cli({"bandwidth", scratch.write("gains.csv", gains_csv(5)), "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("at least 10"));
  const auto lowered =
      run_cli({"bandwidth", scratch.write("gains5.csv", gains_csv(5)), "--minimum-frequencies", "3", "--json"});
  EXPECT_EQ(lowered.exit_code, 0) << lowered.err;
}

TEST(BandwidthCommand, NoBandwidthFromRisingGains) {
  ScratchDirectory scratch;
  std::string text = "freq_hz,gain,phase_deg\n";
  for (int i = 0; i < 10; ++i) text += fmt::format("{},{},-1\n", 10 * (i + 1), 1.0 + 0.01 * i);
  const auto run = run_cli({"bandwidth", scratch.write("gains.csv", text), "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("no bandwidth can be determined"));
}

TEST(BandwidthCommand, RawRecordsListedWithTheirFrequencies) {
  ScratchDirectory scratch;
  const double t = 1.0 / (2 * kPi * kBandwidth);
  std::string listing = "freq_hz,file\n";
  for (int i = 0; i < 10; ++i) {
    const double f = 10.0 * std::pow(60.0, i / 9.0);
    const double w = 2 * kPi * f;
    const double gain = 1.0 / std::sqrt(1 + w * w * t * t);
    const double phase = -std::atan(w * t) - w * kDelay;
    std::string record = "time_s,output,angle_deg\n";
    for (int k = 0; k < 2000; ++k) {
      const double time = k / 10000.0;
      record += fmt::format("{:.17g},{:.17g},{:.17g}\n", time, 100.0 * gain * 0.2 * w * std::sin(w * time + kPi / 2 + phase),
                            0.2 * std::sin(w * time));
    }
    const std::string name = fmt::format("runs/vib_{}.csv", i);
    scratch.write(name, record);
    listing += fmt::format("{:.17g},{}\n", f, name);
  }
  const auto run = run_cli({"bandwidth", "--records", scratch.write("runs.csv", listing), "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_NEAR(json.at("bandwidth").at("value").get<double>(), kBandwidth, kBandwidth * 1e-8);
  EXPECT_NEAR(json.at("delay").at("value").get<double>(), kDelay, kDelay * 1e-8);
  EXPECT_EQ(json.at("vibration_fits").size(), 10u);
}

TEST(BandwidthCommand, ListingNamingAMissingFile) {
  ScratchDirectory scratch;
  const auto listing = scratch.write("runs.csv", "freq_hz,file\n10,nope.csv\n");
  const auto run = run_cli({"bandwidth", "--records", listing, "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr(listing + ":2:4"));
  EXPECT_THAT(run.err, HasSubstr("not found"));
}

TEST(BandwidthCommand, GainsAndRecordsTogetherIsAnError) {
  ScratchDirectory scratch;
  const auto gains = scratch.write("gains.csv", gains_csv(10));
  const auto run = run_cli({"bandwidth", gains, "--records", gains, "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("exactly one"));
}

}  // namespace
}  // namespace inertest
