// The scale factor temperature model (issue 20) through its declaration: rate-table runs made from
// K(T) = K_m (1 + k_T ΔT + k_T2 ΔT²) with known output noise, the coefficients recovered within
// their reported uncertainty, next to GJB 2426A's Kt (eq. 13); Monte Carlo coverage of the stated
// uncertainty with the model right, with scatter the runs' uncertainties leave out, and with a cubic
// fitted as a quadratic (the Birge ratio's scaling and warning).
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/procedure_spec.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

// Of either sign of K (a negative one was refused: "no uncertainty", its u(Ki)/Km below 0).
TEST(ScaleFactorTemperatureModel, RecoversAQuadraticWithinItsUncertainty) {
  for (const double kReference : {36000.0, -36000.0}) {
    const testing::ScratchDirectory scratch;
    constexpr double kLinear = 2.0, kQuadratic = 0.01;  // ppm/degC, ppm/degC^2
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
      const std::string file = scratch.write(fmt::format("points_{}C.csv", t), points);
      call.runs["runs"].push_back({t, file, file});
    }
    const ProcedureSpec* spec = find_procedure_spec("scale_factor_temperature_model");
    ASSERT_NE(spec, nullptr);
    call.parameters = nlohmann::json{{"order", 2}, {"rate_unit", "deg/s"}, {"output_unit", "pulse/s"}};
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
}

// One Monte Carlo trial: runs at `temperatures` of K(T) = 5000 (1 + y(T − 20)·1e-6) pulse/s per deg/s,
// with an extra relative error of each run's K of `run_scatter_ppm` (normal, not in its uncertainty)
// and normal output noise of 1e-3 pulse/s; the fitted coefficients and warnings.
struct Trial {
  double k_t = 0.0, u_k_t = 0.0;
  std::vector<std::string> warnings;
};

double normal(testing::UniformSequence& uniform) {  // a sum of 12 uniforms: mean 0, variance 1
  double sum = 0.0;
  for (int i = 0; i < 12; ++i) sum += uniform.next();
  return sum;
}

template <typename RelativeChange>
Trial trial(const RelativeChange& y_ppm, std::size_t order, double run_scatter_ppm, testing::UniformSequence& uniform) {
  const testing::ScratchDirectory scratch;
  ProcedureCall call;
  for (const double t : {20.0, -40.0, -20.0, 0.0, 40.0, 60.0, 80.0}) {
    const double k = 5000.0 * (1.0 + (y_ppm(t - 20.0) + run_scatter_ppm * normal(uniform)) * 1e-6);
    std::string points = "rate,output\n";
    for (const double rate : {0.0, -300.0, -100.0, -10.0, -1.0, 1.0, 10.0, 100.0, 300.0, 0.0}) {
      points += fmt::format("{},{:.9f}\n", rate, 3.0 + k * rate + 1e-3 * normal(uniform));
    }
    const std::string file = scratch.write(fmt::format("points_{}C.csv", t), points);
    call.runs["runs"].push_back({t, file, file});
  }
  const ProcedureSpec* spec = find_procedure_spec("scale_factor_temperature_model");
  call.parameters = nlohmann::json{{"order", order}, {"rate_unit", "deg/s"}, {"output_unit", "pulse/s"}};
  spec->check(call);
  const nlohmann::json fields = spec->run(call).fields;
  const nlohmann::json& k_t = fields.at("scale_factor_temperature_coefficients").at("k_T");
  return {k_t.at("value").get<double>(), k_t.at("uncertainty").get<double>(),
          fields.at("warnings").get<std::vector<std::string>>()};
}

// The fraction of trials whose k_T lies within its stated 1-sigma of `target` (the truth, or given the
// trials, e.g. their mean).
double coverage(const std::vector<Trial>& trials, double target) {
  std::size_t covered = 0;
  for (const Trial& t : trials) covered += std::abs(t.k_t - target) <= t.u_k_t ? 1 : 0;
  return static_cast<double>(covered) / static_cast<double>(trials.size());
}

// 300 trials each: a binomial fraction near 0.68 has a standard deviation of 0.027, so the bands are
// about ±3 of them. With ν = 7 − 3 = 4 and the covariance scaled by χ²/ν when above 1, the standardised
// error is between a normal's and a Student t's with 4 degrees of freedom (P(|t_4| < 1) = 0.63).
constexpr int kTrials = 300;

double quadratic(double d) { return 2.0 * d + 0.05 * d * d; }

// kTrials trials of the quadratic K(T) fitted at order 2, each run's K off by `scatter` ppm.
std::vector<Trial> quadratic_trials(double scatter, std::uint64_t seed) {
  testing::UniformSequence uniform(seed);
  std::vector<Trial> trials;
  for (int i = 0; i < kTrials; ++i) trials.push_back(trial(quadratic, 2, scatter, uniform));
  return trials;
}

TEST(ScaleFactorTemperatureModel, UncertaintyCoversTheTruthWhenTheModelIsRight) {
  const std::vector<Trial> trials = quadratic_trials(0.0, 5);
  EXPECT_GT(coverage(trials, 2.0), 0.60);
  EXPECT_LT(coverage(trials, 2.0), 0.80);
  // The lack-of-fit warning is for scatter beyond chance: P(chi2_4 / 4 > 1 + 3 sqrt(2/4)) = 0.014.
  const auto warned = std::count_if(trials.begin(), trials.end(), [](const Trial& t) { return !t.warnings.empty(); });
  EXPECT_LT(warned, kTrials / 20);
}

TEST(ScaleFactorTemperatureModel, BirgeRatioRestoresCoverageOfScatterTheUncertaintiesLeaveOut) {
  // Each run's K off by 0.5 ppm (a chamber's repeatability, say), 10^3 times its stated uncertainty:
  // unscaled, nearly no trial would cover; scaled by the Birge ratio, about as many as a t_4's.
  const std::vector<Trial> trials = quadratic_trials(0.5, 7);
  EXPECT_GT(coverage(trials, 2.0), 0.55);
  EXPECT_LT(coverage(trials, 2.0), 0.75);
  for (const Trial& t : trials) {
    ASSERT_EQ(t.warnings.size(), 1u);
    EXPECT_THAT(t.warnings[0], ::testing::HasSubstr("chi2/dof = "));
  }
}

TEST(ScaleFactorTemperatureModel, ACubicFittedAsAQuadraticWarnsAndItsUncertaintyCoversTheFit) {
  // The brief's K(T): a cubic term of 0.002 ppm/degC^3 fitted at order 2. The quadratic's k_T is not
  // the cubic's (its estimate is biased by the cubic term, deterministically for these temperatures,
  // by about 5 Birge-scaled sigmas: no scaling of a covariance covers that); what the uncertainty
  // covers, conservatively, is the quadratic that the fit estimates (the trials' mean), and the
  // warning says to raise the order. At order 3 the truth is covered again.
  testing::UniformSequence uniform(9);
  auto cubic = [](double d) { return 2.0 * d + 0.05 * d * d + 0.002 * d * d * d; };
  std::vector<Trial> trials;
  double mean = 0.0;
  for (int i = 0; i < kTrials; ++i) {
    trials.push_back(trial(cubic, 2, 0.0, uniform));
    mean += trials.back().k_t / kTrials;
    ASSERT_EQ(trials.back().warnings.size(), 1u);
    EXPECT_THAT(trials.back().warnings[0], ::testing::HasSubstr("more than their uncertainties allow: chi2/dof = "));
  }
  EXPECT_GT(coverage(trials, mean), 0.68);
  std::vector<Trial> cubic_fits;
  for (int i = 0; i < kTrials; ++i) cubic_fits.push_back(trial(cubic, 3, 0.0, uniform));
  EXPECT_GT(coverage(cubic_fits, 2.0), 0.60);
  EXPECT_LT(coverage(cubic_fits, 2.0), 0.80);
}

TEST(ScaleFactorTemperatureModel, NoResidualDegreeOfFreedomIsSaid) {
  testing::UniformSequence uniform(3);
  const testing::ScratchDirectory scratch;
  ProcedureCall call;
  for (const double t : {20.0, -40.0, 60.0}) {
    const double k = 5000.0 * (1.0 + 2e-6 * (t - 20.0));
    std::string points = "rate,output\n";
    for (const double rate : {0.0, -300.0, -10.0, 10.0, 300.0, 0.0}) {
      points += fmt::format("{},{:.9f}\n", rate, k * rate + 1e-3 * normal(uniform));
    }
    const std::string file = scratch.write(fmt::format("points_{}C.csv", t), points);
    call.runs["runs"].push_back({t, file, file});
  }
  const ProcedureSpec* spec = find_procedure_spec("scale_factor_temperature_model");
  call.parameters = nlohmann::json{{"order", 2}, {"rate_unit", "deg/s"}, {"output_unit", "pulse/s"}};
  spec->check(call);
  const nlohmann::json warnings = spec->run(call).fields.at("warnings");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "3 runs for a polynomial of order 2: the fit leaves no residual degree of freedom, so its "
                         "uncertainties (from the runs' alone) cannot be checked against the points' scatter");
}

TEST(ScaleFactorTemperatureModel, AnOrderNeedsEnoughRuns) {
  const ProcedureSpec* spec = find_procedure_spec("scale_factor_temperature_model");
  ASSERT_NE(spec, nullptr);
  ProcedureCall call;
  call.runs["runs"] = {{20.0, "a.csv", "a.csv"}, {60.0, "b.csv", "b.csv"}};
  call.parameters = nlohmann::json{{"order", 2}, {"rate_unit", "deg/s"}, {"output_unit", "1"}};
  EXPECT_THROW(spec->check(call), ParameterError);
}

}  // namespace
}  // namespace inertest
