#include "inertest/centrifuge/centrifuge_model.h"

#include <cmath>

#include "test_util/test_util.h"

namespace inertest::centrifuge {
namespace {

constexpr double kPi = constants::kPi;
constexpr double kDegPerHourPerRadPerSecond = 3600.0 / constants::kDegree;

CentrifugeSite paper_site() {
  CentrifugeSite site;
  site.radius_m = 1.0;
  site.latitude_rad = 45.75 * constants::kDegree;
  site.gravity_m_s2 = 9.8;
  site.earth_rate_rad_s = 15.04107 / kDegPerHourPerRadPerSecond;
  return site;
}

TEST(CentrifugeModel, CentripetalAndCoriolisSpecificForce) {
  const CentrifugeSite site = paper_site();
  const double omega = std::sqrt(10.0 * 9.8);
  EXPECT_NEAR(centripetal_specific_force(site, omega), 10.0, 1e-12);
  // A_k = -2 R0 Omega omega_e sin(phi) / g, by hand.
  const double expected = -2.0 * omega * site.earth_rate_rad_s * std::sin(site.latitude_rad) / 9.8;
  EXPECT_NEAR(coriolis_specific_force(site, omega), expected, 1e-18);
  EXPECT_NEAR(expected, -1.05528e-4, 1e-9);  // 2 * 9.8995 * 7.29211e-5 * 0.716302 / 9.8
}

TEST(CentrifugeModel, SpecificForcesAtSpecialAngles) {
  CentrifugeSite site = paper_site();
  site.earth_rate_rad_s = 1e-30;  // A_k ~ 0 for a hand check
  const double omega = std::sqrt(10.0 * 9.8);
  // beta = 0, gamma = 0: the centripetal force lies along -IA, gravity along SA.
  SpecificForce f = centrifuge_specific_force(site, omega, 0.0, 0.0);
  EXPECT_NEAR(f.input, -10.0, 1e-12);
  EXPECT_NEAR(f.output, 0.0, 1e-12);
  EXPECT_NEAR(f.spin, 1.0, 1e-12);
  // beta = pi/2, gamma = pi/2: centripetal along -OA, gravity along IA.
  f = centrifuge_specific_force(site, omega, kPi / 2.0, kPi / 2.0);
  EXPECT_NEAR(f.input, 1.0, 1e-12);
  EXPECT_NEAR(f.output, -10.0, 1e-12);
  EXPECT_NEAR(f.spin, 0.0, 1e-12);
}

TEST(CentrifugeModel, InputRateOfEquationFive) {
  const CentrifugeSite site = paper_site();
  const double omega = 10.0;
  const CentrifugeErrors errors{-2e-5, 2e-5, 1e-5};
  // beta = 0, gamma = 0: w_I = -k1 Omega + omega_e cos(phi).
  EXPECT_NEAR(centrifuge_input_rate(site, errors, omega, 0.0, 0.0),
              (2e-4 + site.earth_rate_rad_s * std::cos(site.latitude_rad)) * kDegPerHourPerRadPerSecond, 1e-9);
  // beta = pi/2: w_I = omega_e sin(phi) + dOmega, whatever gamma.
  EXPECT_NEAR(centrifuge_input_rate(site, errors, omega, kPi / 2.0, 1.234),
              (site.earth_rate_rad_s * std::sin(site.latitude_rad) + 1e-5) * kDegPerHourPerRadPerSecond, 1e-9);
}

TEST(CentrifugeModel, AnglesAddUpToKOneAndKTwo) {
  const CentrifugeErrors errors = CentrifugeErrors::from_angles(1e-5, -3e-5, 2e-5, 5e-6, 7e-6);
  EXPECT_DOUBLE_EQ(errors.k1_rad, -2e-5);
  EXPECT_DOUBLE_EQ(errors.k2_rad, 2.5e-5);
  EXPECT_DOUBLE_EQ(errors.delta_omega_rad_s, 7e-6);
}

// The analytic projection agrees with a 36-point harmonic analysis of the model output, for a
// platform angle that is not a multiple of pi/2.
TEST(CentrifugeModel, HarmonicModelMatchesSampledOutput) {
  const CentrifugeSite site = paper_site();
  const double omega = std::sqrt(20.0 * 9.8);
  const double beta = 0.7;
  const DriftCoefficients q = {0.9, 1.5, 0.74, -0.022, -1.9e-4, 3.2e-4, 2.1e-4, 1.4e-5, -2.5e-5, 2.5e-5};
  const CentrifugeErrors errors{-2e-5, 2e-5, 1e-5};
  const HarmonicModel model = centrifuge_harmonic_model(site, omega, beta);
  constexpr int kSamples = 36;
  for (std::size_t h = 0; h < kHarmonicCount; ++h) {
    double sampled = 0.0;
    for (int i = 0; i < kSamples; ++i) {
      const double gamma = 2.0 * kPi * i / kSamples;
      sampled += centrifuge_model_output(q, site, errors, omega, beta, gamma) * harmonic_basis(h, gamma);
    }
    sampled *= (h == kK0 ? 1.0 : 2.0) / kSamples;
    double predicted = model.earth_rate[h] + errors.k1_rad * model.per_k1[h] + errors.k2_rad * model.per_k2[h] +
                       errors.delta_omega_rad_s * model.per_delta_omega[h];
    for (std::size_t j = 0; j < kDriftTermCount; ++j) predicted += model.structure[h][j] * q[j];
    EXPECT_NEAR(predicted, sampled, 1e-11 * std::max(1.0, std::abs(sampled))) << harmonic_name(h);
  }
}

// Hand-derived entries of Phi at beta = 0: f_I = -(A cos g + A_k), f_O = -A sin g, f_S = 1 in the
// site's g (9.8 m/s^2 here), each times 9.8 / 9.80665 in standard g, the g of the coefficients.
TEST(CentrifugeModel, StructureAtBetaZeroByHand) {
  const CentrifugeSite site = paper_site();
  const double omega = std::sqrt(10.0 * 9.8);
  const double g = 9.8 / 9.80665;  // the site's g in standard g
  const double a = 10.0 * g;
  const double a_k = coriolis_specific_force(site, omega) * g;
  const HarmonicModel model = centrifuge_harmonic_model(site, omega, 0.0);
  EXPECT_NEAR(model.structure[kK0][kF], 1.0, 1e-14);
  EXPECT_NEAR(model.structure[kK0][kI], -a_k, 1e-14);
  EXPECT_NEAR(model.structure[kK1c][kI], -a, 1e-13);
  EXPECT_NEAR(model.structure[kK1s][kO], -a, 1e-13);
  EXPECT_NEAR(model.structure[kK0][kS], g, 1e-14);
  EXPECT_NEAR(model.structure[kK0][kII], a * a / 2.0 + a_k * a_k, 1e-12);      // f_I^2
  EXPECT_NEAR(model.structure[kK2c][kII], a * a / 2.0, 1e-12);
  EXPECT_NEAR(model.structure[kK2c][kOO], -a * a / 2.0, 1e-12);                // f_O^2
  EXPECT_NEAR(model.structure[kK2s][kIO], a * a / 2.0, 1e-12);                 // f_I f_O
  EXPECT_NEAR(model.structure[kK1s][kIO], a * a_k, 1e-12);
  EXPECT_NEAR(model.structure[kK1s][kOS], -a * g, 1e-13);  // f_O f_S
  // Epsilon at beta = 0: k1c = -k1 Omega, k1s = -k2 Omega, in deg/h per rad.
  EXPECT_NEAR(model.per_k1[kK1c], -omega * kDegPerHourPerRadPerSecond, 1e-6);
  EXPECT_NEAR(model.per_k2[kK1s], -omega * kDegPerHourPerRadPerSecond, 1e-6);
  EXPECT_NEAR(model.per_delta_omega[kK0], 0.0, 1e-9);
}

}  // namespace
}  // namespace inertest::centrifuge
