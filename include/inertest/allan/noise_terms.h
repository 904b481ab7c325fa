// Identification of the noise terms of a gyro from its Allan variance (IEEE Std 952-1997 Annex C,
// GJB 2426A-2004 5.12.5.4.2 eqs. (30)-(31)).
//
// Fit: sigma^2(tau) = sum_{p=-2..2} A_p tau^p (GJB eq. 30) by weighted non-negative least squares
// (Lawson & Hanson, "Solving Least Squares Problems", 1974, ch. 23, active set), each point weighted
// by 1/var(sigma^2) = edf / (2 sigma^4), the chi-squared variance of the estimate. Then
// (IEEE 952 C.1, Table C.1):
//   quantization       sigma^2 = 3 Q^2 / tau^2         Q = sqrt(A_-2 / 3)
//   angle random walk  sigma^2 = N^2 / tau             N = sqrt(A_-1)   (= RWC of GJB eq. 31)
//   bias instability   sigma   = 0.664 B (flat part)   B = sqrt(A_0) / 0.664, 0.664 = sqrt(2 ln 2 / pi)
//   rate random walk   sigma^2 = K^2 tau / 3           K = sqrt(3 A_1)
//   rate ramp          sigma^2 = R^2 tau^2 / 2         R = sqrt(2 A_2)
// For an angular-rate input the figures are in arcsec, deg/sqrt(h), deg/h, deg/h/sqrt(h), deg/h/h;
// for another input unit U in (U)*s, (U)*sqrt(s), U, (U)/sqrt(s), (U)/s.
//
// Uncertainty: the covariance of the free coefficients, (J^T W J)^-1, scaled by the reduced
// chi-squared when that exceeds 1 (the octave points share data and are not independent), carried
// to each figure to first order. A coefficient held at zero reports value 0 and as uncertainty the
// figure that its 1-sigma bound would give.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/core/figure.h"

namespace inertest {

struct NoiseTerms {
  Figure quantization;
  Figure angle_random_walk;
  Figure bias_instability;
  Figure rate_random_walk;
  Figure rate_ramp;
  // GJB 2426A eq. (31): RWC = sqrt(A_-1), the angle random walk N.
  const Figure& random_walk_coefficient() const { return angle_random_walk; }
  // A_p for p = -2..2, in (input unit)^2 s^p, and their 1-sigma uncertainties.
  std::array<double, 5> coefficients{};
  std::array<double, 5> coefficient_uncertainties{};
  double reduced_chi_squared = 0.0;
  // For each tau, the power p of the largest term A_p tau^p of the fitted model.
  std::vector<int> dominant_power;

  nlohmann::json to_json(const std::string& input_unit) const;
};

// Throws Error when the spans differ in length, hold fewer than 2 points, or hold a non-positive
// tau, variance or edf.
NoiseTerms fit_noise_terms(std::span<const double> tau_s, std::span<const double> variance,
                           std::span<const double> edf, const std::string& input_unit);

// The slope read-off of MATLAB's allanvar example on the (overlapping) Allan deviation: the point
// where the log-log slope between neighbours is closest to -1/2, 0 and +1/2 gives, on the line of
// that slope through it, N at tau = 1 s, B = sigma / 0.664 and K at tau = 3 s.
struct SlopeReadOff {
  Figure angle_random_walk;
  double angle_random_walk_tau_s = 0.0;
  Figure bias_instability;
  double bias_instability_tau_s = 0.0;
  Figure rate_random_walk;
  double rate_random_walk_tau_s = 0.0;

  nlohmann::json to_json() const;
};

// Needs at least 2 points; the uncertainty of each figure is that of the deviation it is read at,
// sigma / sqrt(2 edf).
SlopeReadOff read_noise_slopes(std::span<const double> tau_s, std::span<const double> deviation,
                               std::span<const double> edf, const std::string& input_unit);

// sqrt(2 ln 2 / pi) = 0.6643, printed 0.664 in IEEE Std 952-1997 C.1.
inline constexpr double kBiasInstabilityFactor = 0.66428696;

}  // namespace inertest
