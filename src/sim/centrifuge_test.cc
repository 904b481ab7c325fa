// The centrifuge's full homogeneous-transform chain (Table 1 of the centrifuge paper) against the first-order
// inputs of reference section 1 (ωI of eq. 5 as the reference restates it, fI, fO, fS of eqs. 6-8).
#include <cmath>
#include <gtest/gtest.h>

#include "inertest/core/units.h"
#include "inertest/sim/centrifuge.h"

namespace inertest::sim {
namespace {

constexpr double kPi = constants::kPi;

struct FirstOrder {
  double omega_i, f_i, f_o, f_s;
};

// Reference section 1: ωI = [−(k1 cos γ + k2 sin γ)Ω + ωe cos φ] cos β + (ωe sin φ + ΔΩ) sin β,
// fI = −(A cos γ + Ak) cos β + sin β, fO = −A sin γ, fS = (A cos γ + Ak) sin β + cos β, with
// A = Ω²R0/g, and k1 = Δθy2t + Δθy2(−Ωt), k2 = Δθx2t + Δθx2(−Ωt) at the instant.
FirstOrder first_order(const Centrifuge& c, const Site& site, double t, double ak) {
  const double g = site.gravity_m_s2;
  const double gamma = c.gamma(t);
  const double phi = site.latitude_deg * constants::kDegree;
  const double we = site.earth_rate_rad_s;
  const double w2 = -(c.rate_rad_s - c.errors.platform_rate_error) * t - c.gamma0_rad + c.errors.wobble2_phase;
  const double k1 = c.errors.y2t + c.errors.wobble2 * std::sin(w2);
  const double k2 = c.errors.x2t + c.errors.wobble2 * std::cos(w2);
  const double a = c.rate_rad_s * c.rate_rad_s * c.radius_m / g;
  const double b = c.beta_rad;
  FirstOrder r;
  r.omega_i = (-(k1 * std::cos(gamma) + k2 * std::sin(gamma)) * c.rate_rad_s + we * std::cos(phi)) * std::cos(b) +
              (we * std::sin(phi) + c.errors.platform_rate_error) * std::sin(b);
  const double g_ratio = g / constants::kStandardGravity;  // the chain reports f in standard g
  r.f_i = (-(a * std::cos(gamma) + ak) * std::cos(b) + std::sin(b)) * g_ratio;
  r.f_o = -a * std::sin(gamma) * g_ratio;
  r.f_s = ((a * std::cos(gamma) + ak) * std::sin(b) + std::cos(b)) * g_ratio;
  return r;
}

Centrifuge paper_case(double beta, double a_level) {
  Centrifuge c;
  c.radius_m = 1.0;
  c.rate_rad_s = std::sqrt(a_level * 9.8 / c.radius_m);
  c.beta_rad = beta;
  c.errors.y2t = -2e-5;  // k1 = -2e-5, k2 = +2e-5, ΔΩ = 1e-5 rad/s: the case that reproduces Table 3
  c.errors.x2t = 2e-5;
  c.errors.platform_rate_error = 1e-5;
  return c;
}

TEST(SimCentrifuge, ChainAgreesWithFirstOrderInputsWithoutEarthRotation) {
  Site site{45.75, 9.8, 0.0};
  for (const double beta : {0.0, kPi / 2, kPi, 3 * kPi / 2}) {
    for (const double level : {10.0, 20.0}) {
      const Centrifuge c = paper_case(beta, level);
      const double a = level;
      for (int k = 0; k < 36; ++k) {
        const double t = (2 * kPi / c.rate_rad_s) * k / 36.0;
        const Stimulus s = c.stimulus(site, t, 0.0, 20.0);
        const FirstOrder r = first_order(c, site, t, 0.0);
        // Neglected terms are second order in the 2e-5 rad angles: Ω·θ² for rates, A·θ for forces
        // (the error angles tilt the frame by θ under a specific force A).
        EXPECT_NEAR(s.rate[0], r.omega_i, 10 * c.rate_rad_s * 4e-10) << beta << " " << level << " " << k;
        EXPECT_NEAR(s.specific_force[0], r.f_i, 3 * a * 3e-5);
        EXPECT_NEAR(s.specific_force[1], r.f_o, 3 * a * 3e-5);
        EXPECT_NEAR(s.specific_force[2], r.f_s, 3 * a * 3e-5);
      }
    }
  }
}

TEST(SimCentrifuge, ChainAgreesWithFirstOrderInputsOnTheRotatingEarth) {
  Site site{45.75, 9.8, 7.2921150e-5};
  for (const double beta : {0.0, kPi / 2, kPi, 3 * kPi / 2}) {
    const Centrifuge c = paper_case(beta, 20.0);
    const double coriolis = 2.0 * c.radius_m * c.rate_rad_s * site.earth_rate_rad_s / site.gravity_m_s2;
    const double ak = -coriolis * std::sin(site.latitude_deg * constants::kDegree);
    for (int k = 0; k < 36; ++k) {
      const double t = 0.37 + (2 * kPi / c.rate_rad_s) * k / 36.0;
      const Stimulus s = c.stimulus(site, t, 0.0, 20.0);
      const FirstOrder r = first_order(c, site, t, ak);
      EXPECT_NEAR(s.rate[0], r.omega_i, 10 * c.rate_rad_s * 4e-10 + 1e-12);
      // The first-order forces place the Coriolis term Ak outside cos γ and drop its vertical part;
      // the chain keeps 2ωe × v exactly, so they differ by at most 2·(2R0Ωωe/g) besides A·θ.
      const double bound = 3 * 20.0 * 3e-5 + 2.0 * coriolis;
      EXPECT_NEAR(s.specific_force[0], r.f_i, bound);
      EXPECT_NEAR(s.specific_force[1], r.f_o, bound);
      EXPECT_NEAR(s.specific_force[2], r.f_s, bound);
    }
  }
}

TEST(SimCentrifuge, PlatformWobbleEntersAsTheTimeVaryingK1K2) {
  Site site{45.75, 9.8, 0.0};
  Centrifuge c = paper_case(0.0, 10.0);
  c.errors.wobble2 = 1e-5;
  c.errors.wobble2_phase = 0.3;
  for (int k = 0; k < 36; ++k) {
    const double t = (2 * kPi / c.rate_rad_s) * k / 36.0;
    const Stimulus s = c.stimulus(site, t, 0.0, 20.0);
    const FirstOrder r = first_order(c, site, t, 0.0);
    // The exact kinematics add the wobble's own rate, of order Ω·w, which the first-order ωI drops:
    // the platform axis tilts back and forth once per turn.
    EXPECT_NEAR(s.rate[0], r.omega_i, 1.01 * c.rate_rad_s * c.errors.wobble2 + 10 * c.rate_rad_s * 9e-10);
  }
}

TEST(SimCentrifuge, ErrorFreeCentrifugeGivesThePureInputs) {
  Site site{30.0, 9.79, 7.2921150e-5};
  Centrifuge c;
  c.radius_m = 1.5;
  c.rate_rad_s = 5.0;
  c.beta_rad = kPi / 2;  // IA up
  const Stimulus s = c.stimulus(site, 1.234, 0.0, 20.0);
  EXPECT_NEAR(s.rate[0], site.earth_rate_rad_s * std::sin(30.0 * constants::kDegree), 1e-15);
  EXPECT_NEAR(s.specific_force[0], 9.79 / constants::kStandardGravity, 1e-4);  // + vertical Coriolis ≤ 1e-4
  const double a = 25.0 * 1.5 / constants::kStandardGravity;
  EXPECT_NEAR(std::hypot(s.specific_force[1], s.specific_force[2]), a, 2e-4 * a + 1e-4);
}

}  // namespace
}  // namespace inertest::sim
