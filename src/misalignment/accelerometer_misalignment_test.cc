#include "inertest/misalignment/accelerometer_misalignment.h"

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/misalignment/misalignment_files.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

// The result's JSON fields as its spec writes them.
nlohmann::json json_of(const AccelerometerMisalignmentResult& result) { return find_procedure_spec("accelerometer_misalignment")->fields_of(&result); }

constexpr double kArcsec = constants::kArcsecond;
constexpr double kPaperScaleFactor = 1.299;  // V/g, misalignment paper, Table 2

AccelerometerMisalignmentOptions paper_options() {
  AccelerometerMisalignmentOptions options;
  options.scale_factor = kPaperScaleFactor;
  options.output_unit = "V";
  return options;
}

std::vector<AccelerometerMisalignmentRow> table2() {
  return read_accelerometer_misalignment_positions(testing::source_path("data/misalignment/accelerometer_table2.csv"));
}

// The paper's model V = V0 + kI·(−Δθy0 − Δθy1 + Δθz2·sinβ − Δθy2·cosβ), angles in rad.
double model_output(double beta_deg, double y2, double z2, double constant, double k) {
  const double b = beta_deg * constants::kDegree;
  return k * (constant + z2 * std::sin(b) - y2 * std::cos(b));
}

TEST(AccelerometerMisalignment, ReproducesPaperTable2EveryRunAndTheMeans) {
  const AccelerometerMisalignmentResult result = accelerometer_misalignment(table2(), paper_options());
  // Table 2 of the misalignment paper, arcsec: Δθy2, Δθz2, γ.
  const std::array<std::array<double, 3>, 3> published = {{{-5.2, 20.9, 21.5}, {-5.4, 20.3, 21.0}, {-5.3, 20.2, 20.9}}};
  ASSERT_EQ(result.by_run.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(i + 1);
    EXPECT_EQ(result.by_run[i].run, static_cast<long>(i + 1));
    EXPECT_NEAR(result.by_run[i].angles.delta_theta_y2.value, published[i][0], 0.1);
    EXPECT_NEAR(result.by_run[i].angles.delta_theta_z2.value, published[i][1], 0.1);
    EXPECT_NEAR(result.by_run[i].angles.misalignment.value, published[i][2], 0.1);
    EXPECT_EQ(result.by_run[i].degrees_of_freedom, 1u);
  }
  // Means (reference README §2): Δθy2 = −5.3″, Δθz2 = 20.5″, γ = 21.1″.
  EXPECT_NEAR(result.combined.delta_theta_y2.value, -5.3, 0.1);
  EXPECT_NEAR(result.combined.delta_theta_z2.value, 20.5, 0.1);
  EXPECT_NEAR(result.combined.misalignment.value, 21.1, 0.1);
  // The standard error of the mean over the three runs, by hand from the per-run values.
  double mean = 0.0;
  for (const auto& r : result.by_run) mean += r.angles.delta_theta_y2.value / 3.0;
  double squares = 0.0;
  for (const auto& r : result.by_run) squares += std::pow(r.angles.delta_theta_y2.value - mean, 2);
  ASSERT_TRUE(result.combined.delta_theta_y2.uncertainty.has_value());
  EXPECT_NEAR_RELATIVE(*result.combined.delta_theta_y2.uncertainty, std::sqrt(squares / 2.0 / 3.0), 1e-9);
  EXPECT_NEAR_RELATIVE(result.combined.delta_theta_y2.value, mean, 1e-12);
}

TEST(AccelerometerMisalignment, PaperClosedFormsEqualLeastSquares) {
  const auto rows = table2();
  const AccelerometerMisalignmentResult result = accelerometer_misalignment(rows, paper_options());
  for (long run = 1; run <= 3; ++run) {
    std::array<double, 4> v{};  // at 0, 90, 180, 270
    for (const auto& row : rows) {
      if (row.run == run) v[static_cast<std::size_t>(row.beta_deg / 90.0)] = row.output;
    }
    const auto closed = four_position_misalignment(v[0], v[1], v[2], v[3], kPaperScaleFactor);
    const auto& angles = result.by_run[static_cast<std::size_t>(run - 1)].angles;
    EXPECT_NEAR_RELATIVE(angles.delta_theta_y2.value * kArcsec, closed[0], 1e-9);
    EXPECT_NEAR_RELATIVE(angles.delta_theta_z2.value * kArcsec, closed[1], 1e-9);
  }
}

TEST(AccelerometerMisalignment, ClosedFormsByHand) {
  // kI = 2: V(π) − V(0) = 4·Δθy2 and V(π/2) − V(3π/2) = 4·Δθz2 from the model.
  const auto angles =
      four_position_misalignment(1.0 - 2.0 * 1e-4, 1.0 + 2.0 * 3e-4, 1.0 + 2.0 * 1e-4, 1.0 - 2.0 * 3e-4, 2.0);
  EXPECT_NEAR_RELATIVE(angles[0], 1e-4, 1e-9);
  EXPECT_NEAR_RELATIVE(angles[1], 3e-4, 1e-9);
  EXPECT_THROW(four_position_misalignment(0, 0, 0, 0, 0.0), Error);
}

TEST(AccelerometerMisalignment, RecoversSyntheticAnglesFromAnyPositionsAndRuns) {
  const double y2 = -5.3 * kArcsec;
  const double z2 = 20.5 * kArcsec;
  std::vector<AccelerometerMisalignmentRow> rows;
  for (long run : {4, 7}) {
    for (double beta : {10.0, 75.0, 160.0, 230.0, 301.0}) {
      rows.push_back({beta, model_output(beta, y2, z2, 0.002 * static_cast<double>(run), 0.8), run, 0});
    }
  }
  AccelerometerMisalignmentOptions options;
  options.scale_factor = 0.8;
  const AccelerometerMisalignmentResult result = accelerometer_misalignment(rows, options);
  ASSERT_EQ(result.by_run.size(), 2u);
  EXPECT_EQ(result.by_run[0].run, 4);
  EXPECT_EQ(result.by_run[1].run, 7);
  for (const auto& run : result.by_run) {
    EXPECT_NEAR_RELATIVE(run.angles.delta_theta_y2.value * kArcsec, y2, 1e-9);
    EXPECT_NEAR_RELATIVE(run.angles.delta_theta_z2.value * kArcsec, z2, 1e-9);
    EXPECT_EQ(run.degrees_of_freedom, 2u);
  }
  EXPECT_NEAR_RELATIVE(result.combined.delta_theta_y2.value * kArcsec, y2, 1e-9);
  EXPECT_NEAR_RELATIVE(result.combined.delta_theta_z2.value * kArcsec, z2, 1e-9);
  EXPECT_NEAR_RELATIVE(result.combined.misalignment.value * kArcsec, std::hypot(y2, z2), 1e-9);
}

TEST(AccelerometerMisalignment, OneRunKeepsItsOwnLeastSquaresUncertainty) {
  std::vector<AccelerometerMisalignmentRow> rows;
  for (double beta : {0.0, 90.0, 180.0, 270.0}) rows.push_back({beta, model_output(beta, 1e-5, 2e-5, 0.0, 1.0), 1, 0});
  rows[0].output += 4e-6;  // breaks the loop V(0) + V(π) = V(π/2) + V(3π/2) by 4e-6
  AccelerometerMisalignmentOptions options;
  options.scale_factor = 1.0;
  const AccelerometerMisalignmentResult result = accelerometer_misalignment(rows, options);
  // Residuals ±1e-6 at every position (the loop vector (1, −1, 1, −1)·e/4); s² = 4e-12, and the
  // Δθy2 column (−1, 0, 1, 0) has norm² 2, so its standard error is s/√2 = 1.414e-6 rad.
  ASSERT_TRUE(result.combined.delta_theta_y2.uncertainty.has_value());
  EXPECT_NEAR_RELATIVE(*result.combined.delta_theta_y2.uncertainty * kArcsec, 2e-6 / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR_RELATIVE(result.by_run[0].residual_rms.value, 1e-6, 1e-9);
  // Δθy2 = (V(π) − V(0))/2 = 1e-5 − 2e-6.
  EXPECT_NEAR_RELATIVE(result.combined.delta_theta_y2.value * kArcsec, 1e-5 - 2e-6, 1e-9);
}

TEST(AccelerometerMisalignment, AStuckOutputIsWarnedAboutAndRealDataIsNot) {
  // Table 2's three runs: only that their mean's 1-sigma, from 2 degrees of freedom, holds the truth
  // less often than 68 % (Student's t: 58 %; 58-62 % measured over 200 simulated tests).
  const std::vector<std::string> real = accelerometer_misalignment(table2(), paper_options()).warnings;
  ASSERT_EQ(real.size(), 1u);
  EXPECT_THAT(real[0], ::testing::HasSubstr("the mean over runs has 2 degrees of freedom"));
  EXPECT_THAT(real[0], ::testing::HasSubstr("about 58 % of tests"));
  std::vector<AccelerometerMisalignmentRow> rows = table2();
  for (auto& row : rows) row.output = -0.5;
  const AccelerometerMisalignmentResult stuck = accelerometer_misalignment(rows, paper_options());
  EXPECT_EQ(stuck.combined.misalignment.value, 0.0);
  ASSERT_EQ(stuck.warnings.size(), 2u);
  EXPECT_THAT(stuck.warnings[0], ::testing::HasSubstr("every position's output equals -0.5 V (a stuck channel?)"));
  EXPECT_EQ(json_of(stuck).at("warnings"), nlohmann::json(stuck.warnings));
  EXPECT_THAT(procedure_text(*find_procedure_spec("accelerometer_misalignment"), json_of(stuck)), ::testing::HasSubstr("warning: every position's output"));
}

TEST(AccelerometerMisalignment, PositionsThatCannotSeparateNameTheAngle) {
  std::vector<AccelerometerMisalignmentRow> rows = {{0, 0.1, 1, 5}, {180, 0.2, 1, 6}, {360 + 180, 0.3, 1, 7}};
  AccelerometerMisalignmentOptions options;
  options.scale_factor = 1.0;
  options.source = "acc.csv";
  try {
    accelerometer_misalignment(rows, options);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), ::testing::HasSubstr("cannot separate delta_theta_z2"));
    EXPECT_THAT(e.message(), ::testing::HasSubstr("run 1"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("acc.csv:5"));
  }
}

TEST(AccelerometerMisalignment, ZeroScaleFactorIsAnError) {
  AccelerometerMisalignmentOptions options;
  EXPECT_THAT([&] { accelerometer_misalignment(table2(), options); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("scale factor kI must be finite and nonzero")));
}

TEST(AccelerometerMisalignment, RepeatedPositionWithinARunIsAnError) {
  std::vector<AccelerometerMisalignmentRow> rows = {{0, 0.1, 1, 5}, {90, 0.2, 1, 6}, {0, 0.3, 1, 7}};
  AccelerometerMisalignmentOptions options;
  options.scale_factor = 1.0;
  options.source = "acc.csv";
  try {
    accelerometer_misalignment(rows, options);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.location()->line, 7u);
    EXPECT_THAT(e.message(), ::testing::HasSubstr("first at line 5"));
  }
}

TEST(AccelerometerMisalignment, NonIntegerRunIsAnErrorAtItsLine) {
  testing::ScratchDirectory scratch;
  const std::string path = scratch.write("acc.csv", "beta_deg,output,run\n0,0.1,1\n90,0.2,1.5\n");
  EXPECT_THAT([&] { read_accelerometer_misalignment_positions(path); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("acc.csv:3")));
}

TEST(AccelerometerMisalignment, JsonHasTheFiguresAndByRun) {
  const nlohmann::json json = json_of(accelerometer_misalignment(table2(), paper_options()));
  for (const char* key : {"delta_theta_y2", "delta_theta_z2", "misalignment"}) {
    EXPECT_EQ(json.at(key).at("unit"), "arcsec") << key;
    EXPECT_EQ(json.at("by_run").at(0).at(key).at("unit"), "arcsec") << key;
  }
  EXPECT_EQ(json.at("by_run").size(), 3u);
  EXPECT_EQ(json.at("by_run").at(1).at("run"), 2);
}

}  // namespace
}  // namespace inertest
