#include "inertest/centrifuge/centrifuge_record.h"

#include <cmath>
#include <fmt/format.h>

#include "test_util/test_util.h"

namespace inertest::centrifuge {
namespace {

using ::testing::HasSubstr;

// Runs parse_centrifuge_record and returns the Error it throws.
Error parse_error(const std::string& text) {
  try {
    parse_centrifuge_record(text, "rec.csv");
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "expected an Error for:\n" << text;
  return Error("none");
}

TEST(CentrifugeRecord, ReadsTheTable3Harmonics) {
  const CentrifugeRecord record = read_centrifuge_record(testing::source_path("data/centrifuge/table3_harmonics.csv"));
  ASSERT_EQ(record.kind, CentrifugeRecord::Kind::kHarmonics);
  ASSERT_EQ(record.harmonic_runs.size(), 8u);
  const CentrifugeRun& last = record.harmonic_runs.back();
  EXPECT_EQ(last.accel_g, 20.0);
  EXPECT_NEAR(last.beta_rad, 1.5 * constants::kPi, 1e-15);
  EXPECT_EQ(last.amplitudes[kK1s], -14.8614);
  EXPECT_FALSE(last.omega_rad_s.has_value());
  EXPECT_EQ(last.location.line, 14u);
}

TEST(CentrifugeRecord, ColumnsInAnyOrderWithOmega) {
  const CentrifugeRecord record = parse_centrifuge_record(
      "k2s,k2c,k1s,k1c,k0,beta_deg,accel_g,omega_rad_s\n0.5,0.4,0.3,0.2,0.1,90,10,9.9\n", "rec.csv");
  ASSERT_EQ(record.harmonic_runs.size(), 1u);
  const CentrifugeRun& run = record.harmonic_runs[0];
  EXPECT_EQ(run.amplitudes, (HarmonicAmplitudes{0.1, 0.2, 0.3, 0.4, 0.5}));
  EXPECT_EQ(run.omega_rad_s, 9.9);
}

TEST(CentrifugeRecord, GroupsSamplesIntoRuns) {
  std::string text = "# raw samples\naccel_g,beta_deg,gamma_deg,output\n";
  for (double beta : {0.0, 90.0}) {
    for (int i = 0; i < 8; ++i) {
      const double gamma = 45.0 * i;
      text += fmt::format("10,{},{},{}\n", beta, gamma, 1.0 + 2.0 * std::cos(gamma * constants::kDegree));
    }
  }
  const CentrifugeRecord record = parse_centrifuge_record(text, "rec.csv");
  ASSERT_EQ(record.kind, CentrifugeRecord::Kind::kSamples);
  ASSERT_EQ(record.sample_runs.size(), 2u);
  EXPECT_EQ(record.sample_runs[1].gamma_rad.size(), 8u);
  EXPECT_EQ(record.sample_runs[1].location.line, 11u);
  const std::vector<CentrifugeRun> runs = record.runs();
  EXPECT_NEAR(runs[0].amplitudes[kK0], 1.0, 1e-14);
  EXPECT_NEAR(runs[0].amplitudes[kK1c], 2.0, 1e-14);
}

TEST(CentrifugeRecord, MissingColumnIsAnErrorAtTheHeader) {
  const Error e = parse_error("# comment\naccel_g,beta_deg,k0,k1c,k1s,k2c\n10,0,1,2,3,4\n");
  EXPECT_THAT(e.message(), HasSubstr("needs the column 'k2s'"));
  ASSERT_TRUE(e.location().has_value());
  EXPECT_EQ(e.location()->file, "rec.csv");
  EXPECT_EQ(e.location()->line, 2u);
}

TEST(CentrifugeRecord, UnknownColumnIsAnError) {
  const Error e = parse_error("accel_g,beta_deg,gamma_deg,output,temperature\n10,0,0,1,20\n");
  EXPECT_THAT(e.message(), HasSubstr("unknown column 'temperature'"));
  EXPECT_EQ(e.location()->line, 1u);
}

TEST(CentrifugeRecord, UnrecognisedHeaderIsAnError) {
  const Error e = parse_error("rate,output_v\n1,2\n");
  EXPECT_THAT(e.message(), HasSubstr("cannot tell the kind"));
}

TEST(CentrifugeRecord, MixedKindsAreAnError) {
  const Error e = parse_error("accel_g,beta_deg,gamma_deg,output,k0\n10,0,0,1,2\n");
  EXPECT_THAT(e.message(), HasSubstr("unknown column 'k0'"));
}

TEST(CentrifugeRecord, BadNumberNamesLineAndColumn) {
  const Error e = parse_error("accel_g,beta_deg,k0,k1c,k1s,k2c,k2s\n10,0,1,2,x,4,5\n");
  ASSERT_TRUE(e.location().has_value());
  EXPECT_EQ(e.location()->line, 2u);
  EXPECT_GT(e.location()->column, 0u);
}

TEST(CentrifugeRecord, InconsistentOmegaWithinARunIsAnError) {
  const Error e = parse_error(
      "accel_g,beta_deg,gamma_deg,output,omega_rad_s\n10,0,0,1,9.9\n10,0,10,1,9.9\n10,0,20,1,9.8\n");
  EXPECT_THAT(e.message(), HasSubstr("omega_rad_s"));
  EXPECT_EQ(e.location()->line, 4u);
}

TEST(CentrifugeRecord, TooFewSamplesNamesTheRun) {
  const CentrifugeRecord record =
      parse_centrifuge_record("accel_g,beta_deg,gamma_deg,output\n10,0,0,1\n10,0,90,1\n20,0,0,1\n", "rec.csv");
  try {
    record.runs();
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("10 g and beta = 0 deg"));
    EXPECT_EQ(e.location()->line, 2u);
  }
}

}  // namespace
}  // namespace inertest::centrifuge
