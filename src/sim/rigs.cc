#include "inertest/sim/rigs.h"

#include <cmath>

#include "inertest/core/units.h"

namespace inertest::sim {

Vector3 Site::earth_rate_enu() const {
  const double phi = latitude_deg * constants::kDegree;
  return {0.0, earth_rate_rad_s * std::cos(phi), earth_rate_rad_s * std::sin(phi)};
}

Vector3 Site::specific_force_enu_g() const { return {0.0, 0.0, gravity_m_s2 / constants::kStandardGravity}; }

double normal_gravity(double latitude_deg) {
  // WGS 84 (NIMA TR8350.2, eq. 4-1): γ = γe (1 + k sin²φ) / √(1 − e² sin²φ).
  const double s2 = std::pow(std::sin(latitude_deg * constants::kDegree), 2);
  return 9.7803253359 * (1.0 + 0.00193185265241 * s2) / std::sqrt(1.0 - 0.00669437999013 * s2);
}

Matrix3 mounting(const Vector3& input_axis, const Vector3& output_axis) {
  const Vector3 spin_axis = cross(input_axis, output_axis);
  return {{{input_axis[0], output_axis[0], spin_axis[0]},
           {input_axis[1], output_axis[1], spin_axis[1]},
           {input_axis[2], output_axis[2], spin_axis[2]}}};
}

TemperatureProfile constant_temperature(double celsius) {
  return [celsius](double) { return celsius; };
}

TemperatureProfile TemperatureChamber::profile(double start_s) const {
  const TemperatureChamber chamber = *this;
  return [chamber, start_s](double t) {
    // First-order lag through each soak: T_k(end) carries into the next step.
    double temperature = chamber.initial_c;
    double elapsed = t - start_s;
    for (const double set_point : chamber.set_points_c) {
      const double span = std::min(elapsed, chamber.soak_s);
      if (span <= 0.0) break;
      temperature = set_point + (temperature - set_point) * std::exp(-span / chamber.thermal_time_constant_s);
      elapsed -= chamber.soak_s;
    }
    return temperature;
  };
}

Rig RateTable::rig(const Site& site, const Matrix3& gyro_mounting, double rate_rad_s, double angle_rad,
                   double start_s, TemperatureProfile temperature) const {
  const RateTable table = *this;
  const Vector3 earth = site.earth_rate_enu();
  const Vector3 gravity = site.specific_force_enu_g();
  return [=](double t) {
    const double rate = rate_rad_s * (1.0 + table.rate_error);
    const double theta = angle_rad + rate * (t - start_s);
    // ENU → tilted axis (tilt + wobble about east and north) → turning table → face → gyro.
    const ChainLink links[] = {
        {Axis::kX, table.tilt_east_rad + table.wobble_rad * std::cos(theta), -table.wobble_rad * std::sin(theta) * rate},
        {Axis::kY, table.tilt_north_rad + table.wobble_rad * std::sin(theta), table.wobble_rad * std::cos(theta) * rate},
        {Axis::kZ, theta, rate},
        {Axis::kX, table.face_x_rad, 0.0},
        {Axis::kY, table.face_y_rad, 0.0},
    };
    const ChainState state = evaluate_chain(links, std::size(links));
    const Matrix3 gyro_to_enu = multiply(state.orientation, gyro_mounting);
    const Matrix3 enu_to_gyro = transpose(gyro_to_enu);
    Stimulus s;
    s.rate = add(multiply(transpose(gyro_mounting), state.angular_velocity), multiply(enu_to_gyro, earth));
    s.specific_force = multiply(enu_to_gyro, gravity);
    s.temperature_c = temperature(t);
    return s;
  };
}

Rig static_rig(const Site& site, const Matrix3& gyro_mounting, TemperatureProfile temperature) {
  const Matrix3 enu_to_gyro = transpose(gyro_mounting);
  const Vector3 rate = multiply(enu_to_gyro, site.earth_rate_enu());
  const Vector3 force = multiply(enu_to_gyro, site.specific_force_enu_g());
  return [=](double t) { return Stimulus{rate, force, temperature(t)}; };
}

double VibrationTable::angle(double t) const {
  return amplitude_rad * std::sin(2.0 * constants::kPi * frequency_hz * (t - start_s));
}

Rig VibrationTable::rig(const Site& site, TemperatureProfile temperature) const {
  const VibrationTable table = *this;
  const Matrix3 ia_up = mounting({0, 0, 1}, {1, 0, 0});
  const Rig base = static_rig(site, ia_up, temperature);
  return [=](double t) {
    Stimulus s = base(t);
    const double w = 2.0 * constants::kPi * table.frequency_hz;
    s.rate[0] += table.amplitude_rad * w * std::cos(w * (t - table.start_s));
    return s;
  };
}

}  // namespace inertest::sim
