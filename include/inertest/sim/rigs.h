// The test rigs of the virtual lab. Each makes a Rig (gyro_model.h): the angular rate and
// specific force in the gyro's IA/OA/SA frame and its temperature, as functions of time.
//
// Frames: the local level frame is east-north-up (ENU). The Earth rate there is
// (0, ωe·cos φ, ωe·sin φ); a body at rest feels the specific force (0, 0, g_site) (upward).
// A mounting is the gyro frame (IA, OA, SA, right-handed) expressed in the frame it sits on.
#pragma once

#include <functional>

#include "inertest/sim/gyro_model.h"

namespace inertest::sim {

struct Site {
  double latitude_deg = 0.0;
  double gravity_m_s2 = 9.80665;
  double earth_rate_rad_s = 7.2921150e-5;  // IERS; set 0 to switch the Earth's rotation off

  Vector3 earth_rate_enu() const;
  Vector3 specific_force_enu_g() const;  // (0, 0, g_site/g0)
};

// Normal gravity at the ellipsoid (WGS 84, Somigliana's closed form), m/s².
double normal_gravity(double latitude_deg);

// Gyro frame in the frame it is mounted on: columns IA, OA, SA.
Matrix3 mounting(const Vector3& input_axis, const Vector3& output_axis);

// The gyro's temperature over time.
using TemperatureProfile = std::function<double(double t)>;
TemperatureProfile constant_temperature(double celsius);

// A temperature chamber: soaks at each set point in turn for soak_s, the air following set-point
// steps at once and the gyro lagging it with a first-order thermal time constant.
struct TemperatureChamber {
  std::vector<double> set_points_c;
  double soak_s = 3600.0;
  double thermal_time_constant_s = 600.0;
  double initial_c = 20.0;

  TemperatureProfile profile(double start_s) const;
};

// Single-axis rate table or position table (dividing head): the axis is nominally up; it leans by
// `tilt` (rotations about east then north), wobbles by `wobble` amplitude (rad) as it turns
// (about east ∝ cos θ, about north ∝ sin θ, the tilt changing once per revolution), its face
// normal leans by `face` (about the face's x then y), and it turns at rate·(1 + rate_error) from
// angle start_angle. Rate 0 makes a position table.
struct RateTable {
  double tilt_east_rad = 0.0;
  double tilt_north_rad = 0.0;
  double wobble_rad = 0.0;
  double face_x_rad = 0.0;
  double face_y_rad = 0.0;
  double rate_error = 0.0;  // relative, e.g. 1e-6

  // Rig for a gyro mounted on the face (mounting: gyro frame in face coordinates) with the table at
  // `angle_rad` at t = start_s and turning at `rate_rad_s` (commanded).
  Rig rig(const Site& site, const Matrix3& gyro_mounting, double rate_rad_s, double angle_rad, double start_s,
          TemperatureProfile temperature) const;
};

// A gyro standing still in the local level frame (mounting in ENU).
Rig static_rig(const Site& site, const Matrix3& gyro_mounting, TemperatureProfile temperature);

// Angular vibration table: the axis up, the gyro's IA along it, the table angle
// θ(t) = amplitude·sin(2π f (t − start_s)). The interferometer reads θ(t).
struct VibrationTable {
  double frequency_hz = 1.0;
  double amplitude_rad = 0.0;
  double start_s = 0.0;

  double angle(double t) const;
  Rig rig(const Site& site, TemperatureProfile temperature) const;
};

}  // namespace inertest::sim
