// The scale factor temperature model (issue 20) through its declaration: rate-table runs made from
// K(T) = K_m (1 + k_T ΔT + k_T2 ΔT²) with known output noise, the coefficients recovered within
// their reported uncertainty, next to GJB 2426A's Kt (eq. 13).
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/procedure_spec.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

TEST(ScaleFactorTemperatureModel, RecoversAQuadraticWithinItsUncertainty) {
  const testing::ScratchDirectory scratch;
  constexpr double kReference = 36000.0, kLinear = 2.0, kQuadratic = 0.01;  // ppm/degC, ppm/degC^2
  testing::UniformSequence noise(11);
  ProcedureCall call;
  for (const double t : {20.0, -40.0, -10.0, 40.0, 60.0}) {
    const double dt = t - 20.0;
    const double k = kReference * (1.0 + (kLinear * dt + kQuadratic * dt * dt) * 1e-6);
    std::string points = "rate,output\n0,0\n";
    for (const double rate : {-300.0, -100.0, -10.0, 10.0, 100.0, 300.0}) {
      points += fmt::format("{},{}\n", rate, k * rate + 5.0 * noise.next());
    }
    points += "0,0\n";
    call.runs["runs"].push_back({t, scratch.write(fmt::format("points_{}C.csv", t), points)});
  }
  const ProcedureSpec* spec = find_procedure_spec("scale_factor_temperature_model");
  ASSERT_NE(spec, nullptr);
  call.parameters = {{"order", 2}, {"rate_unit", "deg/s"}, {"output_unit", "pulse/s"}};
  spec->check(call);
  const nlohmann::json fields = spec->run(call).fields;
  const nlohmann::json& coefficients = fields.at("scale_factor_temperature_coefficients");
  for (const auto& [name, truth] : {std::pair{"k_T", kLinear}, std::pair{"k_T2", kQuadratic}}) {
    const nlohmann::json& c = coefficients.at(name);
    EXPECT_NEAR(c.at("value").get<double>(), truth, 4.0 * c.at("uncertainty").get<double>()) << name;
    EXPECT_LT(c.at("uncertainty").get<double>(), 0.1 * truth) << name;
  }
  // GJB's one number: the largest |ΔK/K_m/ΔT|, at 60 degC: 2 + 0.01·40 = 2.4 ppm/degC.
  EXPECT_NEAR(fields.at("scale_factor_temperature_sensitivity").at("value").get<double>(), 2.4, 0.05);
  EXPECT_EQ(fields.at("points").size(), 5u);
}

TEST(ScaleFactorTemperatureModel, AnOrderNeedsEnoughRuns) {
  const ProcedureSpec* spec = find_procedure_spec("scale_factor_temperature_model");
  ASSERT_NE(spec, nullptr);
  ProcedureCall call;
  call.runs["runs"] = {{20.0, "a.csv"}, {60.0, "b.csv"}};
  call.parameters = {{"order", 2}, {"rate_unit", "deg/s"}, {"output_unit", "1"}};
  EXPECT_THROW(spec->check(call), ParameterError);
}

}  // namespace
}  // namespace inertest
