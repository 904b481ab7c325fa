#include <cmath>
#include <fstream>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/centrifuge/centrifuge_model.h"
#include "test_util/test_util.h"

namespace inertest::testing {
namespace {

using ::testing::HasSubstr;

// The paper's Table 3 coefficients are per its g of 9.8 m/s^2, the results per standard g: a
// coefficient of order n is (9.80665 / 9.8)^n times the paper's.
constexpr double kPerStandardG = 9.80665 / 9.8;

const std::string kTable3 = "data/centrifuge/table3_harmonics.csv";

std::vector<std::string> paper_arguments(std::vector<std::string> extra) {
  std::vector<std::string> arguments = {"centrifuge", source_path(kTable3), "--radius", "1",
                                        "--latitude", "45.75", "--gravity", "9.8",
                                        "--k1", "-2e-5", "--k2", "2e-5", "--delta-omega", "1e-5"};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  arguments.push_back("--json");
  return arguments;
}

TEST(CentrifugeCommand, ReferenceCaseFromTable3) {
  const CliRun run = run_cli(paper_arguments({}));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  const auto& q = json["coefficients"];
  EXPECT_NEAR(q["D_F"]["value"].get<double>(), 0.90605, 0.5e-5);
  EXPECT_NEAR(q["D_I"]["value"].get<double>(), 1.5366 * kPerStandardG, 0.5e-4);
  EXPECT_NEAR(q["D_O"]["value"].get<double>(), 0.7431 * kPerStandardG, 0.5e-4);
  EXPECT_NEAR(q["D_S"]["value"].get<double>(), -0.021962 * kPerStandardG, 0.5e-6);
  EXPECT_NEAR(q["D_OO"]["value"].get<double>(), 3.2411e-4 * kPerStandardG * kPerStandardG, 0.5e-8);
  EXPECT_NEAR(q["D_SS"]["value"].get<double>(), 2.0991e-4 * kPerStandardG * kPerStandardG, 0.5e-8);
  EXPECT_NEAR(q["D_OS"]["value"].get<double>(), 2.5223e-5 * kPerStandardG * kPerStandardG, 0.5e-9);
  EXPECT_NEAR_RELATIVE(q["D_II"]["value"].get<double>(), -1.9246e-4 * kPerStandardG * kPerStandardG, 0.01);
  EXPECT_NEAR_RELATIVE(q["D_IO"]["value"].get<double>(), 1.3698e-5 * kPerStandardG * kPerStandardG, 0.01);
  EXPECT_NEAR_RELATIVE(q["D_IS"]["value"].get<double>(), -2.4943e-5 * kPerStandardG * kPerStandardG, 0.01);
  EXPECT_EQ(q["D_F"]["unit"], "deg/h");
  EXPECT_EQ(q["D_I"]["unit"], "deg/h/g");
  EXPECT_EQ(q["D_IS"]["unit"], "deg/h/g^2");
  EXPECT_TRUE(q["D_IS"].contains("uncertainty"));
  EXPECT_NEAR(json["residual_rms"]["value"].get<double>(), 0.0014, 0.5e-4);
  for (const char* error : {"k1", "k2", "delta_omega", "earth_rate"}) {
    EXPECT_TRUE(json["influence"][error]["shift"].contains("D_I")) << error;
  }
}

TEST(CentrifugeCommand, NoCompensationGivesThePapersDI) {
  const CliRun run = run_cli(paper_arguments({"--no-compensation"}));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_NEAR(json["coefficients"]["D_I"]["value"].get<double>(), -1.5268 * kPerStandardG, 0.5e-4);
  EXPECT_FALSE(json["compensation"].get<bool>());
  // The measured errors are the ones given, and said to be applied nowhere (they read "measured"
  // with the 0 that was applied).
  const nlohmann::json& k1 = json.at("centrifuge_errors").at("k1");
  EXPECT_EQ(k1.at("value").at("value"), -2e-5);
  EXPECT_EQ(k1.at("source"), "measured, not applied (compensation off)");
}

TEST(CentrifugeCommand, RawSamplesWithOmegaColumn) {
  using namespace inertest::centrifuge;
  CentrifugeSite site;
  site.latitude_rad = 30.0 * constants::kDegree;
  const DriftCoefficients q = {0.9043, 1.5365, 0.7431, -0.0221, -1.9e-4, 3.2e-4, 2.1e-4, 1.4e-5, -2.5e-5, 2.5e-5};
  const CentrifugeErrors errors{-2e-5, 2e-5, 1e-5};
  std::string text = "accel_g,beta_deg,gamma_deg,output,omega_rad_s\n";
  for (double a : {10.0, 20.0}) {
    const double omega = std::sqrt(a * 9.80665) * 1.001;  // a rate not quite nominal
    for (double beta : {0.0, 90.0, 180.0, 270.0}) {
      for (int i = 0; i < 36; ++i) {
        const double gamma = 10.0 * i;
        const double output = centrifuge_model_output(q, site, errors, omega, beta * constants::kDegree,
                                                      gamma * constants::kDegree);
        text += fmt::format("{},{},{},{:.17g},{:.17g}\n", a, beta, gamma, output, omega);
      }
    }
  }
  ScratchDirectory scratch;
  const std::string file = scratch.write("samples.csv", text);
  const CliRun run = run_cli({"centrifuge", file, "--latitude", "30", "--k1", "-2e-5", "--k2", "2e-5",
                              "--delta-omega", "1e-5", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  for (std::size_t j = 0; j < kDriftTermCount; ++j) {
    const std::string name(drift_term_name(j));
    EXPECT_NEAR_RELATIVE(json["coefficients"][name]["value"].get<double>(), q[j], 1e-6) << name;
  }
  EXPECT_EQ(json["runs"][0]["harmonic_fit"]["method"], "dft");
}

TEST(CentrifugeCommand, LatitudeIsRequiredWhenCompensating) {
  const CliRun run = run_cli({"centrifuge", source_path(kTable3), "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("--latitude is required"));
  EXPECT_TRUE(run.out.empty());
}

TEST(CentrifugeCommand, WrongColumnsNameTheFileAndLine) {
  ScratchDirectory scratch;
  const std::string file = scratch.write("bad.csv", "# test\naccel_g,beta,k0,k1c,k1s,k2c,k2s\n10,0,1,2,3,4,5\n");
  const CliRun run = run_cli({"centrifuge", file, "--latitude", "45", "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr(file + ":2"));
  EXPECT_THAT(run.err, HasSubstr("beta_deg"));
}

TEST(CentrifugeCommand, OneGLevelNamesTheUnidentifiableCoefficients) {
  ScratchDirectory scratch;
  std::string text;
  std::ifstream table(source_path(kTable3));
  std::string line;
  while (std::getline(table, line)) {
    if (line.rfind("20,", 0) != 0) text += line + "\n";
  }
  const std::string file = scratch.write("ten_g.csv", text);
  const CliRun run = run_cli({"centrifuge", file, "--latitude", "45.75", "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("cannot identify D_F, D_II, D_OO, D_SS"));
}

}  // namespace
}  // namespace inertest::testing
