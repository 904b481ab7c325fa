// Identification of the noise terms of a gyro from its Allan variance (IEEE Std 952-1997 Annex C,
// GJB 2426A-2004 5.12.5.4.2 eqs. (30)-(31)).
//
// Fit: sigma^2(tau) = sum_{p=-2..2} A_p tau^p (GJB eq. 30) by non-negative generalised least squares
// (Lawson & Hanson, "Solving Least Squares Problems", 1974, ch. 23, active set, on the whitened
// system). Then (IEEE 952 C.1, Table C.1):
//   quantization       sigma^2 = 3 Q^2 / tau^2         Q = sqrt(A_-2 / 3)
//   angle random walk  sigma^2 = N^2 / tau             N = sqrt(A_-1)   (= RWC of GJB eq. 31)
//   bias instability   sigma   = 0.664 B (flat part)   B = sqrt(A_0) / 0.664, 0.664 = sqrt(2 ln 2 / pi)
//   rate random walk   sigma^2 = K^2 tau / 3           K = sqrt(3 A_1)
//   rate ramp          sigma^2 = R^2 tau^2 / 2         R = sqrt(2 A_2)
// For an angular-rate input the figures are in arcsec, deg/sqrt(h), deg/h, deg/h/sqrt(h), deg/h/h;
// for a specific force (an accelerometer) they are velocity quantization, velocity random walk,
// bias instability, acceleration random walk and acceleration ramp (IEEE Std 1293-1998), in m/s,
// m/s/sqrt(h), ug, m/s/h/sqrt(h), m/s/h/h; for another input unit U in (U)*s, (U)*sqrt(s), U,
// (U)/sqrt(s), (U)/s.
//
// Covariance of the points: overlapping estimates at different taus share data and are correlated.
// The variance of point i is 2 sigma_i^4 / edf_i (sigma_i of the model, edf_i the curve's: of one
// noise type) times the ratio, where above 1, of sum_k C_ii(k)^2 / C_ii(0)^2 of the random mix to
// that of its largest term alone (each term of a mix scatters with its own edf); the correlation of points i, j is that of two means of squared, jointly Gaussian second differences,
//   Cov(s_i^2, s_j^2) = (2 / max(M_i, M_j)) sum_k C_ij(k)^2     (Isserlis' theorem)
// with C_ij(k) the cross-covariance at lag k of the second differences at tau_i and tau_j, computed
// from the fitted model through the generalised covariance of the angle (Matheron, "The intrinsic
// random functions and their applications", Adv. Appl. Prob. 5, 1973; second differences filter out
// polynomials of degree 1): K(h) = Q^2 delta(h) - N^2 |h| / 2 + B'^2 h^2 ln|h| / (4 ln 2) + K^2 |h|^3 / 12
// with B' = 0.664 B; each term reproduces its line of Table C.1 exactly. The rate ramp is deterministic
// and adds no covariance. Fit and covariance are iterated (the covariance from the previous fit,
// which avoids the bias of weighting by the observed points). Checked by a Monte Carlo test over
// 200 simulated records: the 1-sigma intervals of N, B and K cover the truth in 60-76 % of them.
// For more than 64 taus (a dense grid) the correlation is not modelled and a warning says so; for
// taus closer than an octave it is, but that model is validated on octave grids only, and a
// warning says the uncertainties may be understated.
//
// Fit range: eq. (30) describes the gyro's noise, not its anti-alias filter or coarse quantisation,
// which flatten or bend the shortest taus. Unless a range is given, the fewest taus are dropped that
// make the fit consistent (reduced chi-squared at most 1 + 3 sqrt(2 / dof)): the shortest first and,
// at the same count, up to two of the longest, whose few degrees of freedom let a random walk's
// excursion break every range keeping them; if no range is consistent, the one of least reduced
// chi-squared is kept and the verdict says the model does not fit. The range and the reason are
// reported.
//
// R acts only at the long end of the curve, where it trades off against K: when R lies within 2 of
// its 1-sigma uncertainties of zero, one of R and K is held at zero (backward elimination), since
// left free R's non-negativity bound biases K; which one, the fits holding each at zero tell: K is
// held when the fit without it leaves a chi-squared less by 1 than the fit without R (tested
// alone, R's z is small whenever K takes up a ramp).
// Q, which trades off against N at the short end, is not eliminated: a digitised output always
// carries quantisation, and holding a real Q at zero whenever it is within 2 sigma of zero (a
// pre-test estimator) moves its 3 Q^2 / tau^2 into N. Measured on the
// golden campaign's 2-hour record (5 Hz, 0.1 arcsec pulses, Q about 0.03 arcsec, fit from tau = 8 s;
// 200 seeds): Q was held at zero in 95 of them, where N read 17.5 % high with a 2.2 % uncertainty
// (6 sigma), and N's 4-sigma truth check failed in 47 %; left free, N reads 0.8 +- 0.6 % high, its
// 1-sigma interval covers the truth in 74 % of seeds, and 199 pass. The price when there is no
// quantisation (same record without it, 200 seeds): the bound Q >= 0 pulls N 2.6 % (0.18 sigma)
// low instead of 0.5 %, coverage 70 % against 66 %. Only the non-negativity bound itself still holds
// Q at zero, when its unconstrained estimate is negative.
//
// Uncertainty: the GLS covariance of the free coefficients, (J^T V^-1 J)^-1, scaled by the reduced
// chi-squared when that exceeds 1, carried to each figure to first order. A coefficient that the
// non-negative fit holds at zero was not measured: it is reported as not identified, with an upper
// bound max(0, a) + 2 s, a and s its unconstrained estimate and 1-sigma uncertainty when it is
// freed along with the free ones, under the covariance of the model that holds it at that bound.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/core/figure.h"

namespace inertest {

// What a rate record measures, from its input unit: an angular rate (a gyro), a specific force (an
// accelerometer: m/s^2, g, mg, ug), or anything else (counts, volts: the gyro's names, the input's
// own unit). Throws Error for a unit that does not parse.
enum class SensorKind { kGyro, kAccelerometer, kOther };
SensorKind sensor_kind_of(const std::string& input_unit);

// The name of the term A_p tau^p (index p + 2) for a sensor: its JSON key and its label in text.
// A gyro's: quantization, angle_random_walk, bias_instability, rate_random_walk, rate_ramp; an
// accelerometer's: quantization, velocity_random_walk, bias_instability, acceleration_random_walk,
// acceleration_ramp.
struct NoiseTermName {
  std::string_view key;
  std::string_view label;
};
const std::array<NoiseTermName, 5>& noise_term_names(SensorKind kind);

// The taus fitted, inclusive, and why.
struct FitRange {
  double tau_min_s = 0.0;
  double tau_max_s = 0.0;
};

struct NoiseFitOptions {
  std::optional<FitRange> fit_range;  // empty: chosen automatically (see above)
  // Samples in the record, for the number of terms M_i = N - 2 m_i of each point; 0: unknown (M_i
  // taken equal, which overstates the correlation of the longest taus a little).
  std::size_t sample_count = 0;
  // The record's sample interval; 0: the shortest tau.
  double sample_interval_s = 0.0;

  // Throws Error for a range that is not 0 < tau_min <= tau_max (finite).
  void validate() const;
};

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
  // Per coefficient A_p (index p + 2): false when the fit holds it at zero; its figure's upper bound.
  std::array<bool, 5> identified{};
  // Per coefficient: identified and at least 2 of its 1-sigma uncertainties above zero. A figure is
  // the square root of its coefficient, so its own value / uncertainty is twice the coefficient's: B
  // = 0.02 +- 0.01 deg/h is a coefficient 1 sigma from zero, which chance gives a term the record
  // does not have in about a sixth of records. Such a figure keeps its value and uncertainty and
  // gets an upper bound too, A_p + 2 sigma, as a coefficient held at zero.
  std::array<bool, 5> significant{};
  std::array<std::optional<Figure>, 5> upper_bounds;
  double reduced_chi_squared = 0.0;  // of the generalised least squares, over the fit range
  std::size_t degrees_of_freedom = 0;
  std::string verdict;  // "consistent", "inconsistent" or "undetermined" (no degree of freedom)
  FitRange fit_range;
  std::string fit_range_chosen_by;  // "automatic" or "user"
  std::string fit_range_reason;
  std::vector<std::string> warnings;

  // Keys named for the sensor the input unit measures (noise_term_names).
  nlohmann::json to_json(const std::string& input_unit) const;
};

// Throws Error when the spans differ in length, hold fewer than 2 points, hold a non-positive
// tau, variance or edf, or when the fit range holds fewer than 2 taus.
NoiseTerms fit_noise_terms(std::span<const double> tau_s, std::span<const double> variance,
                           std::span<const double> edf, const std::string& input_unit,
                           const NoiseFitOptions& options = {});

// "TMIN:TMAX" in s, as the CLI's --fit-range. Throws Error saying what is wrong.
FitRange parse_fit_range(const std::string& text);

// The slope read-off of MATLAB's allanvar example on the (overlapping) Allan deviation: the pair of
// neighbouring points whose log-log slope is closest to -1/2 and +1/2 gives, on the line of that
// slope through its first point, N at tau = 1 s and K at tau = 3 s. B = sigma_min / 0.664 is read at
// the curve's floor (IEEE 952 C.1, Fig. C.1: the flat part is where the curve bottoms out), the
// least resolved point, and only when a resolved pair beside it is flat (slope within the tolerance
// of 0) and the slope turns across it by at most kFloorTurn: a flat part at short tau (anti-alias
// filter, quantisation) lies above the floor and is never read, nor the bottom of a valley between
// angle and rate random walk (where the slope turns by about 0.3 an octave).
//
// A figure is read only where the curve has a region of its slope: a pair qualifies when its slope
// lies within kSlopeTolerance of the target and is resolved, i.e. its 1-sigma uncertainty
// sqrt(1/(2 edf_i) + 1/(2 edf_i+1)) / ln(tau_i+1 / tau_i) (neighbours taken as independent, which
// overstates it) is at most kSlopeResolution, so that a slope this close to the target is at least
// 2 sigma from the neighbouring regimes (+-1/2 away). Otherwise the figure is not identified (empty)
// and `warnings` says why: e.g. no flat part (B) in pure white noise, whose noisy last points would
// otherwise give a number.
struct SlopeReading {
  std::optional<Figure> figure;  // empty: no region of the slope
  double tau_s = 0.0;            // the first point of the pair read (when identified)
  double slope = 0.0;            // its log-log slope (when identified)
};

struct SlopeReadOff {
  SlopeReading angle_random_walk;
  SlopeReading bias_instability;
  SlopeReading rate_random_walk;
  std::vector<std::string> warnings;

  // Keys named for the sensor the input unit measures (noise_term_names).
  nlohmann::json to_json(const std::string& input_unit) const;
};

// Needs at least 2 points; the uncertainty of each figure is that of the deviation it is read at,
// sigma / sqrt(2 edf).
SlopeReadOff read_noise_slopes(std::span<const double> tau_s, std::span<const double> deviation,
                               std::span<const double> edf, const std::string& input_unit);

inline constexpr double kSlopeTolerance = 0.1;
inline constexpr double kSlopeResolution = 0.2;
inline constexpr double kFloorTurn = 0.25;

// sqrt(2 ln 2 / pi) = 0.6643, printed 0.664 in IEEE Std 952-1997 C.1.
inline constexpr double kBiasInstabilityFactor = 0.66428696;

}  // namespace inertest
