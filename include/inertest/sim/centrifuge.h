// Precision centrifuge with a counter-rotating platform (the centrifuge paper, Fig. 2
// and Table 1). The nine frames ground → main-axis sleeve → main axis → platform sleeve →
// platform → rate-table sleeve → rate table → work face → gyro are chained with the error angles
// of Table 1, and the gyro's angular velocity and specific force come from that whole chain:
//   T0→1t = Rot(x, Δθx1t)·Rot(y, Δθy1t)
//   T1t→1 = Rot(x, Δθx1(Ωt))·Rot(y, Δθy1(Ωt))·Rot(z, Ωt)
//   T1→2t = Trans(R0, 0, 0)·Rot(x, Δθx2t)·Rot(y, Δθy2t)
//   T2t→2 = Rot(x, Δθx2(−Ωt))·Rot(y, Δθy2(−Ωt))·Rot(z, −(Ω − ΔΩ)t − γ0)
//   T2→3t = Rot(x, Δθx3t)·Rot(z, Δθz3t)
//   T3t→3 = Rot(x, Δθx3(ωt))·Rot(z, Δθz3(ωt))·Rot(y, −(ωt + β))
//   T3→4  = Rot(x, Δθx4)·Rot(z, Δθz4)
//   T4→5  = Rot(y, Δθy5)·Rot(x, Δθx5)·Rot(z, Δθz5)
// Ground frame: x north, y west, z up (the Earth rate is (ωe cos φ, 0, ωe sin φ), paper eq. 3).
// Gyro frame 5: x = IA, y = OA, z = SA.
// Sign choice: the table angle enters as Rot(y, −(ωt + β)) so that IA rises toward the vertical for
// positive β, as the paper's fI = −(A cos γ + Ak) cos β + sin β requires; the paper's rotation
// convention is not stated.
// Wobble (the "(Ωt)" angles) is modelled as a tilt of amplitude w turning with the axis:
// Δθx(θ) = w·cos(θ + p), Δθy(θ) = w·sin(θ + p); its angular rate is kept (exact kinematics).
// Specific force: f = [a_rel + 2 ωe × v_rel + (0, 0, g)] / g0 in the gyro frame, a_rel and v_rel of
// the gyro's position relative to the Earth (central differences of the homogeneous chain).
#pragma once

#include "inertest/sim/gyro_model.h"
#include "inertest/sim/rigs.h"

namespace inertest::sim {

struct CentrifugeErrors {
  double x1t = 0, y1t = 0;          // main-axis sleeve mounting, rad
  double wobble1 = 0, wobble1_phase = 0;  // main-axis tilt turning with the axis, rad
  double x2t = 0, y2t = 0;          // platform axis to disk perpendicularity, rad
  double wobble2 = 0, wobble2_phase = 0;  // platform-axis tilt turning with the platform
  double x3t = 0, z3t = 0;          // rate-table axis to platform axis perpendicularity
  double x4 = 0, z4 = 0;            // work face to platform axis perpendicularity
  double x5 = 0, z5 = 0, y5 = 0;    // gyro mounting attitude and initial zeroing error
  double platform_rate_error = 0;   // ΔΩ, rad/s: platform rate minus main-axis rate (magnitudes)
};

struct Centrifuge {
  double radius_m = 1.0;   // R0
  double rate_rad_s = 0.0; // Ω
  double beta_rad = 0.0;   // β, the work-face angle about axis C
  double gamma0_rad = 0.0; // γ0
  CentrifugeErrors errors;

  // Angle γ between IA and the centripetal direction as the platform encoder reads it:
  // γ = (Ω − ΔΩ)·t + γ0.
  double gamma(double t) const;
  // Stimulus at time t (rig time, the run starting at t = start_s).
  Stimulus stimulus(const Site& site, double t, double start_s, double temperature_c) const;
  Rig rig(const Site& site, double start_s, TemperatureProfile temperature) const;

  // Gyro orientation (gyro → ground) and position in the ground frame at time t.
  ChainState orientation(double t) const;
  Vector3 position(double t) const;
};

}  // namespace inertest::sim
