// Random walk coefficient by the normalisation method: GJB 2426A-2004 5.12.5.4.1, eqs. (23)-(24).
//
//   τ = k·t0, k = 1, 2, 4, 8, ...                                                          (23)
//   at each τ the new sequence is the means of adjacent pairs of the previous one, and Bs(τ) is
//   eq. (20) on it; NER = Bs(1 s) (the noise equivalent rate);
//   RWC = NER · τ^½ with τ = 1 s                                                           (24)
//
// In consistent units NER in deg/h times √(1 s) is deg/h·√s, and deg/h·√s = deg/√h ÷ 60 (√3600 s/h
// = 60), so RWC[deg/√h] = Bs(1 s)[deg/h] / 60. For white rate noise of density N this equals N.
// The functions here work in the record's output unit; bias.h converts.
#pragma once

#include <span>
#include <vector>

namespace inertest {

struct NormalisedStabilityPoint {
  double tau_s = 0.0;      // τ = 2^k·t0
  double stability = 0.0;  // Bs(τ) by eq. (20), output unit
};

// Bs(τ) for τ = t0, 2·t0, 4·t0, ... while the sequence keeps at least two values (eq. 23). A pair
// left without partner at the end of a sequence is dropped. Throws Error for a non-positive rate or
// fewer than two samples.
std::vector<NormalisedStabilityPoint> normalised_stability_curve(std::span<const double> output, double sample_rate_hz);

// NER = Bs(1 s) in the output unit. When 1 s is a whole number of samples it is eq. (20) on the
// means of whole 1 s windows (which is the 2^k sequence of eq. 23 whenever 1 s = 2^k·t0). Otherwise
// it is interpolated on the curve above, linearly in log Bs against log τ (the curve is a straight
// line of slope −½ there for the white noise the coefficient describes, note 3 of 5.12.5.4.1).
// Throws Error when the record is shorter than 2 s or the sample interval longer than 1 s.
double noise_equivalent_rate(std::span<const double> output, double sample_rate_hz);

}  // namespace inertest
