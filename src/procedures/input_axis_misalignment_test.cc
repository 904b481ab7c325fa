#include "inertest/procedures/input_axis_misalignment.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using constants::kArcsecond;
using constants::kDegree;
using ::testing::HasSubstr;

constexpr double kScale = 2.0;   // output per deg/s
constexpr double kRate = 100.0;  // deg/s

// The outputs a gyro with IA tilted by `delta` out of the plane normal to the table axis gives.
MisalignmentPosition position(double delta, double bias = 5.0) {
  return {bias + kScale * kRate * delta, bias - kScale * kRate * delta};
}

InputAxisMisalignmentOptions options() {
  InputAxisMisalignmentOptions o;
  o.scale_factor = kScale;
  o.rate = kRate;
  return o;
}

TEST(InputAxisMisalignment, TwoPositionsHandComputed) {
  // δ1 = 1e-4, δ2 = −2e-4 rad: (F+ − F−)/(2KΩ) gives them back; α = asin(√5e-8).
  const std::vector<MisalignmentPosition> positions = {position(1e-4), position(-2e-4)};
  const auto result = input_axis_misalignment(positions, options());
  const double alpha = std::asin(std::sqrt(5e-8));
  EXPECT_NEAR_RELATIVE(result.misalignment.value, alpha / kArcsecond, 1e-9);
  EXPECT_EQ(result.misalignment.unit, "arcsec");
  EXPECT_NEAR_RELATIVE(result.misalignment_deg.value, alpha / kDegree, 1e-9);
  ASSERT_EQ(result.deltas.size(), 2u);
  EXPECT_NEAR_RELATIVE(result.deltas[0].value, 1e-4 / kArcsecond, 1e-9);
  EXPECT_NEAR_RELATIVE(result.deltas[1].value, -2e-4 / kArcsecond, 1e-9);
  EXPECT_FALSE(result.mounting_error.has_value());
  // Hand value: √5e-8 rad = 2.2360680e-4 rad = 46.1219 arcsec.
  EXPECT_NEAR(result.misalignment.value, 46.1219, 1e-3);
}

// K is per deg/s whatever unit the rate is given in, as threshold and resolution take it: with K
// read per rate unit, the same gyro gave 0.0311 arcsec at 360000 deg/h and 6407 at 1.745 rad/s.
TEST(InputAxisMisalignment, TheRateInAnyUnitWithKPerDegPerSecond) {
  const std::vector<MisalignmentPosition> positions = {position(1e-4), position(-2e-4)};
  const double alpha = std::asin(std::sqrt(5e-8)) / kArcsecond;
  auto o = options();
  o.rate = kRate * 3600.0;
  o.rate_unit = "deg/h";
  EXPECT_NEAR_RELATIVE(input_axis_misalignment(positions, o).misalignment.value, alpha, 1e-9);
  o.rate = kRate * kDegree;
  o.rate_unit = "rad/s";
  EXPECT_NEAR_RELATIVE(input_axis_misalignment(positions, o).misalignment.value, alpha, 1e-9);
}

TEST(InputAxisMisalignment, FourPositionsCancelTheMountingError) {
  // IA components δx = 1e-4, δy = −2e-4, fixture tilt ε = 3e-5: δ1 = δx + ε, δ2 = δy + ε,
  // δ3 = −δx + ε, δ4 = −δy + ε.
  const double dx = 1e-4;
  const double dy = -2e-4;
  const double eps = 3e-5;
  const std::vector<MisalignmentPosition> positions = {position(dx + eps), position(dy + eps), position(-dx + eps),
                                                       position(-dy + eps)};
  const auto result = input_axis_misalignment(positions, options());
  EXPECT_NEAR_RELATIVE(result.misalignment.value, std::asin(std::hypot(dx, dy)) / kArcsecond, 1e-9);
  ASSERT_TRUE(result.mounting_error.has_value());
  EXPECT_NEAR_RELATIVE(result.mounting_error->value, eps / kArcsecond, 1e-9);
  EXPECT_NEAR_RELATIVE(result.misalignment_toward_ox->value, dx / kArcsecond, 1e-9);
  EXPECT_NEAR_RELATIVE(result.misalignment_toward_oy->value, dy / kArcsecond, 1e-9);
  // Eq. (50) as printed: asin(√(2δx² + 2δy² + 4ε²)).
  EXPECT_NEAR_RELATIVE(result.misalignment_eq50_as_printed->value,
                       std::asin(std::sqrt(2 * dx * dx + 2 * dy * dy + 4 * eps * eps)) / kArcsecond, 1e-9);
  const ProcedureSpec spec = input_axis_misalignment_spec();
  EXPECT_TRUE(procedure_json(spec, spec.fields_of(&result)).contains("mounting_error"));
  // Two positions: the four-position figures are left out of the JSON.
  const auto two = input_axis_misalignment(std::span(positions).first(2), options());
  EXPECT_FALSE(procedure_json(spec, spec.fields_of(&two)).contains("mounting_error"));
}

TEST(InputAxisMisalignment, AStuckChannelIsNamedNotReportedAsAligned) {
  // Every output the same: delta = 0 at each position, alpha = 0, which is no measurement.
  const std::vector<MisalignmentPosition> stuck = {position(0.0, 7.25), position(0.0, 7.25)};
  const auto result = input_axis_misalignment(stuck, options());
  EXPECT_EQ(result.misalignment.value, 0.0);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], HasSubstr("every output equals 7.25"));
  EXPECT_THAT(result.warnings[0], HasSubstr("stuck channel"));
  // An aligned axis that still sees the bias change between positions is a measurement.
  const std::vector<MisalignmentPosition> aligned = {position(0.0, 7.25), position(0.0, 7.5)};
  EXPECT_TRUE(input_axis_misalignment(aligned, options()).warnings.empty());
  EXPECT_TRUE(input_axis_misalignment(std::vector{position(1e-4), position(-2e-4)}, options()).warnings.empty());
}

TEST(InputAxisMisalignment, BadInputIsAnError) {
  const std::vector<MisalignmentPosition> three = {position(0), position(0), position(0)};
  try {
    input_axis_misalignment(three, options());
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("3 position(s)"));
  }
  const std::vector<MisalignmentPosition> two = {position(1e-4), position(1e-4)};
  auto o = options();
  o.scale_factor = 0.0;
  EXPECT_THROW(input_axis_misalignment(two, o), Error);
  o = options();
  o.rate = -1.0;
  EXPECT_THROW(input_axis_misalignment(two, o), Error);
  o = options();
  o.rate_unit = "deg";
  EXPECT_THROW(input_axis_misalignment(two, o), Error);
  // K given as input per output (0.5 instead of 2) makes δ 16x too large: sin > 1 here.
  const std::vector<MisalignmentPosition> large = {position(0.3), position(0.2)};
  o = options();
  o.scale_factor = 0.5;
  EXPECT_THROW(input_axis_misalignment(large, o), Error);
}

}  // namespace
}  // namespace inertest
