#include "inertest/centrifuge/drift_calibration.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <random>

#include "inertest/centrifuge/centrifuge_record.h"
#include "test_util/test_util.h"

namespace inertest::centrifuge {
namespace {

using ::testing::HasSubstr;
constexpr double kPi = constants::kPi;
constexpr double kDegPerHourPerRadPerSecond = 3600.0 / constants::kDegree;

// The result's JSON fields as its spec writes them.
nlohmann::json json_of(const DriftCalibrationResult& result) { return find_procedure_spec("centrifuge")->fields_of(&result); }

// The reference case (reference README section 1): R0 = 1 m, phi = 45.75 deg, g = 9.8 m/s^2,
// omega_e = 15.04107 deg/h, k1 = -2e-5 rad, k2 = +2e-5 rad, dOmega = 1e-5 rad/s.
DriftCalibrationOptions paper_options() {
  DriftCalibrationOptions options;
  options.site.radius_m = 1.0;
  options.site.latitude_rad = 45.75 * constants::kDegree;
  options.site.gravity_m_s2 = 9.8;
  options.site.earth_rate_rad_s = 15.04107 / kDegPerHourPerRadPerSecond;
  options.k1_rad = -2e-5;
  options.k2_rad = 2e-5;
  options.delta_omega_rad_s = 1e-5;
  return options;
}

std::vector<CentrifugeRun> table3_runs() {
  return read_centrifuge_record(testing::source_path("data/centrifuge/table3_harmonics.csv")).runs();
}

// The paper's coefficients are per its g of 9.8 m/s^2; the results are per standard g. A
// coefficient of order n (0 for D_F, 1 for D_I..D_S, 2 for D_II..D_OS) per 9.8 m/s^2 is
// (9.80665 / 9.8)^n times that per standard g: f_9.8 = f_standard * 9.80665 / 9.8.
double per_standard_g(double per_paper_g, int order) { return per_paper_g * std::pow(9.80665 / 9.8, order); }

// |actual - printed| within half a unit of the printed value's last digit, the printed value (per
// the paper's g) converted to per standard g.
void expect_to_last_digit(const Figure& actual, double printed, double last_digit, int order) {
  EXPECT_NEAR(actual.value, per_standard_g(printed, order), 0.5 * last_digit) << "printed " << printed;
}

TEST(CentrifugeDriftCalibration, ReproducesTheReferenceFitOfTable3) {
  const auto runs = table3_runs();
  ASSERT_EQ(runs.size(), 8u);
  const DriftCalibrationResult result = calibrate_drift_coefficients(runs, paper_options());
  const auto& q = result.coefficients;
  expect_to_last_digit(q[kF], 0.90605, 1e-5, 0);
  expect_to_last_digit(q[kI], 1.5366, 1e-4, 1);
  expect_to_last_digit(q[kO], 0.7431, 1e-4, 1);
  expect_to_last_digit(q[kS], -0.021962, 1e-6, 1);
  expect_to_last_digit(q[kOO], 3.2411e-4, 1e-8, 2);
  expect_to_last_digit(q[kSS], 2.0991e-4, 1e-8, 2);
  expect_to_last_digit(q[kOS], 2.5223e-5, 1e-9, 2);
  EXPECT_NEAR_RELATIVE(q[kII].value, per_standard_g(-1.9246e-4, 2), 0.01);
  EXPECT_NEAR_RELATIVE(q[kIO].value, per_standard_g(1.3698e-5, 2), 0.01);
  EXPECT_NEAR_RELATIVE(q[kIS].value, per_standard_g(-2.4943e-5, 2), 0.01);
  expect_to_last_digit(result.residual_rms, 0.0014, 1e-4, 0);
  EXPECT_EQ(result.residual_rms.unit, "deg/h");
  EXPECT_EQ(result.degrees_of_freedom, 30u);
  EXPECT_EQ(result.g_levels, 2u);
  EXPECT_EQ(q[kF].unit, "deg/h");
  EXPECT_EQ(q[kI].unit, "deg/h/g");
  EXPECT_EQ(q[kOS].unit, "deg/h/g^2");
  // The table's rounding (5e-5 deg/h) bounds what the fit can resolve: uncertainties are small
  // but present.
  ASSERT_TRUE(q[kI].uncertainty.has_value());
  EXPECT_GT(*q[kI].uncertainty, 0.0);
  EXPECT_LT(*q[kI].uncertainty, 1e-3);
  EXPECT_TRUE(result.warnings.empty());
}

TEST(CentrifugeDriftCalibration, WithoutCompensationDIIsThePapersWrongValue) {
  DriftCalibrationOptions options = paper_options();
  options.compensation = false;
  const DriftCalibrationResult result = calibrate_drift_coefficients(table3_runs(), options);
  expect_to_last_digit(result.coefficients[kI], -1.5268, 1e-4, 1);
  EXPECT_FALSE(result.compensation);
  EXPECT_EQ(result.errors.k1_rad, 0.0);
}

// Paper section 6: k1 and dOmega move D_I (and the k1c/k0 partners), k2 moves D_OS; each shift is
// exactly the difference between the uncompensated and the compensated estimates.
TEST(CentrifugeDriftCalibration, ErrorInfluenceOfEachErrorAlone) {
  const auto runs = table3_runs();
  const DriftCalibrationOptions options = paper_options();
  const DriftCalibrationResult result = calibrate_drift_coefficients(runs, options);
  ASSERT_EQ(result.influence.size(), 4u);
  const auto find = [&](const std::string& name) {
    for (const auto& i : result.influence) {
      if (i.error == name) return i;
    }
    ADD_FAILURE() << "no influence for " << name;
    return ErrorInfluence{};
  };
  const ErrorInfluence k1 = find("k1");
  const ErrorInfluence k2 = find("k2");
  const ErrorInfluence delta_omega = find("delta_omega");
  const ErrorInfluence earth = find("earth_rate");
  EXPECT_EQ(k1.magnitude.value, -2e-5);
  EXPECT_EQ(k1.magnitude.unit, "rad");
  EXPECT_EQ(delta_omega.magnitude.unit, "rad/s");
  // k1 alone: at beta = 0, k1c gets -k1 Omega = 2e-5 * 9.9 rad/s = 40.8 deg/h at 10 g (57.7 at 20 g),
  // which the fit reads as -A * D_I: about -3.1 deg/h/g.
  EXPECT_NEAR(k1.shift[kI].value, per_standard_g(-3.1145, 1), 5e-4);
  EXPECT_EQ(k1.shift[kI].unit, "deg/h/g");
  ASSERT_TRUE(k1.sensitivity.has_value());
  EXPECT_EQ((*k1.sensitivity)[kI].unit, "deg/h/g/rad");
  EXPECT_NEAR((*k1.sensitivity)[kI].value * -2e-5, k1.shift[kI].value, 1e-12);
  // k2 alone moves D_OS, not D_I; dOmega alone moves D_I through the sin(beta) constant term.
  EXPECT_GT(std::abs(k2.shift[kOS].value), 1e-2);
  EXPECT_LT(std::abs(k2.shift[kI].value), 1e-9);
  EXPECT_GT(std::abs(delta_omega.shift[kI].value), 1e-3);
  EXPECT_EQ((*delta_omega.sensitivity)[kI].unit, "deg/h/g/(rad/s)");
  EXPECT_FALSE(earth.sensitivity.has_value());
  // The paper's section 6 figures are e = -(Phi^T Phi)^-1 Phi^T epsilon with epsilon holding ONE
  // angle of 1e-5 rad (half of k1 or k2, with the simulation's sign) or dOmega = 1e-5 rad/s, PLUS
  // the Earth-rate terms. With that reading the model reproduces all five printed numbers:
  // dtheta_y2t -> D_I 1.5143, D_S -0.0418; dtheta_x2t -> D_I -0.0429, D_OS -0.0182;
  // dOmega -> D_I -0.0511.
  const auto paper_figure = [&](const ErrorInfluence& error, double amount, std::size_t j) {
    return -((*error.sensitivity)[j].value * amount + earth.shift[j].value);
  };
  EXPECT_NEAR(paper_figure(k1, -1e-5, kI), per_standard_g(1.5143, 1), 0.5e-4);
  EXPECT_NEAR(paper_figure(k1, -1e-5, kS), per_standard_g(-0.0418, 1), 0.5e-4);
  EXPECT_NEAR(paper_figure(k2, 1e-5, kI), per_standard_g(-0.0429, 1), 0.5e-4);
  EXPECT_NEAR(paper_figure(k2, 1e-5, kOS), per_standard_g(-0.0182, 2), 0.5e-4);
  EXPECT_NEAR(paper_figure(delta_omega, 1e-5, kI), per_standard_g(-0.0511, 1), 0.5e-4);
  // The shifts add up to uncompensated minus compensated, coefficient by coefficient.
  DriftCalibrationOptions uncompensated = options;
  uncompensated.compensation = false;
  const DriftCalibrationResult raw = calibrate_drift_coefficients(runs, uncompensated);
  for (std::size_t j = 0; j < kDriftTermCount; ++j) {
    const double total = k1.shift[j].value + k2.shift[j].value + delta_omega.shift[j].value + earth.shift[j].value;
    EXPECT_NEAR(total, raw.coefficients[j].value - result.coefficients[j].value,
                1e-9 * std::max(1.0, std::abs(total)))
        << drift_term_name(j);
  }
  // Unit strings parse (they are meant for Figure::in).
  for (std::size_t j = 0; j < kDriftTermCount; ++j) {
    EXPECT_NO_THROW(Unit::parse((*delta_omega.sensitivity)[j].unit));
  }
}

// --- Synthetic records from the first-order model ---

const DriftCoefficients kTrueCoefficients = {0.9043,   1.5365,  0.7431,  -0.0221,  -1.9e-4,
                                             3.2e-4,   2.1e-4,  1.4e-5,  -2.5e-5,  2.5e-5};
const CentrifugeErrors kTrueErrors{-2e-5, 2e-5, 1e-5};

std::vector<CentrifugeSampleRun> simulate(const CentrifugeSite& site, const std::vector<double>& g_levels,
                                          const std::vector<double>& betas_deg, bool irregular) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * kPi);
  std::vector<CentrifugeSampleRun> runs;
  for (double a : g_levels) {
    const double omega = std::sqrt(a * site.gravity_m_s2 / site.radius_m);
    for (double beta_deg : betas_deg) {
      CentrifugeSampleRun run;
      run.accel_g = a;
      run.beta_rad = beta_deg * constants::kDegree;
      for (int i = 0; i < 36; ++i) {
        const double gamma = irregular ? angle(random) : 2.0 * kPi * i / 36.0;
        run.gamma_rad.push_back(gamma);
        run.output.push_back(
            centrifuge_model_output(kTrueCoefficients, site, kTrueErrors, omega, run.beta_rad, gamma));
      }
      runs.push_back(run);
    }
  }
  return runs;
}

void expect_true_coefficients(const DriftCalibrationResult& result, double tolerance) {
  for (std::size_t j = 0; j < kDriftTermCount; ++j) {
    EXPECT_NEAR_RELATIVE(result.coefficients[j].value, kTrueCoefficients[j], tolerance) << drift_term_name(j);
  }
}

TEST(CentrifugeDriftCalibration, RecoversCoefficientsFromSimulatedSamples) {
  const DriftCalibrationOptions options = paper_options();
  const auto samples = simulate(options.site, {10.0, 20.0}, {0.0, 90.0, 180.0, 270.0}, false);
  const auto runs = analyse_sample_runs(samples);
  for (const auto& run : runs) {
    ASSERT_TRUE(run.harmonic_fit.has_value());
    EXPECT_EQ(run.harmonic_fit->method, HarmonicFit::Method::kDiscreteFourier);
  }
  DriftCalibrationOptions exact = options;
  exact.k1_rad = kTrueErrors.k1_rad;
  exact.k2_rad = kTrueErrors.k2_rad;
  exact.delta_omega_rad_s = kTrueErrors.delta_omega_rad_s;
  const DriftCalibrationResult result = calibrate_drift_coefficients(runs, exact);
  expect_true_coefficients(result, 1e-6);
  EXPECT_LT(result.residual_rms.value, 1e-10);
  ASSERT_TRUE(result.runs[0].harmonic_fit.has_value());
  EXPECT_LT(result.runs[0].harmonic_fit->residual_rms, 1e-10);
}

TEST(CentrifugeDriftCalibration, AStuckRunIsWarnedAbout) {
  DriftCalibrationOptions options = paper_options();
  auto samples = simulate(options.site, {10.0, 20.0}, {0.0, 90.0, 180.0, 270.0}, false);
  EXPECT_TRUE(calibrate_drift_coefficients(analyse_sample_runs(samples), options).warnings.empty());
  std::fill(samples[1].output.begin(), samples[1].output.end(), 3.5);
  const auto runs = analyse_sample_runs(samples);
  EXPECT_TRUE(runs[1].harmonic_fit->constant_output);
  const DriftCalibrationResult result = calibrate_drift_coefficients(runs, options);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], HasSubstr(fmt::format("all {} samples equal 3.5 deg/h (a stuck channel?)",
                                                        samples[1].output.size())));
}

// Samples over half a revolution give harmonics fitted over part of a turn: said, run by run.
// Irregular sampling (angles in any order) is not judged so.
TEST(CentrifugeDriftCalibration, PartOfARevolutionIsWarnedAbout) {
  const DriftCalibrationOptions options = paper_options();
  auto samples = simulate(options.site, {10.0, 20.0}, {0.0, 90.0, 180.0, 270.0}, false);
  samples[2].gamma_rad.resize(18);
  samples[2].output.resize(18);
  const DriftCalibrationResult result = calibrate_drift_coefficients(analyse_sample_runs(samples), options);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], HasSubstr("the samples cover 0.5 of a revolution"));
  const auto irregular = simulate(options.site, {10.0, 20.0}, {0.0, 90.0, 180.0, 270.0}, true);
  EXPECT_TRUE(calibrate_drift_coefficients(analyse_sample_runs(irregular), options).warnings.empty());
  // Angles in radians read as degrees: a turn spans 6.28 deg, an error that says so.
  auto radians = simulate(options.site, {10.0, 20.0}, {0.0, 90.0, 180.0, 270.0}, false);
  for (double& gamma : radians[1].gamma_rad) gamma *= constants::kDegree;
  try {
    calibrate_drift_coefficients(analyse_sample_runs(radians), options);
    ADD_FAILURE() << "a run over 6 deg was fitted";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("run at 10 g and beta = 90 deg: the samples cover 0.0175 of a revolution (6.28 "
                                       "deg of gamma): eq. (11)'s harmonics need the turn; are the angles in radians?"));
  }
}

// The coefficients are per standard g at any site: a gyro whose drift is D per standard g
// (9.80665 m/s^2, what the unit deg/h/g means to Unit::parse) calibrated at a site of 9.78 m/s^2,
// where each specific force in the site's g is 9.78 / 9.80665 of itself in standard g.
TEST(CentrifugeDriftCalibration, AnOmegaThatIsNotTheGLevelIsAnErrorAtItsRow) {
  // Table 3 with Omega = sqrt(A g / R0) of the paper's R0 = 1 m, g = 9.8 m/s^2.
  std::vector<CentrifugeRun> runs = table3_runs();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    runs[i].omega_rad_s = std::sqrt(runs[i].accel_g * 9.8 / 1.0);
    runs[i].location = {"table3.csv", i + 2, 0};
  }
  DriftCalibrationOptions options = paper_options();
  const DriftCalibrationResult consistent = calibrate_drift_coefficients(runs, options);
  // A radius of 5 m makes the same rates 50 and 100 g: the coefficients would be 5x off.
  options.site.radius_m = 5.0;
  try {
    calibrate_drift_coefficients(runs, options);
    ADD_FAILURE() << "omega at 5 m accepted as 10 g";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "table3.csv:2: centrifuge: omega_rad_s 9.899494937 at radius 5 m and gravity 9.8 m/s^2 is a g-level of "
              "50 g (Omega^2 R0 / g), not the run's accel_g 10: they differ by 400 %, more than 1 % (is --radius or "
              "--gravity wrong, or omega_rad_s in another unit?)");
  }
  // Within 1 %: levels of Omega set with 9.8 m/s^2, at a site of 9.78 m/s^2 (0.2 % apart).
  options.site.radius_m = 1.0;
  options.site.gravity_m_s2 = 9.78;
  EXPECT_NO_THROW(calibrate_drift_coefficients(runs, options));
  options.site.gravity_m_s2 = 9.8;
  runs.back().omega_rad_s = *runs.back().omega_rad_s * 1.006;  // 1.2 % in Omega^2
  EXPECT_THROW(calibrate_drift_coefficients(runs, options), Error);
  EXPECT_EQ(consistent.coefficients.size(), kDriftTermCount);
}

TEST(CentrifugeDriftCalibration, CoefficientsArePerStandardGAtAnySiteGravity) {
  DriftCalibrationOptions options = paper_options();
  options.site.gravity_m_s2 = 9.78;
  options.k1_rad = kTrueErrors.k1_rad;
  options.k2_rad = kTrueErrors.k2_rad;
  options.delta_omega_rad_s = kTrueErrors.delta_omega_rad_s;
  const CentrifugeSite& site = options.site;
  std::vector<CentrifugeRun> runs;
  for (double a : {10.0, 20.0}) {
    const double omega = std::sqrt(a * site.gravity_m_s2 / site.radius_m);
    for (double beta_deg : {0.0, 90.0, 180.0, 270.0}) {
      std::vector<double> gamma;
      std::vector<double> output;
      for (int i = 0; i < 36; ++i) {
        gamma.push_back(2.0 * kPi * i / 36.0);
        SpecificForce f = centrifuge_specific_force(site, omega, beta_deg * constants::kDegree, gamma.back());
        f = {f.input * 9.78 / 9.80665, f.output * 9.78 / 9.80665, f.spin * 9.78 / 9.80665};  // in standard g
        const DriftCoefficients r = drift_regressors(f);
        double w = centrifuge_input_rate(site, kTrueErrors, omega, beta_deg * constants::kDegree, gamma.back());
        for (std::size_t j = 0; j < kDriftTermCount; ++j) w += kTrueCoefficients[j] * r[j];
        output.push_back(w);
      }
      runs.push_back({a, omega, beta_deg * constants::kDegree, analyse_harmonics(gamma, output).amplitudes, {}, {}});
    }
  }
  const DriftCalibrationResult result = calibrate_drift_coefficients(runs, options);
  expect_true_coefficients(result, 1e-6);
  EXPECT_NEAR_RELATIVE(convert(result.coefficients[kI].value, result.coefficients[kI].unit, "deg/h/(m/s^2)"),
                       kTrueCoefficients[kI] / 9.80665, 1e-6);
  EXPECT_THAT(json_of(result).at("coefficients_g").get<std::string>(), HasSubstr("standard g"));
  EXPECT_THAT(procedure_text(*find_procedure_spec("centrifuge"), json_of(result)), HasSubstr("per standard g"));
}

// Any platform angles, three g-levels, irregular sampling (least-squares harmonic fit).
TEST(CentrifugeDriftCalibration, RecoversCoefficientsForAnyBetasAndIrregularSampling) {
  const DriftCalibrationOptions options = paper_options();
  const auto samples = simulate(options.site, {5.0, 12.0, 30.0}, {10.0, 100.0, 200.0, 330.0, 45.0}, true);
  const auto runs = analyse_sample_runs(samples);
  EXPECT_EQ(runs[0].harmonic_fit->method, HarmonicFit::Method::kLeastSquares);
  const DriftCalibrationResult result = calibrate_drift_coefficients(runs, options);
  expect_true_coefficients(result, 1e-6);
  EXPECT_EQ(result.g_levels, 3u);
}

// Beyond the paper: the unmeasured k1, k2, dOmega are estimated with the coefficients.
TEST(CentrifugeDriftCalibration, EstimatesUnmeasuredCentrifugeErrors) {
  DriftCalibrationOptions options = paper_options();
  options.k1_rad.reset();
  options.k2_rad.reset();
  options.delta_omega_rad_s.reset();
  options.estimate_errors = true;
  const auto runs = analyse_sample_runs(simulate(options.site, {10.0, 20.0}, {0.0, 90.0, 180.0, 270.0}, false));
  const DriftCalibrationResult result = calibrate_drift_coefficients(runs, options);
  expect_true_coefficients(result, 1e-6);
  ASSERT_EQ(result.estimated_errors.size(), 3u);
  EXPECT_NEAR_RELATIVE(result.estimated_errors[0].value.value, kTrueErrors.k1_rad, 1e-6);
  EXPECT_NEAR_RELATIVE(result.estimated_errors[1].value.value, kTrueErrors.k2_rad, 1e-6);
  EXPECT_NEAR_RELATIVE(result.estimated_errors[2].value.value, kTrueErrors.delta_omega_rad_s, 1e-6);
  EXPECT_EQ(result.estimated_errors[0].name, "k1");
  EXPECT_EQ(result.estimated_errors[0].value.unit, "rad");
  EXPECT_EQ(result.estimated_errors[2].value.unit, "rad/s");
  // 12 other parameters; k1 and D_I share the k1c cos(beta) column up to sqrt(A) vs A: strongly
  // correlated.
  ASSERT_EQ(result.estimated_errors[0].correlation.size(), 12u);
  double k1_with_di = 0.0;
  for (const auto& [name, rho] : result.estimated_errors[0].correlation) {
    EXPECT_LE(std::abs(rho), 1.0 + 1e-12);
    if (name == "D_I") k1_with_di = rho;
  }
  EXPECT_GT(std::abs(k1_with_di), 0.9);
  EXPECT_EQ(result.errors.k2_rad, result.estimated_errors[1].value.value);
  const nlohmann::json json = json_of(result);
  EXPECT_EQ(json["centrifuge_errors"]["k1"]["source"], "estimated");
  EXPECT_TRUE(json["centrifuge_errors"]["k1"]["correlation"].contains("D_I"));
}

// On the paper's own table the errors come out of the fit at the values that made it (which
// confirms the reconstruction of eq. 5): k1 = -2e-5, k2 = 2e-5, dOmega = 1e-5, within the
// uncertainty that the table's rounding leaves.
TEST(CentrifugeDriftCalibration, EstimatesErrorsFromTable3) {
  DriftCalibrationOptions options = paper_options();
  options.k1_rad.reset();
  options.k2_rad.reset();
  options.delta_omega_rad_s.reset();
  options.estimate_errors = true;
  const DriftCalibrationResult result = calibrate_drift_coefficients(table3_runs(), options);
  ASSERT_EQ(result.estimated_errors.size(), 3u);
  EXPECT_TRUE(result.measured_errors.empty());
  const std::array<double, 3> truth = {-2e-5, 2e-5, 1e-5};
  for (std::size_t e = 0; e < 3; ++e) {
    const Figure& value = result.estimated_errors[e].value;
    ASSERT_TRUE(value.uncertainty.has_value());
    EXPECT_NEAR(value.value, truth[e], 4.0 * *value.uncertainty) << result.estimated_errors[e].name;
    EXPECT_NEAR_RELATIVE(value.value, truth[e], 1e-3);
  }
  expect_to_last_digit(result.coefficients[kF], 0.90605, 1e-5, 0);
  expect_to_last_digit(result.coefficients[kS], -0.021962, 1e-6, 1);
}

TEST(CentrifugeDriftCalibration, OneGLevelCannotIdentifyAllTen) {
  auto runs = table3_runs();
  runs.resize(4);  // the 10 g level only
  try {
    calibrate_drift_coefficients(runs, paper_options());
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("cannot identify D_F, D_II, D_OO, D_SS"));
    EXPECT_THAT(e.message(), HasSubstr("second g-level"));
  }
}

TEST(CentrifugeDriftCalibration, TwoPlatformAnglesCannotIdentifyAllTen) {
  auto runs = table3_runs();
  std::vector<CentrifugeRun> two_betas;
  for (const auto& run : runs) {
    if (run.beta_rad < 1.6) two_betas.push_back(run);  // beta = 0 and 90 deg
  }
  EXPECT_THROW(calibrate_drift_coefficients(two_betas, paper_options()), Error);
}

TEST(CentrifugeDriftCalibration, EstimatingErrorsNeedsTwoGLevels) {
  auto runs = table3_runs();
  runs.resize(4);
  DriftCalibrationOptions options = paper_options();
  options.k1_rad.reset();
  options.estimate_errors = true;
  try {
    calibrate_drift_coefficients(runs, options);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("cannot identify"));
    EXPECT_THAT(e.message(), HasSubstr("second g-level"));
  }
}

// Platform angles that differ between g-levels: accepted when the design has full rank (20 g
// without beta = 270 deg), rejected by the rank check when it does not (20 g at beta = 0 alone
// beside 10 g at 0 and 90 deg; two angles at both levels cannot identify all ten already).
TEST(CentrifugeDriftCalibration, PlatformAnglesMayDifferBetweenGLevelsWhenTheRankIsFull) {
  DriftCalibrationOptions options = paper_options();
  options.k1_rad = kTrueErrors.k1_rad;
  options.k2_rad = kTrueErrors.k2_rad;
  options.delta_omega_rad_s = kTrueErrors.delta_omega_rad_s;
  auto samples = simulate(options.site, {10.0, 20.0}, {0.0, 90.0, 180.0, 270.0}, false);
  samples.pop_back();  // 20 g without beta = 270 deg
  const DriftCalibrationResult result = calibrate_drift_coefficients(analyse_sample_runs(samples), options);
  expect_true_coefficients(result, 1e-6);
  EXPECT_EQ(result.runs.size(), 7u);
  EXPECT_EQ(result.g_levels, 2u);

  std::vector<CentrifugeRun> runs = analyse_sample_runs(simulate(options.site, {10.0}, {0.0, 90.0}, false));
  runs.push_back(analyse_sample_runs(simulate(options.site, {20.0}, {0.0}, false)).front());
  try {
    calibrate_drift_coefficients(runs, options);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("the test cannot identify"));
    EXPECT_THAT(e.message(), HasSubstr("add g-levels or platform angles"));
  }
}

TEST(CentrifugeDriftCalibration, DuplicatedRunIsAnError) {
  auto runs = table3_runs();
  runs.push_back(runs[1]);
  runs.back().beta_rad += 2.0 * kPi;  // the same angle, one turn on
  EXPECT_THROW(calibrate_drift_coefficients(runs, paper_options()), Error);
}

TEST(CentrifugeDriftCalibration, InvalidInputsAreErrors) {
  auto runs = table3_runs();
  DriftCalibrationOptions options = paper_options();
  options.estimate_errors = true;
  options.compensation = false;
  EXPECT_THROW(calibrate_drift_coefficients(runs, options), Error);
  options = paper_options();
  options.site.radius_m = 0.0;
  EXPECT_THROW(calibrate_drift_coefficients(runs, options), Error);
  // A radius in mm and errors not in rad gave coefficients far off, silently.
  const auto message = [&](const DriftCalibrationOptions& o) {
    try {
      calibrate_drift_coefficients(runs, o);
    } catch (const Error& e) {
      return e.message();
    }
    return std::string("no error");
  };
  options = paper_options();
  options.site.radius_m = 1000.0;
  EXPECT_THAT(message(options), HasSubstr("a radius of 1000 m is longer than any centrifuge's arm (50 m): is it in mm?"));
  options = paper_options();
  options.k1_rad = -20.0;
  EXPECT_THAT(message(options), HasSubstr("k1 = -20 rad is not a small error (over 0.1): the errors are in rad and rad/s"));
  runs[2].accel_g = -1.0;
  EXPECT_THROW(calibrate_drift_coefficients(runs, paper_options()), Error);
  EXPECT_THROW(calibrate_drift_coefficients(std::vector<CentrifugeRun>{}, paper_options()), Error);
}

TEST(CentrifugeDriftCalibration, UnmeasuredErrorsAreZeroWithAWarning) {
  DriftCalibrationOptions options = paper_options();
  options.k2_rad.reset();
  const DriftCalibrationResult result = calibrate_drift_coefficients(table3_runs(), options);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], HasSubstr("k2 not measured"));
  const nlohmann::json json = json_of(result);
  EXPECT_EQ(json["centrifuge_errors"]["k2"]["source"], "not measured (0)");
  EXPECT_EQ(json["centrifuge_errors"]["k1"]["source"], "measured");
}

TEST(CentrifugeDriftCalibration, JsonHoldsTheFigures) {
  const nlohmann::json json = json_of(calibrate_drift_coefficients(table3_runs(), paper_options()));
  for (const char* name : {"D_F", "D_I", "D_O", "D_S", "D_II", "D_OO", "D_SS", "D_IO", "D_IS", "D_OS"}) {
    ASSERT_TRUE(json["coefficients"].contains(name)) << name;
    EXPECT_TRUE(json["coefficients"][name].contains("uncertainty")) << name;
  }
  EXPECT_EQ(json["coefficients"]["D_SS"]["unit"], "deg/h/g^2");
  EXPECT_EQ(json["residual_rms"]["unit"], "deg/h");
  EXPECT_TRUE(json["influence"]["k1"]["shift"].contains("D_OS"));
  EXPECT_EQ(json["runs"].size(), 8u);
  EXPECT_NEAR(json["runs"][4]["omega"]["value"].get<double>(), std::sqrt(20.0 * 9.8), 1e-12);
}

}  // namespace
}  // namespace inertest::centrifuge
