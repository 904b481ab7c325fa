#include "inertest/misalignment/gyro_misalignment.h"

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
nlohmann::json json_of(const GyroMisalignmentResult& result) { return find_procedure_spec("gyro_misalignment")->fields_of(&result); }

constexpr double kArcsec = constants::kArcsecond;
constexpr double kPaperScaleFactor = -2.9222;  // V/(deg/s), misalignment paper, Table 1

// The paper's five positions V1..V5 as (alpha, beta) in deg.
constexpr std::array<std::array<double, 2>, 5> kPaperPositions = {{{0, 0}, {0, 180}, {180, 180}, {90, 180}, {0, 90}}};

struct TrueAngles {
  double y0, x0, y1, y2, z2;  // rad
};

// Output of the model V = V0 + kI·ωI averaged over whole revolutions (reference README §2): the
// Earth-rate terms average out, the rest is ω times the angle combination.
double model_output(const TrueAngles& t, double alpha_deg, double beta_deg, double rate_dps, double v0, double k) {
  const double a = alpha_deg * constants::kDegree;
  const double b = beta_deg * constants::kDegree;
  const double input =
      rate_dps * (-t.y0 * std::cos(b) + t.x0 * std::sin(b) - t.y1 + t.z2 * std::sin(a) - t.y2 * std::cos(a));
  return v0 + k * input;
}

std::vector<GyroMisalignmentRow> synthetic_rows(const TrueAngles& t,
                                                const std::vector<std::array<double, 2>>& positions,
                                                const std::vector<double>& rates, double k) {
  std::vector<GyroMisalignmentRow> rows;
  for (double rate : rates) {
    for (std::size_t p = 0; p < positions.size(); ++p) {
      const double v0 = 0.013 * static_cast<double>(p) - 0.021;  // a different bias at each position
      for (double sign : {1.0, -1.0}) {
        rows.push_back({positions[p][0], positions[p][1], sign * rate,
                        model_output(t, positions[p][0], positions[p][1], sign * rate, v0, k), 0});
      }
    }
  }
  return rows;
}

void expect_angles(const GyroMisalignmentAngles& a, const TrueAngles& t, double tolerance) {
  EXPECT_NEAR_RELATIVE(a.delta_theta_y0.value * kArcsec, t.y0, tolerance);
  EXPECT_NEAR_RELATIVE(a.delta_theta_x0.value * kArcsec, t.x0, tolerance);
  EXPECT_NEAR_RELATIVE(a.delta_theta_y1.value * kArcsec, t.y1, tolerance);
  EXPECT_NEAR_RELATIVE(a.delta_theta_y2.value * kArcsec, t.y2, tolerance);
  EXPECT_NEAR_RELATIVE(a.delta_theta_z2.value * kArcsec, t.z2, tolerance);
  EXPECT_NEAR_RELATIVE(a.misalignment.value * kArcsec, std::hypot(t.y2, t.z2), tolerance);
  EXPECT_EQ(a.misalignment.unit, "arcsec");
}

GyroMisalignmentOptions paper_options() {
  GyroMisalignmentOptions options;
  options.scale_factor = kPaperScaleFactor;
  options.output_unit = "V";
  return options;
}

std::string table1_path() { return testing::source_path("data/misalignment/gyro_table1.csv"); }

TEST(GyroMisalignment, ReproducesPaperTable1AtEveryRate) {
  const auto rows = read_gyro_misalignment_positions(table1_path());
  const GyroMisalignmentResult result = gyro_misalignment(rows, paper_options());
  // Table 1 of the misalignment paper, arcsec: Δθy0, Δθx0, Δθy1, Δθy2, Δθz2, γ.
  const std::array<std::array<double, 7>, 3> published = {{
      {20, -7.6, 2.3, -54.0, -162.2, 55.4, 171.4},
      {30, -7.4, 2.4, -53.7, -162.2, 55.8, 171.5},
      {40, -7.5, 2.4, -53.8, -162.0, 56.3, 171.5},
  }};
  ASSERT_EQ(result.by_rate.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& r = result.by_rate[i];
    SCOPED_TRACE(r.rate_dps);
    EXPECT_EQ(r.rate_dps, published[i][0]);
    const GyroMisalignmentAngles& a = r.fit.angles;
    EXPECT_NEAR(a.delta_theta_y0.value, published[i][1], 0.1);
    EXPECT_NEAR(a.delta_theta_x0.value, published[i][2], 0.1);
    EXPECT_NEAR(a.delta_theta_y1.value, published[i][3], 0.1);
    EXPECT_NEAR(a.delta_theta_y2.value, published[i][4], 0.1);
    EXPECT_NEAR(a.delta_theta_z2.value, published[i][5], 0.1);
    EXPECT_NEAR(a.misalignment.value, published[i][6], 0.1);
    // Five equations, five unknowns: no residual, no uncertainty.
    EXPECT_EQ(r.fit.degrees_of_freedom, 0u);
    EXPECT_FALSE(a.delta_theta_y0.uncertainty.has_value());
  }
  // All rates together: 15 equations, 10 degrees of freedom, uncertainties from the residuals.
  EXPECT_EQ(result.combined.equation_count, 15u);
  EXPECT_EQ(result.combined.degrees_of_freedom, 10u);
  ASSERT_TRUE(result.combined.angles.delta_theta_y2.uncertainty.has_value());
  EXPECT_GT(*result.combined.angles.delta_theta_y2.uncertainty, 0.0);
  ASSERT_TRUE(result.combined.angles.misalignment.uncertainty.has_value());
}

TEST(GyroMisalignment, CombinedEqualsMeanOfRatesWhenPositionsAgree) {
  const GyroMisalignmentResult result =
      gyro_misalignment(read_gyro_misalignment_positions(table1_path()), paper_options());
  double sum = 0.0;
  for (const auto& r : result.by_rate) sum += r.fit.angles.delta_theta_z2.value;
  EXPECT_NEAR_RELATIVE(result.combined.angles.delta_theta_z2.value, sum / 3.0, 1e-12);
}

TEST(GyroMisalignment, PaperClosedFormsEqualLeastSquaresOnTable1) {
  const auto rows = read_gyro_misalignment_positions(table1_path());
  const GyroMisalignmentResult result = gyro_misalignment(rows, paper_options());
  for (const auto& r : result.by_rate) {
    SCOPED_TRACE(r.rate_dps);
    FivePositionOutputs outputs;
    for (const auto& row : rows) {
      if (std::abs(row.rate_dps) != r.rate_dps) continue;
      for (std::size_t p = 0; p < 5; ++p) {
        if (row.alpha_deg == kPaperPositions[p][0] && row.beta_deg == kPaperPositions[p][1]) {
          (row.rate_dps > 0 ? outputs.plus : outputs.minus)[p] = row.output;
        }
      }
    }
    const auto closed = five_position_misalignment(outputs, kPaperScaleFactor, r.rate_dps);
    const auto& a = r.fit.angles;
    EXPECT_NEAR_RELATIVE(a.delta_theta_y0.value * kArcsec, closed[0], 1e-9);
    EXPECT_NEAR_RELATIVE(a.delta_theta_x0.value * kArcsec, closed[1], 1e-9);
    EXPECT_NEAR_RELATIVE(a.delta_theta_y1.value * kArcsec, closed[2], 1e-9);
    EXPECT_NEAR_RELATIVE(a.delta_theta_y2.value * kArcsec, closed[3], 1e-9);
    EXPECT_NEAR_RELATIVE(a.delta_theta_z2.value * kArcsec, closed[4], 1e-9);
  }
}

TEST(GyroMisalignment, ClosedFormsRecoverSyntheticAnglesByHand) {
  // Hand check of the closed forms on the model with only Δθy2 = 100″, kI = 2, ω = 10: the angle
  // term −Δθy2·cosα is −Δθy2 at V1, V2, V5 (α = 0), +Δθy2 at V3 (α = 180°), 0 at V4 (α = 90°), so
  // Δθy2 = (D3 − D2)/(4kω) = (40·Δθy2 + 40·Δθy2)/80 and every other form cancels.
  const double y2 = 100.0 * kArcsec;
  FivePositionOutputs outputs;
  const std::array<double, 5> combination = {-y2, -y2, y2, 0.0, -y2};  // −Δθy2·cosα at each position
  for (std::size_t p = 0; p < 5; ++p) {
    outputs.plus[p] = 0.5 + 2.0 * 10.0 * combination[p];
    outputs.minus[p] = 0.5 - 2.0 * 10.0 * combination[p];
  }
  const auto angles = five_position_misalignment(outputs, 2.0, 10.0);
  EXPECT_NEAR(angles[0], 0.0, 1e-18);
  EXPECT_NEAR(angles[1], 0.0, 1e-18);
  EXPECT_NEAR(angles[2], 0.0, 1e-18);
  EXPECT_NEAR_RELATIVE(angles[3], y2, 1e-12);
  EXPECT_NEAR(angles[4], 0.0, 1e-18);
}

TEST(GyroMisalignment, RecoversSyntheticAnglesFromPaperPositions) {
  const TrueAngles truth{-7.5 * kArcsec, 2.4 * kArcsec, -53.8 * kArcsec, -162.0 * kArcsec, 56.3 * kArcsec};
  const std::vector<std::array<double, 2>> positions(kPaperPositions.begin(), kPaperPositions.end());
  const auto rows = synthetic_rows(truth, positions, {20, 30, 40}, kPaperScaleFactor);
  const GyroMisalignmentResult result = gyro_misalignment(rows, paper_options());
  for (const auto& r : result.by_rate) expect_angles(r.fit.angles, truth, 1e-9);
  expect_angles(result.combined.angles, truth, 1e-9);
  EXPECT_LT(result.combined.residual_rms.value, 1e-9);
}

TEST(GyroMisalignment, RecoversSyntheticAnglesFromAnyIdentifyingPositions) {
  // Twelve positions at odd angles and one rate: over-determined, exact data, zero residuals.
  const TrueAngles truth{12.0 * kArcsec, -31.0 * kArcsec, 4.5 * kArcsec, 88.0 * kArcsec, -17.0 * kArcsec};
  std::vector<std::array<double, 2>> positions;
  for (double alpha : {0.0, 120.0, 240.0}) {
    for (double beta : {30.0, 100.0, 215.0, 300.0}) positions.push_back({alpha, beta});
  }
  const auto rows = synthetic_rows(truth, positions, {15.0}, 0.75);
  GyroMisalignmentOptions options;
  options.scale_factor = 0.75;
  const GyroMisalignmentResult result = gyro_misalignment(rows, options);
  ASSERT_EQ(result.by_rate.size(), 1u);
  expect_angles(result.by_rate[0].fit.angles, truth, 1e-9);
  EXPECT_EQ(result.by_rate[0].fit.degrees_of_freedom, 7u);
  ASSERT_EQ(result.by_rate[0].fit.residuals.size(), 12u);
  for (const auto& r : result.by_rate[0].fit.residuals) EXPECT_NEAR(r.residual_arcsec, 0.0, 1e-9);
  ASSERT_TRUE(result.by_rate[0].fit.angles.delta_theta_x0.uncertainty.has_value());
  EXPECT_NEAR(*result.by_rate[0].fit.angles.delta_theta_x0.uncertainty, 0.0, 1e-9);
}

TEST(GyroMisalignment, AStuckOutputIsWarnedAboutAndRealDataIsNot) {
  const std::vector<std::array<double, 2>> positions(kPaperPositions.begin(), kPaperPositions.end());
  const TrueAngles truth{-7.5 * kArcsec, 2.4 * kArcsec, -53.8 * kArcsec, -162.0 * kArcsec, 56.3 * kArcsec};
  auto rows = synthetic_rows(truth, positions, {20}, kPaperScaleFactor);
  EXPECT_TRUE(gyro_misalignment(rows, paper_options()).warnings.empty());
  for (auto& row : rows) row.output = 0.125;
  const GyroMisalignmentResult stuck = gyro_misalignment(rows, paper_options());
  EXPECT_EQ(stuck.combined.angles.misalignment.value, 0.0);
  ASSERT_EQ(stuck.warnings.size(), 1u);
  EXPECT_THAT(stuck.warnings[0], ::testing::HasSubstr("every position's output equals 0.125 V (a stuck channel?)"));
  EXPECT_EQ(json_of(stuck).at("warnings"), nlohmann::json(stuck.warnings));
  EXPECT_THAT(procedure_text(*find_procedure_spec("gyro_misalignment"), json_of(stuck)), ::testing::HasSubstr("warning: every position's output"));
}

TEST(GyroMisalignment, ResidualsAndUncertaintiesOfAnOverDeterminedSetByHand) {
  // The paper's positions plus V6 (180°, 0): g6 = −Δθy0 − Δθy1 + Δθy2 closes the loop
  // g1 − g2 + g3 − g6 = 0, so a disturbance e on equation 6 leaves the residuals c·e/4 with
  // c = (−1, 1, −1, 0, 0, 1) and s² = e²/4 (one degree of freedom). The columns of Δθy0, Δθy1,
  // Δθy2 over V1, V2, V3, V6 are orthogonal with norm² 4, so their standard errors are s/2 = e/4
  // and Δθy0 = −e/4; Δθx0 = g5 + Δθy1 + Δθy2 has the variance s² + s²/4 + s²/4 = 3s²/2.
  const double e = 6.0;  // arcsec
  std::vector<std::array<double, 2>> positions(kPaperPositions.begin(), kPaperPositions.end());
  positions.push_back({180, 0});
  auto rows = synthetic_rows({0, 0, 0, 0, 0}, positions, {10.0}, 1.0);
  ASSERT_EQ(rows[10].rate_dps, 10.0);
  rows[10].output += 2.0 * 1.0 * 10.0 * e * kArcsec;  // V6(+): (V(+) − V(−))/(2kω) raised by e
  GyroMisalignmentOptions options;
  options.scale_factor = 1.0;
  const GyroMisalignmentFit fit = gyro_misalignment(rows, options).by_rate.at(0).fit;
  EXPECT_EQ(fit.degrees_of_freedom, 1u);
  const std::array<double, 6> expected_residuals = {-e / 4, e / 4, -e / 4, 0.0, 0.0, e / 4};
  ASSERT_EQ(fit.residuals.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(fit.residuals[i].residual_arcsec, expected_residuals[i], 1e-9) << i;
  EXPECT_NEAR(fit.residual_rms.value, e / (2.0 * std::sqrt(6.0)), 1e-9);
  EXPECT_NEAR(fit.angles.delta_theta_y0.value, -e / 4, 1e-9);
  EXPECT_NEAR(*fit.angles.delta_theta_y0.uncertainty, e / 4, 1e-9);
  EXPECT_NEAR(*fit.angles.delta_theta_y1.uncertainty, e / 4, 1e-9);
  EXPECT_NEAR(*fit.angles.delta_theta_y2.uncertainty, e / 4, 1e-9);
  EXPECT_NEAR(*fit.angles.delta_theta_x0.uncertainty, e / 2.0 * std::sqrt(1.5), 1e-9);
}

TEST(GyroMisalignment, PositionsThatCannotSeparateNameTheAngles) {
  // Without V5 no position has sin(beta) != 0: Δθx0 is not identified.
  const auto rows = read_gyro_misalignment_positions(table1_path());
  std::vector<GyroMisalignmentRow> without_v5;
  for (const auto& row : rows) {
    if (!(row.alpha_deg == 0 && row.beta_deg == 90)) without_v5.push_back(row);
  }
  GyroMisalignmentOptions options = paper_options();
  options.source = "table1.csv";
  try {
    gyro_misalignment(without_v5, options);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), ::testing::HasSubstr("delta_theta_x0"));
    EXPECT_THAT(e.message(), ::testing::HasSubstr("cannot separate"));
    EXPECT_THAT(e.message(), ::testing::Not(::testing::HasSubstr("delta_theta_y0")));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("table1.csv"));
  }
}

TEST(GyroMisalignment, DependentPositionsNameTheDependentAngle) {
  // alpha always 0: Δθy1 and Δθy2 enter every equation as −(Δθy1 + Δθy2); Δθz2 is absent.
  const TrueAngles truth{1e-5, 2e-5, 3e-5, 4e-5, 5e-5};
  const auto rows = synthetic_rows(truth, {{0, 0}, {0, 90}, {0, 180}, {0, 270}, {0, 45}}, {10.0}, 1.0);
  GyroMisalignmentOptions options;
  options.scale_factor = 1.0;
  try {
    gyro_misalignment(rows, options);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), ::testing::HasSubstr("delta_theta_z2"));
    EXPECT_THAT(e.message(),
                ::testing::AnyOf(::testing::HasSubstr("delta_theta_y1"), ::testing::HasSubstr("delta_theta_y2")));
  }
}

TEST(GyroMisalignment, FewerPositionsThanAnglesIsAnErrorNamingAngles) {
  const auto rows = synthetic_rows({0, 0, 0, 0, 0}, {{0, 0}, {0, 180}}, {10.0}, 1.0);
  GyroMisalignmentOptions options;
  options.scale_factor = 1.0;
  EXPECT_THAT([&] { gyro_misalignment(rows, options); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("2 equation(s) for 5 unknowns) cannot separate")));
}

TEST(GyroMisalignment, MissingDirectionIsAnErrorAtItsLine) {
  auto rows = read_gyro_misalignment_positions(table1_path());
  // Drop V4(−) at 30 deg/s; the error points at the line of V4(+) at 30 deg/s.
  std::size_t plus_line = 0;
  std::erase_if(rows, [&](const GyroMisalignmentRow& r) {
    if (r.alpha_deg == 90 && r.rate_dps == 30) plus_line = r.line;
    return r.alpha_deg == 90 && r.rate_dps == -30;
  });
  GyroMisalignmentOptions options = paper_options();
  options.source = "table1.csv";
  try {
    gyro_misalignment(rows, options);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    ASSERT_TRUE(e.location().has_value());
    EXPECT_EQ(e.location()->line, plus_line);
    EXPECT_THAT(e.message(), ::testing::HasSubstr("no row at -30 deg/s"));
  }
}

TEST(GyroMisalignment, ZeroScaleFactorIsAnError) {
  const auto rows = read_gyro_misalignment_positions(table1_path());
  GyroMisalignmentOptions options;
  options.scale_factor = 0.0;
  EXPECT_THAT([&] { gyro_misalignment(rows, options); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("scale factor kI must be finite and nonzero")));
  EXPECT_THROW(five_position_misalignment({}, 0.0, 20.0), Error);
}

TEST(GyroMisalignment, ZeroRateAndAnUnpairedRepeatAreErrors) {
  std::vector<GyroMisalignmentRow> rows = {{0, 0, 0.0, 1.0, 7}};
  GyroMisalignmentOptions options;
  options.scale_factor = 1.0;
  EXPECT_THAT([&] { gyro_misalignment(rows, options); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("rate_dps is zero")));
  // A position read twice at +ω and once at −ω: its second reading has no partner.
  rows = {{0, 0, 10.0, 1.0, 3}, {0, 0, -10.0, 0.5, 5}, {0, 0, 10.0, 1.5, 9}};
  EXPECT_THAT([&] { gyro_misalignment(rows, options); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("has no row at -10 deg/s")));
}

// Repeated readings of each position (a lab's practice; they were refused as duplicate rows) are
// more equations: the same angles from exact data, with the degrees of freedom of every reading.
TEST(GyroMisalignment, RepeatedReadingsAreMoreEquations) {
  const TrueAngles truth{-7.5 * kArcsec, 2.4 * kArcsec, -53.8 * kArcsec, -162.0 * kArcsec, 56.3 * kArcsec};
  const std::vector<std::array<double, 2>> positions(kPaperPositions.begin(), kPaperPositions.end());
  std::vector<GyroMisalignmentRow> rows = synthetic_rows(truth, positions, {20}, kPaperScaleFactor);
  const std::vector<GyroMisalignmentRow> once = rows;
  rows.insert(rows.end(), once.begin(), once.end());
  const GyroMisalignmentResult result = gyro_misalignment(rows, paper_options());
  expect_angles(result.combined.angles, truth, 1e-9);
  EXPECT_EQ(result.combined.equation_count, 2 * positions.size());
  EXPECT_EQ(result.combined.degrees_of_freedom, 2 * positions.size() - 5);
}

TEST(GyroMisalignment, JsonHasTheFiguresAndByRate) {
  const GyroMisalignmentResult result =
      gyro_misalignment(read_gyro_misalignment_positions(table1_path()), paper_options());
  const nlohmann::json json = json_of(result);
  for (const char* key :
       {"delta_theta_y0", "delta_theta_x0", "delta_theta_y1", "delta_theta_y2", "delta_theta_z2", "misalignment"}) {
    EXPECT_EQ(json.at(key).at("unit"), "arcsec") << key;
    EXPECT_EQ(json.at("by_rate").at(0).at(key).at("unit"), "arcsec") << key;
  }
  EXPECT_EQ(json.at("by_rate").size(), 3u);
  EXPECT_EQ(json.at("by_rate").at(2).at("rate_dps"), 40.0);
}

}  // namespace
}  // namespace inertest
