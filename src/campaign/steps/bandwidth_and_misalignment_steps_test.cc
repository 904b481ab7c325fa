// Plan steps bandwidth and input_axis_misalignment, run through inertest::run_campaign.
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using testing::ScratchDirectory;
using ::testing::HasSubstr;

constexpr double kPi = 3.14159265358979323846;
constexpr double kBandwidth = 200.0;
constexpr double kDelay = 5e-4;

const char* kHeader = R"([instrument]
id = "FOG-1"
output_unit = "pulse/s"
nominal_scale_factor = 2.0
)";

double gain(double f) { return 1.0 / std::sqrt(1 + std::pow(f / kBandwidth, 2)); }
double phase(double f) { return -std::atan(f / kBandwidth) - 2 * kPi * f * kDelay; }

std::string plan_with(const ScratchDirectory& scratch, const std::string& name, const std::string& steps) {
  return scratch.write(name, std::string(kHeader) + steps);
}

TEST(BandwidthStep, GainsTable) {
  ScratchDirectory scratch;
  std::string text = "freq_hz,gain,phase_deg\n";
  for (int i = 0; i < 10; ++i) {
    const double f = 10.0 * std::pow(50.0, i / 9.0);
    text += fmt::format("{:.17g},{:.17g},{:.17g}\n", f, gain(f), phase(f) * 180 / kPi);
  }
  scratch.write("gains.csv", text);
  const auto plan = plan_with(scratch, "plan.toml", "[[procedure]]\nkind = \"bandwidth\"\nfile = \"gains.csv\"\n");
  const auto result = run_campaign(plan, scratch.path() + "/out").results.at("procedures").at(0).at("result");
  EXPECT_NEAR(result.at("bandwidth").at("value").get<double>(), kBandwidth, kBandwidth * 1e-9);
  EXPECT_NEAR(result.at("delay").at("value").get<double>(), kDelay, kDelay * 1e-9);
}

TEST(BandwidthStep, TheBundledExamplePlan) {
  // examples/bandwidth/gains.csv: a 300 Hz lag with a 0.2 ms delay, gains to 6 and phases to 4 decimals.
  ScratchDirectory scratch;
  const auto summary = run_campaign(testing::source_path("examples/bandwidth/plan.toml"), scratch.path());
  const auto& result = summary.results.at("procedures").at(0).at("result");
  EXPECT_NEAR(result.at("bandwidth").at("value").get<double>(), 300.0, 0.01);
  EXPECT_NEAR(result.at("delay").at("value").get<double>(), 2e-4, 1e-8);
  EXPECT_EQ(summary.results.at("verdict"), "PASS");
}

TEST(BandwidthStep, RawRecordsWithTheirOwnColumnNames) {
  ScratchDirectory scratch;
  std::string runs;
  for (int i = 0; i < 10; ++i) {
    const double f = 10.0 * std::pow(50.0, i / 9.0);
    const double w = 2 * kPi * f;
    std::string record = "t,gyro,theta\n";
    for (int k = 0; k < 2000; ++k) {
      const double t = k / 20000.0;
      record += fmt::format("{:.17g},{:.17g},{:.17g}\n", t, 7.0 * gain(f) * 1e-3 * w * std::sin(w * t + 1.0 + kPi / 2 + phase(f)),
                            1e-3 * std::sin(w * t + 1.0));
    }
    scratch.write(fmt::format("v{}.csv", i), record);
    runs += fmt::format("[[procedure.run]]\nfrequency_hz = {:.17g}\nfile = \"v{}.csv\"\n", f, i);
  }
  const auto plan = plan_with(scratch, "plan.toml",
                              "[[procedure]]\nkind = \"bandwidth\"\ntime_column = \"t\"\noutput_column = \"gyro\"\n"
                              "angle_column = \"theta\"\nangle_unit = \"rad\"\n" + runs);
  const auto result = run_campaign(plan, scratch.path() + "/out").results.at("procedures").at(0).at("result");
  EXPECT_NEAR(result.at("bandwidth").at("value").get<double>(), kBandwidth, kBandwidth * 1e-8);
  EXPECT_NEAR(result.at("delay").at("value").get<double>(), kDelay, kDelay * 1e-8);
  EXPECT_EQ(result.at("gain_at_lowest_frequency").at("unit"), "pulse/s/(rad/s)");
}

TEST(BandwidthStep, FrequenciesNotIncreasingAreRejectedAtTheirLine) {
  ScratchDirectory scratch;
  scratch.write("a.csv", "t,output,angle_deg\n0,0,0\n");
  scratch.write("b.csv", "t,output,angle_deg\n0,0,0\n");
  const auto plan = plan_with(scratch, "plan.toml", R"(
[[procedure]]
kind = "bandwidth"
minimum_frequencies = 3
[[procedure.run]]
frequency_hz = 20
file = "a.csv"
[[procedure.run]]
frequency_hz = 10
file = "b.csv"
)");
  try {
    run_campaign(plan, scratch.path() + "/out");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("plan.toml:13"));
    EXPECT_THAT(e.what(), HasSubstr("must increase"));
  }
}

TEST(BandwidthStep, TooFewRunsAreRejected) {
  ScratchDirectory scratch;
  scratch.write("a.csv", "t,output,angle_deg\n0,0,0\n");
  const auto plan = plan_with(scratch, "plan.toml", R"(
[[procedure]]
kind = "bandwidth"
[[procedure.run]]
frequency_hz = 10
file = "a.csv"
)");
  try {
    run_campaign(plan, scratch.path() + "/out");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("at least 10"));
  }
}

TEST(InputAxisMisalignmentStep, FourPositionsWithTheNominalScaleFactor) {
  ScratchDirectory scratch;
  // K = 2 (nominal), Ω = 100: δ = 1.3e-4, −1.7e-4, −0.7e-4, 2.3e-4 → δx = 1e-4, δy = −2e-4, ε = 3e-5.
  std::string text = "position,output_positive,output_negative\n";
  int j = 0;
  for (double d : {1.3e-4, -1.7e-4, -0.7e-4, 2.3e-4}) text += fmt::format("{},{:.17g},{:.17g}\n", ++j, 1 + 200 * d, 1 - 200 * d);
  scratch.write("pos.csv", text);
  const auto plan = plan_with(scratch, "plan.toml",
                              "[[procedure]]\nkind = \"input_axis_misalignment\"\nfile = \"pos.csv\"\nrate = 100\n");
  const auto result = run_campaign(plan, scratch.path() + "/out").results.at("procedures").at(0).at("result");
  const double arcsec = kPi / 180 / 3600;
  EXPECT_NEAR(result.at("misalignment").at("value").get<double>(), std::asin(std::hypot(1e-4, 2e-4)) / arcsec, 1e-6);
  EXPECT_NEAR(result.at("mounting_error").at("value").get<double>(), 3e-5 / arcsec, 1e-6);
}

}  // namespace
}  // namespace inertest
