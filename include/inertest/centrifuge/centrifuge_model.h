// First-order model of a gyro on a precision centrifuge with a counter-rotating platform, after
// the paper on calibrating gyro drift coefficients on a precision centrifuge with a counter-rotating
// platform (core/citations.h):
//   gyro static error model, eq. (2); input rate, eq. (5) in the reconstructed form that reproduces
//   the paper's Table 3; nominal specific forces with the Coriolis term, eqs. (6)-(8); harmonic
//   form of the output, eq. (11).
// This is the FIRST-ORDER model: it keeps only the error terms of the paper's homogeneous-transform
// chain (its Table 1) that survive to first order (k1, k2, delta-omega). A full-chain simulator
// belongs elsewhere; this model is what the calibration inverts, and what tests use to make data.
//
// Units: angles (beta, gamma, k1, k2) in rad, rates (Omega, delta-omega, Earth rate) in rad/s,
// the gyro output in deg/h. Specific forces of eqs. (6)-(8) are in the site's g, as the paper
// defines A = Omega^2 R0 / g (SpecificForce, centrifuge_specific_force). The drift coefficients are
// per STANDARD g (9.80665 m/s^2, the "g" that Unit::parse reads in deg/h/g, deg/h/g^2): eq. (2) is
// applied to the forces converted by in_standard_g, so a coefficient of order n per site g equals
// the same coefficient per standard g times (g_site / 9.80665)^n (the paper's Table 3, with
// g = 9.8, prints its coefficients per site g).
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

#include "inertest/core/units.h"

namespace inertest::centrifuge {

// The ten drift coefficients of eq. (2), in the order of q in eq. (13):
// q = [D_F D_I D_O D_S D_II D_OO D_SS D_IO D_IS D_OS]^T.
inline constexpr std::size_t kDriftTermCount = 10;
enum DriftTerm : std::size_t { kF, kI, kO, kS, kII, kOO, kSS, kIO, kIS, kOS };
using DriftCoefficients = std::array<double, kDriftTermCount>;

// "D_F", "D_I", ... "D_OS".
std::string_view drift_term_name(std::size_t term);
// "deg/h" (D_F), "deg/h/g" (first order), "deg/h/g^2" (second order); g is standard gravity.
std::string_view drift_term_unit(std::size_t term);

// The five harmonic amplitudes of eq. (11): k0, k1c, k1s, k2c, k2s (deg/h).
inline constexpr std::size_t kHarmonicCount = 5;
enum HarmonicTerm : std::size_t { kK0, kK1c, kK1s, kK2c, kK2s };
using HarmonicAmplitudes = std::array<double, kHarmonicCount>;
// "k0", "k1c", "k1s", "k2c", "k2s".
std::string_view harmonic_name(std::size_t harmonic);
// The value of the harmonic's basis function at gamma: 1, cos g, sin g, cos 2g, sin 2g.
double harmonic_basis(std::size_t harmonic, double gamma_rad);

// The rig and the site.
struct CentrifugeSite {
  double radius_m = 1.0;                            // R0, nominal radius of the gyro's mounting point
  double latitude_rad = 0.0;                        // phi
  double gravity_m_s2 = constants::kStandardGravity; // g: local gravity, the unit of the specific forces
  double earth_rate_rad_s = constants::kEarthRate;  // omega_e

  // Throws Error for a radius, gravity or Earth rate that is not positive and finite, or a
  // latitude outside [-pi/2, pi/2].
  void validate() const;
};

// The centrifuge errors that survive to first order in eq. (5).
struct CentrifugeErrors {
  double k1_rad = 0.0;             // k1 = dtheta_y2t + dtheta_y2(-Omega t)
  double k2_rad = 0.0;             // k2 = dtheta_x2t + dtheta_x2(-Omega t)
  double delta_omega_rad_s = 0.0;  // platform rate minus main-axis rate

  // k1 and k2 from the angles they come from (paper, after eq. 5): the perpendicularity of the
  // platform axis to the disk (dtheta_y2t, dtheta_x2t) and the platform axis wobble
  // (dtheta_y2(-Omega t), dtheta_x2(-Omega t)), taken as constant over the test.
  static CentrifugeErrors from_angles(double perpendicularity_y_rad, double wobble_y_rad,
                                      double perpendicularity_x_rad, double wobble_x_rad,
                                      double delta_omega_rad_s);
};

// Specific force along the gyro's input, output and spin axes (g).
struct SpecificForce {
  double input = 0.0;   // f_I
  double output = 0.0;  // f_O
  double spin = 0.0;    // f_S
};

// A = Omega^2 R0 / g, the centripetal specific force in g (paper, after eq. 8).
double centripetal_specific_force(const CentrifugeSite& site, double omega_rad_s);
// A_k = -2 R0 Omega omega_e sin(phi) / g, the Coriolis term (paper, after eq. 8).
double coriolis_specific_force(const CentrifugeSite& site, double omega_rad_s);

// Eqs. (6)-(8): f_I = -(A cos g + A_k) cos b + sin b; f_O = -A sin g; f_S = (A cos g + A_k) sin b + cos b.
SpecificForce centrifuge_specific_force(const CentrifugeSite& site, double omega_rad_s, double beta_rad,
                                        double gamma_rad);

// Eq. (5), the rate about the input axis, in deg/h:
// w_I = [-(k1 cos g + k2 sin g) Omega + omega_e cos phi] cos b + (omega_e sin phi + dOmega) sin b.
double centrifuge_input_rate(const CentrifugeSite& site, const CentrifugeErrors& errors, double omega_rad_s,
                             double beta_rad, double gamma_rad);

// A specific force in the site's g expressed in standard g: f * g_site / 9.80665.
SpecificForce in_standard_g(const SpecificForce& force_site_g, const CentrifugeSite& site);

// The ten regressors of eq. (2): 1, f_I, f_O, f_S, f_I^2, f_O^2, f_S^2, f_I f_O, f_I f_S, f_O f_S
// (in the unit of the force given).
DriftCoefficients drift_regressors(const SpecificForce& force);

// The first-order model's noise-free gyro output (deg/h): eq. (2) with the inputs of eqs. (5)-(8),
// sigma = 0, coefficients per standard g. gamma is the angle from the input axis to the
// centripetal direction (gamma0 = 0).
double centrifuge_model_output(const DriftCoefficients& coefficients, const CentrifugeSite& site,
                               const CentrifugeErrors& errors, double omega_rad_s, double beta_rad,
                               double gamma_rad);

// The model projected on the harmonics of eq. (11) at one main-axis rate and platform angle:
// amplitudes = structure * q + earth_rate + k1 * per_k1 + k2 * per_k2 + dOmega * per_delta_omega.
// Every term of the model is a trigonometric polynomial of degree <= 2 in gamma, so the projection
// is exact (computed by an 8-point discrete Fourier transform, which does not alias degree 2).
struct HarmonicModel {
  std::array<DriftCoefficients, kHarmonicCount> structure{};  // rows of Phi (eq. 13), q per standard g
  HarmonicAmplitudes earth_rate{};       // epsilon from omega_e (deg/h)
  HarmonicAmplitudes per_k1{};           // epsilon per rad of k1 (deg/h/rad)
  HarmonicAmplitudes per_k2{};           // epsilon per rad of k2 (deg/h/rad)
  HarmonicAmplitudes per_delta_omega{};  // epsilon per rad/s of delta-omega (deg/h/(rad/s))
};
HarmonicModel centrifuge_harmonic_model(const CentrifugeSite& site, double omega_rad_s, double beta_rad);

}  // namespace inertest::centrifuge
