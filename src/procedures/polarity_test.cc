#include "inertest/procedures/polarity.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/procedures/hand_checks.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

TEST(PolarityTest, SignOfTheOutputChange) {
  const PolarityResult positive = polarity(500.0, -480.0);
  EXPECT_EQ(positive.polarity, 1);
  EXPECT_TRUE(positive.signs_opposite);
  const PolarityResult negative = polarity(-500.0, 520.0, {"pulse/s", 1});
  EXPECT_EQ(negative.polarity, -1);
  EXPECT_FALSE(*negative.pass);
}

TEST(PolarityTest, BiasLargerThanTheResponseWarns) {
  const PolarityResult result = polarity(12.0, 8.0, {"V", 1});
  EXPECT_EQ(result.polarity, 1);
  EXPECT_FALSE(result.signs_opposite);
  EXPECT_EQ(result.warnings.size(), 1u);
  EXPECT_TRUE(*result.pass);
  EXPECT_STREQ(output_sign_name(result.output_negative_rate.value), "positive");
}

TEST(PolarityTest, BadInputIsAnError) {
  EXPECT_THROW(polarity(1.0, 1.0), Error);
  EXPECT_THROW(polarity(1.0, -1.0, {"1", 2}), Error);
}

// Means of records carry their standard errors: a difference within 3 of them is noise, not a
// polarity (two records of one mean, 1e6 with a sample noise of 1 over 1000 samples, passed as
// positive).
TEST(PolarityTest, ADifferenceWithinTheRecordsNoiseIsAnError) {
  const double standard_error = 1.0 / std::sqrt(1000.0);
  try {
    polarity(1e6 + 0.069, 1e6, {"pulse/s", 1}, standard_error, standard_error);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), ::testing::HasSubstr("F(+) - F(-) = 0.069 pulse/s is within 3 standard errors (0.0447 "
                                                  "pulse/s) of zero"));
  }
  const PolarityResult result = polarity(1e6 + 0.2, 1e6, {"pulse/s", 1}, standard_error, standard_error);
  EXPECT_EQ(result.polarity, 1);
  EXPECT_EQ(result.output_positive_rate.uncertainty, standard_error);
}

TEST(HandChecksTest, FiguresAndPassFlags) {
  std::vector<HandCheck> checks(3);
  checks[0] = {"Appearance", std::nullopt, true, "1", std::nullopt, std::nullopt};
  checks[1] = {"Insulation resistance (case to power)", 150.0, std::nullopt, "MOhm", 20.0, std::nullopt};
  checks[2] = {"Power, +15 V supply", 4.2, std::nullopt, "W", std::nullopt, 4.0};
  const HandChecksResult result = hand_checks(checks);
  EXPECT_FALSE(result.all_pass);
  const nlohmann::json json = result.to_json();
  EXPECT_EQ(json.at("appearance").at("value"), 1.0);
  EXPECT_EQ(json.at("insulation_resistance_case_to_power").at("unit"), "MOhm");
  EXPECT_EQ(json.at("power_15_v_supply").at("value"), 4.2);
  EXPECT_TRUE(json.at("check_pass").at("insulation_resistance_case_to_power").get<bool>());
  EXPECT_FALSE(json.at("check_pass").at("power_15_v_supply").get<bool>());
  EXPECT_EQ(json.at("checks").at(0).at("value"), "pass");
  // A check named in Chinese keeps its name (it was "no usable name").
  EXPECT_EQ(snake_case_key("绝缘电阻 (壳体)"), "绝缘电阻_壳体");
  EXPECT_EQ(snake_case_key("绝缘电阻（壳体）"), "绝缘电阻_壳体");  // full-width parentheses separate too
  EXPECT_EQ(snake_case_key("a\u00a0b"), snake_case_key("a b"));  // a no-break space is a space
  EXPECT_EQ(snake_case_key("——"), "");  // dashes alone are no name
  // A max alone bounds the magnitude, as the plan's limit the campaign judges it with does; with a
  // min beside it, the signed value.
  const std::vector<HandCheck> offsets = {{"Offset", -0.8, std::nullopt, "V", std::nullopt, 0.5},
                                          {"Offset in range", -0.8, std::nullopt, "V", -1.0, 0.5}};
  const HandChecksResult judged = hand_checks(offsets);
  EXPECT_FALSE(judged.checks[0].pass);
  EXPECT_TRUE(judged.checks[1].pass);
}

TEST(HandChecksTest, BadInputIsAnError) {
  EXPECT_THROW(hand_checks(std::vector<HandCheck>{}), Error);
  EXPECT_THROW(hand_checks(std::vector<HandCheck>{{"a b", 1.0, {}, "1", {}, {}}, {"A-B", 2.0, {}, "1", {}, {}}}), Error);
  EXPECT_THROW(hand_checks(std::vector<HandCheck>{{"x", std::nullopt, std::nullopt, "1", {}, {}}}), Error);
  EXPECT_THROW(hand_checks(std::vector<HandCheck>{{"x", std::nullopt, true, "1", 1.0, {}}}), Error);
  EXPECT_THROW(hand_checks(std::vector<HandCheck>{{"x", 1.0, std::nullopt, "1", 2.0, 1.0}}), Error);
  EXPECT_THROW(hand_checks(std::vector<HandCheck>{{"x", 1.0, std::nullopt, "1", std::nan(""), {}}}), Error);
  EXPECT_THROW(hand_checks(std::vector<HandCheck>{{"x", 1.0, std::nullopt, "1", {}, HUGE_VAL}}), Error);
  EXPECT_THROW(hand_checks(std::vector<HandCheck>{{"x", -15.2, std::nullopt, "V", {}, -14.0}}), Error);  // |v| <= -14
  EXPECT_THROW(hand_checks(std::vector<HandCheck>{{"checks", 1.0, std::nullopt, "1", {}, {}}}), Error);
  EXPECT_THROW(hand_checks(std::vector<HandCheck>{{"--", 1.0, std::nullopt, "1", {}, {}}}), Error);
}

}  // namespace
}  // namespace inertest
