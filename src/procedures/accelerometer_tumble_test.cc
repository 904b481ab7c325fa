// Accelerometer multipoint tumble (IEEE Std 1293-1998 8.3), through its declaration: positions made
// from known coefficients by the model equation give them back, exactly without noise and within
// their uncertainties with it (Monte Carlo coverage); too few positions are said; bad files refused.
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/procedure_spec.h"
#include "inertest/core/units.h"
#include "inertest/sim/dividing_head_tumble.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;

constexpr double kGravity = 9.7936;  // m/s^2, the site of the examples

using Truth = sim::AccelerometerTumbleTruth;

// Positions of the simulated dividing head (sim/dividing_head_tumble.h), at one mounting or both.
std::string positions_csv(const Truth& t, int count, int turns, bool head_along_output, double sigma,
                          std::uint64_t seed, bool both_mountings = false) {
  sim::AccelerometerTumbleOptions options;
  options.truth = t;
  options.truth.noise = sigma;
  options.positions = static_cast<std::size_t>(count);
  options.turns = static_cast<std::size_t>(turns);
  options.both_mountings = both_mountings;
  options.head_along_output = head_along_output;
  options.gravity_m_s2 = kGravity;
  return sim::simulate_accelerometer_tumble(options, seed);
}

nlohmann::json run_on(const std::string& path, const nlohmann::json& parameters = nlohmann::json::object()) {
  const ProcedureSpec* spec = find_procedure_spec("accelerometer_tumble");
  EXPECT_NE(spec, nullptr);
  ProcedureCall call;
  for (const auto& [name, value] : spec->defaults) call.parameters[name] = value;
  for (const auto& [name, value] : parameters.items()) call.parameters[name] = value;
  call.files["positions"] = path;
  spec->check(call);
  return spec->run(call).fields;
}

double value_of(const nlohmann::json& fields, const char* name) { return fields.at(name).at("value").get<double>(); }

struct Layout {
  int positions;
  bool head_along_output;
  const char* name;
};

class TumbleExact : public ::testing::TestWithParam<Layout> {};

// Noise-free positions: every coefficient of the model back to rounding, in its unit.
TEST_P(TumbleExact, RecoversEveryCoefficient) {
  const Layout layout = GetParam();
  const Truth truth;
  const testing::ScratchDirectory scratch;
  const std::string path =
      scratch.write("positions.csv", positions_csv(truth, layout.positions, 1, layout.head_along_output, 0.0, 1));
  const nlohmann::json fields =
      run_on(path, {{"output_unit", "mA"},
                    {"gravity_m_s2", kGravity},
                    {"head_axis", layout.head_along_output ? "output" : "pendulous"}});
  EXPECT_NEAR(value_of(fields, "bias"), truth.bias_g, 1e-12);
  EXPECT_NEAR(value_of(fields, "scale_factor"), truth.scale_factor, 1e-12);
  EXPECT_NEAR(value_of(fields, "second_order"), truth.second_order, 1e-12);
  EXPECT_NEAR(value_of(fields, "third_order"), truth.third_order, 1e-12);
  EXPECT_EQ(fields.at("bias").at("unit"), "g");
  EXPECT_EQ(fields.at("scale_factor").at("unit"), "mA/g");
  EXPECT_EQ(fields.at("second_order").at("unit"), "1/g");
  EXPECT_EQ(fields.at("third_order").at("unit"), "1/g^2");
  const char* misalignment =
      layout.head_along_output ? "misalignment_about_output_axis" : "misalignment_about_pendulous_axis";
  const char* other = layout.head_along_output ? "misalignment_about_pendulous_axis" : "misalignment_about_output_axis";
  const char* cross = layout.head_along_output ? "cross_coupling_ip" : "cross_coupling_io";
  EXPECT_NEAR(value_of(fields, misalignment), truth.misalignment_rad, 1e-12);
  EXPECT_EQ(fields.at(misalignment).at("unit"), "rad");
  EXPECT_TRUE(fields.at(other).is_null());
  EXPECT_NEAR(value_of(fields, cross), truth.cross_coupling, 1e-12);
  EXPECT_EQ(fields.at("positions"), layout.positions);
  EXPECT_EQ(fields.at("degrees_of_freedom"), layout.positions - 6);
  EXPECT_LT(value_of(fields, "residual_rms"), 1e-12);
  ASSERT_EQ(fields.at("residuals").size(), static_cast<std::size_t>(layout.positions));
  EXPECT_NEAR(fields.at("residuals")[1].at("angle").at("value").get<double>(), 360.0 / layout.positions, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Tumble, TumbleExact,
                         ::testing::Values(Layout{8, true, "eight_head_along_output"},
                                           Layout{12, true, "twelve_head_along_output"},
                                           Layout{16, false, "sixteen_head_along_pendulous"},
                                           Layout{24, false, "twenty_four_head_along_pendulous"}),
                         testing::NameOfParam());

// Four positions identify K0, K1, K2 and the misalignment, exactly (no degrees of freedom left);
// K3 and the cross-coupling are not identified and the result says so.
TEST(Tumble, FourPositionsIdentifyTheFirstTermsAndSaySo) {
  Truth truth;
  truth.third_order = 0.0;  // at 0, 90, 180, 270 deg cos 3t equals cos t: K3 would read as scale factor
  const testing::ScratchDirectory scratch;
  const nlohmann::json fields =
      run_on(scratch.write("positions.csv", positions_csv(truth, 4, 1, true, 0.0, 1)),
             {{"output_unit", "mA"}, {"gravity_m_s2", kGravity}});
  EXPECT_NEAR(value_of(fields, "bias"), truth.bias_g, 1e-12);
  EXPECT_NEAR(value_of(fields, "scale_factor"), truth.scale_factor, 1e-12);
  EXPECT_NEAR(value_of(fields, "second_order"), truth.second_order, 1e-12);
  EXPECT_NEAR(value_of(fields, "misalignment_about_output_axis"), truth.misalignment_rad, 1e-12);
  EXPECT_TRUE(fields.at("third_order").is_null());
  EXPECT_TRUE(fields.at("cross_coupling_ip").is_null());
  EXPECT_FALSE(fields.at("scale_factor").contains("uncertainty"));
  EXPECT_EQ(fields.at("degrees_of_freedom"), 0);
  ASSERT_EQ(fields.at("warnings").size(), 2u);
  EXPECT_THAT(fields.at("warnings")[0].get<std::string>(), HasSubstr("do not identify K3 and K_ip"));
  EXPECT_THAT(fields.at("warnings")[1].get<std::string>(), HasSubstr("no uncertainty"));
}

// The head's angle written over two turns (0..630 deg) or negative (-720..-90) is the same position
// as within one turn: four positions identify the same terms and give the same figures. In radians
// sin(2 x 450 deg) is 1.1e-16, not 0, and the sin 2t column of that rounding made K_ip fitted, 1.85e9
// +- 2.3e9 1/g, from noise of 1e-6.
TEST(Tumble, AnglesBeyondOneTurnOrNegativeAreTheSamePositions) {
  Truth truth;
  truth.third_order = 0.0;  // at 0, 90, 180, 270 deg cos 3t equals cos t
  sim::AccelerometerTumbleOptions options;
  options.truth = truth;
  options.positions = 4;
  options.gravity_m_s2 = kGravity;
  const testing::ScratchDirectory scratch;
  const auto positions = [&](double offset_deg) {
    std::string csv = "angle_deg,output\n";
    for (int turn = 0; turn < 2; ++turn) {
      for (int k = 0; k < 4; ++k) {
        const double angle = 90.0 * k;
        const double noise = 1e-6 * ((k + turn) % 3 == 0 ? 1.0 : -0.5);  // fixed offsets: 4 degrees of freedom
        csv += fmt::format("{},{:.17g}\n", angle + 360.0 * turn + offset_deg,
                           sim::accelerometer_tumble_output(options, angle, false) + noise);
      }
    }
    return csv;
  };
  const nlohmann::json parameters = {{"output_unit", "mA"}, {"gravity_m_s2", kGravity}};
  const nlohmann::json within = run_on(scratch.write("within.csv", positions(0.0)), parameters);
  for (const double offset_deg : {360.0, -720.0}) {
    const nlohmann::json fields = run_on(scratch.write("turns.csv", positions(offset_deg)), parameters);
    EXPECT_TRUE(fields.at("cross_coupling_ip").is_null()) << offset_deg << " " << fields.at("cross_coupling_ip");
    EXPECT_TRUE(fields.at("third_order").is_null()) << offset_deg;
    ASSERT_FALSE(fields.at("warnings").empty());
    EXPECT_THAT(fields.at("warnings")[0].get<std::string>(),
                HasSubstr("8 positions at 4 head angles do not identify K3 and K_ip"));
    for (const char* name : {"bias", "scale_factor", "second_order", "misalignment_about_output_axis"}) {
      EXPECT_EQ(value_of(fields, name), value_of(within, name)) << offset_deg << " " << name;
    }
    EXPECT_NEAR(value_of(fields, "scale_factor"), truth.scale_factor, 1e-5 * std::abs(truth.scale_factor));
  }
}

// With noise, each coefficient's 1-sigma interval holds the truth in about 68 % of the tumbles:
// 8 positions over 2 turns leave 10 degrees of freedom, P(|t_10| <= 1) = 0.659; over 400 tumbles
// the fraction's standard error is 0.024, and the bounds are 3 of them either side.
TEST(Tumble, OneSigmaIntervalsCoverTheTruthInAboutTwoThirdsOfTheTumbles) {
  const Truth truth;
  const testing::ScratchDirectory scratch;
  constexpr int kTumbles = 400;
  const char* names[] = {"bias", "scale_factor", "second_order", "third_order", "misalignment_about_output_axis",
                         "cross_coupling_ip"};
  const double truths[] = {truth.bias_g, truth.scale_factor, truth.second_order, truth.third_order, truth.misalignment_rad, truth.cross_coupling};
  int covered[6] = {};
  for (int seed = 1; seed <= kTumbles; ++seed) {
    const nlohmann::json fields =
        run_on(scratch.write("positions.csv", positions_csv(truth, 8, 2, true, 2e-6, static_cast<std::uint64_t>(seed))),
               {{"output_unit", "mA"}, {"gravity_m_s2", kGravity}});
    for (int k = 0; k < 6; ++k) {
      const nlohmann::json& figure = fields.at(names[k]);
      if (std::abs(figure.at("value").get<double>() - truths[k]) <= figure.at("uncertainty").get<double>()) {
        ++covered[k];
      }
    }
  }
  for (int k = 0; k < 6; ++k) {
    const double fraction = static_cast<double>(covered[k]) / kTumbles;
    EXPECT_GT(fraction, 0.659 - 3 * 0.024) << names[k];
    EXPECT_LT(fraction, 0.659 + 3 * 0.024) << names[k];
  }
  // One turn of 8 positions leaves 2 degrees of freedom: the warning says how seldom the 1-sigma
  // holds (53-58 % of trials, Student's t 58 %), where nothing was said.
  const nlohmann::json one_turn =
      run_on(scratch.write("positions.csv", positions_csv(truth, 8, 1, true, 2e-6, 1)), {{"gravity_m_s2", kGravity}});
  EXPECT_THAT(one_turn.at("warnings").dump(), HasSubstr("the fit has 2 degrees of freedom: its 1-sigma uncertainties, "
                                                        "estimated from so few residuals, hold the truth in about 58 %"));
}

// Both mountings (0 and 180 deg about IA): the fixture's mounting error e and the misalignment are
// separated. Noise-free, both come back to the terms the fit leaves out (header comment of the
// spec): e^2 / 2 ~ 5e-8 in K1 and the harmonics' angle shift, K2 e ~ 5e-9 in the cross-coupling.
// One mounting alone reads their sum as the misalignment.
TEST(Tumble, BothMountingsSeparateTheMountingErrorFromTheMisalignment) {
  Truth truth;
  truth.mounting_error_rad = 3e-4;
  const testing::ScratchDirectory scratch;
  const nlohmann::json both = run_on(scratch.write("both.csv", positions_csv(truth, 8, 1, true, 0.0, 1, true)),
                                     {{"output_unit", "mA"}, {"gravity_m_s2", kGravity}});
  EXPECT_NEAR(value_of(both, "misalignment_about_output_axis"), truth.misalignment_rad, 1e-9);
  EXPECT_NEAR(value_of(both, "mounting_error"), truth.mounting_error_rad, 1e-9);
  EXPECT_EQ(both.at("mounting_error").at("unit"), "rad");
  EXPECT_NEAR(value_of(both, "scale_factor"), truth.scale_factor, 1e-7);
  EXPECT_NEAR(value_of(both, "bias"), truth.bias_g, 1e-9);
  EXPECT_NEAR(value_of(both, "cross_coupling_ip"), truth.cross_coupling, 1e-8);
  EXPECT_EQ(both.at("positions"), 16);
  EXPECT_EQ(both.at("degrees_of_freedom"), 16 - 7);
  EXPECT_EQ(both.at("residuals")[8].at("mounting").at("value"), 180.0);
  const nlohmann::json one = run_on(scratch.write("one.csv", positions_csv(truth, 8, 1, true, 0.0, 1)),
                                    {{"output_unit", "mA"}, {"gravity_m_s2", kGravity}});
  EXPECT_NEAR(value_of(one, "misalignment_about_output_axis"), truth.misalignment_rad + truth.mounting_error_rad, 1e-9);
  EXPECT_TRUE(one.at("mounting_error").is_null());
}

// With both mountings and noise, the 1-sigma intervals of the misalignment and of the mounting
// error hold the truth in about 68 % of the tumbles: 8 positions x 2 mountings x 2 turns leave 25
// degrees of freedom, P(|t_25| <= 1) = 0.673; 400 tumbles, bounds 3 standard errors (0.023).
TEST(Tumble, BothMountingsOneSigmaIntervalsCoverTheTruth) {
  Truth truth;
  truth.mounting_error_rad = -1.5e-4;
  const testing::ScratchDirectory scratch;
  constexpr int kTumbles = 400;
  int covered[2] = {};
  for (int seed = 1; seed <= kTumbles; ++seed) {
    const nlohmann::json fields = run_on(
        scratch.write("positions.csv", positions_csv(truth, 8, 2, true, 2e-6, static_cast<std::uint64_t>(seed), true)),
        {{"output_unit", "mA"}, {"gravity_m_s2", kGravity}});
    const auto within = [&](const char* name, double expected) {
      const nlohmann::json& figure = fields.at(name);
      return std::abs(figure.at("value").get<double>() - expected) <= figure.at("uncertainty").get<double>();
    };
    covered[0] += within("misalignment_about_output_axis", truth.misalignment_rad) ? 1 : 0;
    covered[1] += within("mounting_error", truth.mounting_error_rad) ? 1 : 0;
  }
  for (const int c : covered) {
    EXPECT_GT(static_cast<double>(c) / kTumbles, 0.673 - 3 * 0.023);
    EXPECT_LT(static_cast<double>(c) / kTumbles, 0.673 + 3 * 0.023);
  }
}

TEST(Tumble, CommandGivesTheSameFigures) {
  const Truth truth;
  const testing::ScratchDirectory scratch;
  const std::string path = scratch.write("positions.csv", positions_csv(truth, 8, 1, true, 0.0, 1));
  const auto run = testing::run_cli({"accelerometer-tumble", path, "--output-unit", "mA", "--gravity",
                                     fmt::format("{}", kGravity), "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json.at("procedure"), "accelerometer_tumble");
  EXPECT_EQ(json.at("clause"), "IEEE Std 1293-1998 8.3");
  EXPECT_NEAR(json.at("scale_factor").at("value").get<double>(), truth.scale_factor, 1e-12);
  EXPECT_NEAR(json.at("second_order").at("value").get<double>(), truth.second_order, 1e-12);
}

struct Refusal {
  const char* name;
  const char* content;
  const char* message;  // with the place it names, after the file name
};

class TumbleRefuses : public ::testing::TestWithParam<Refusal> {};

TEST_P(TumbleRefuses, NamingTheFileAndThePlace) {
  const testing::ScratchDirectory scratch;
  const std::string path = scratch.write("positions.csv", GetParam().content);
  const auto run = testing::run_cli({"accelerometer-tumble", path, "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_TRUE(run.out.empty());
  EXPECT_THAT(run.err, HasSubstr(path + GetParam().message));
}

INSTANTIATE_TEST_SUITE_P(
    Tumble, TumbleRefuses,
    ::testing::Values(
        Refusal{"missing_output", "angle_deg,volts\n0,1\n90,0\n180,-1\n270,0\n", ":1:1: expected a header row"},
        Refusal{"not_a_number", "angle_deg,output\n0,1\n90,x\n180,-1\n270,0\n", ":3:4"},
        Refusal{"three_positions", "angle_deg,output\n0,1\n120,-0.5\n240,-0.5\n", ": the 3 positions do not identify"},
        Refusal{"mounting_not_0_or_180", "angle_deg,output,mounting_deg\n0,1,0\n90,0,90\n180,-1,0\n270,0,0\n",
                ":3:6: mounting_deg is 90"},
        Refusal{"four_rows_two_angles", "angle_deg,output\n0,1\n180,-1\n0,1.1\n180,-0.9\n",
                ": the head angles leave 180 deg of the turn without a position (from 180 deg on)"},
        // Radians in the degrees' column, and a part of a turn: figures a million times off, no word.
        Refusal{"radians", "angle_deg,output\n0,1\n1.5708,0\n3.1416,-1\n4.7124,0\n",
                ":3: angle_deg 1.5708: the column's angles all lie within 2 pi and are not all whole degrees: radians? "
                "Give them in degrees"},
        Refusal{"part_of_a_turn", "angle_deg,output\n0,1\n45,0.7\n90,0\n135,-0.7\n",
                ": the head angles leave 225 deg of the turn without a position (from 135 deg on)"}),
    testing::NameOfParam());

TEST(Tumble, GravityOffTheEarthIsRefusedBeforeReading) {
  const auto run = testing::run_cli({"accelerometer-tumble", testing::source_path("examples/accelerometer_tumble/positions.csv"),
                                     "--gravity", "98.1", "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("98.1 m/s^2 is not a gravity on the Earth's surface"));
}

}  // namespace
}  // namespace inertest
