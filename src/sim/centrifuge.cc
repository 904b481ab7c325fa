#include "inertest/sim/centrifuge.h"

#include <cmath>

#include "inertest/core/units.h"

namespace inertest::sim {
namespace {

// The rotational part of the chain of Table 1 (see the header), with the rate of every angle.
ChainState chain(const Centrifuge& c, double t) {
  const CentrifugeErrors& e = c.errors;
  const double omega = c.rate_rad_s;
  const double main_angle = omega * t;
  const double platform_rate = -(omega - e.platform_rate_error);
  const double platform_angle = platform_rate * t - c.gamma0_rad;
  const double w1 = main_angle + e.wobble1_phase;
  const double w2 = platform_angle + e.wobble2_phase;
  const ChainLink links[] = {
      {Axis::kX, e.x1t, 0.0},
      {Axis::kY, e.y1t, 0.0},
      {Axis::kX, e.wobble1 * std::cos(w1), -e.wobble1 * std::sin(w1) * omega},
      {Axis::kY, e.wobble1 * std::sin(w1), e.wobble1 * std::cos(w1) * omega},
      {Axis::kZ, main_angle, omega},
      {Axis::kX, e.x2t, 0.0},
      {Axis::kY, e.y2t, 0.0},
      {Axis::kX, e.wobble2 * std::cos(w2), -e.wobble2 * std::sin(w2) * platform_rate},
      {Axis::kY, e.wobble2 * std::sin(w2), e.wobble2 * std::cos(w2) * platform_rate},
      {Axis::kZ, platform_angle, platform_rate},
      {Axis::kX, e.x3t, 0.0},
      {Axis::kZ, e.z3t, 0.0},
      {Axis::kY, -c.beta_rad, 0.0},
      {Axis::kX, e.x4, 0.0},
      {Axis::kZ, e.z4, 0.0},
      {Axis::kY, e.y5, 0.0},
      {Axis::kX, e.x5, 0.0},
      {Axis::kZ, e.z5, 0.0},
  };
  return evaluate_chain(links, std::size(links));
}

}  // namespace

double Centrifuge::gamma(double t) const { return (rate_rad_s - errors.platform_rate_error) * t + gamma0_rad; }

ChainState Centrifuge::orientation(double t) const { return chain(*this, t); }

Vector3 Centrifuge::position(double t) const {
  // Origin of the platform frames: Trans(R0, 0, 0) in the main-axis frame (frame 1). The gyro's
  // offset from the platform axis is taken as zero (the paper: every part on the platform sees
  // the same centripetal acceleration).
  const CentrifugeErrors& e = errors;
  const double main_angle = rate_rad_s * t;
  const double w1 = main_angle + e.wobble1_phase;
  const ChainLink links[] = {
      {Axis::kX, e.x1t, 0.0},
      {Axis::kY, e.y1t, 0.0},
      {Axis::kX, e.wobble1 * std::cos(w1), 0.0},
      {Axis::kY, e.wobble1 * std::sin(w1), 0.0},
      {Axis::kZ, main_angle, 0.0},
  };
  const ChainState arm = evaluate_chain(links, std::size(links));
  return multiply(arm.orientation, Vector3{radius_m, 0.0, 0.0});
}

Stimulus Centrifuge::stimulus(const Site& site, double t, double start_s, double temperature_c) const {
  const double local = t - start_s;
  const ChainState state = chain(*this, local);
  const Matrix3 ground_to_gyro = transpose(state.orientation);
  const double phi = site.latitude_deg * constants::kDegree;
  const Vector3 earth = {site.earth_rate_rad_s * std::cos(phi), 0.0, site.earth_rate_rad_s * std::sin(phi)};
  // Central differences of the position; h balances truncation (h²·Ω⁴R/12) and rounding.
  const double h = 2e-5;
  const Vector3 before = position(local - h);
  const Vector3 here = position(local);
  const Vector3 after = position(local + h);
  Vector3 velocity{};
  Vector3 acceleration{};
  for (int i = 0; i < 3; ++i) {
    velocity[i] = (after[i] - before[i]) / (2.0 * h);
    acceleration[i] = (after[i] - 2.0 * here[i] + before[i]) / (h * h);
  }
  Vector3 force = add(acceleration, scale(cross(earth, velocity), 2.0));
  force[2] += site.gravity_m_s2;
  Stimulus s;
  s.rate = add(state.angular_velocity, multiply(ground_to_gyro, earth));
  s.specific_force = scale(multiply(ground_to_gyro, force), 1.0 / constants::kStandardGravity);
  s.temperature_c = temperature_c;
  return s;
}

Rig Centrifuge::rig(const Site& site, double start_s, TemperatureProfile temperature) const {
  const Centrifuge centrifuge = *this;
  return [centrifuge, site, start_s, temperature](double t) {
    return centrifuge.stimulus(site, t, start_s, temperature(t));
  };
}

}  // namespace inertest::sim
