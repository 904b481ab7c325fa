// Equivalent degrees of freedom and chi-squared confidence intervals of Allan-family deviations
// (NIST SP 1065 (2008) 5.3 and eq. (45)).
#pragma once

#include <cstddef>
#include <string_view>

#include "inertest/allan/allan_engine.h"

namespace inertest {

// Power-law noise, named by alpha, the exponent of the frequency PSD S_y(f) ~ f^alpha.
enum class NoiseType { kWhitePhase = 2, kFlickerPhase = 1, kWhiteFrequency = 0, kFlickerFrequency = -1, kRandomWalkFrequency = -2 };

// "white_pm", "flicker_pm", "white_fm", "flicker_fm", "random_walk_fm".
std::string_view noise_type_name(NoiseType type);

// NIST SP 1065 Table 5 ("simple approximate formulae", after Stein 1985): edf of the overlapping
// Allan variance of `phase_count` phase points at averaging factor m.
double edf_overlapping_allan(double phase_count, double m, NoiseType type);

// NIST SP 1065 Table 7: edf of the total variance, b (T/tau) - c, for white, flicker and random
// walk FM, with T/tau = N_x / m for N_x phase points (as Stable32 takes it: its published bounds
// match this to 0.03 %, and (N_x - 1) / m to 0.17 % only); phase noises, which Table 7 does not
// cover, take Table 5 (edf_overlapping_allan), as Stable32 does.
double edf_total(double phase_count, double m, NoiseType type);

// Greenhall's combined edf algorithm for the variances of d-th differences of the phase, which
// NIST SP 1065 (2008) 5.3 names for AVAR, MVAR and HVAR: C. A. Greenhall and W. J. Riley,
// "Uncertainty of stability variances based on finite differences", Proc. 35th PTTI (2003),
// eqs. (7)-(10), the four cases of its section 4 and its Tables 1-3.
//   alpha        noise type (S_y ~ f^alpha), +2 .. -2; alpha + 2 d > 1 is required
//   d            2: Allan (MVAR when modified), 3: Hadamard
//   m            averaging factor; phase_count: N_x, the number of phase points (rate samples + 1)
//   overlapping  stride tau0 (OAVAR, MVAR, OHVAR) instead of tau (AVAR, HVAR)
//   modified     MVAR (phase averaged over m points) instead of the unmodified variances
// Throws Error outside that domain or when the record holds no term.
double edf_greenhall(NoiseType type, int d, double m, double phase_count, bool overlapping, bool modified);

// The edf used for each estimator on N rate samples (N + 1 phase points) at averaging factor m, as
// NIST SP 1065 (2008) 5.3 and Stable32 compute it:
//   ADEV, OADEV, MDEV, HDEV, OHDEV  Greenhall's algorithm (edf_greenhall);
//   TOTDEV                          Table 7 (edf_total).
// The result is at least 1; it may exceed the number of terms (TOTDEV's reflected record, the
// correlation of overlapping terms counted by Greenhall's sums), as in Stable32.
double equivalent_degrees_of_freedom(Estimator estimator, std::size_t sample_count, std::size_t m, NoiseType type);

// Where the edf of an estimator comes from, for the JSON: "NIST SP 1065 Table 5", ...
std::string_view edf_method(Estimator estimator);

struct DeviationInterval {
  double lower = 0.0;
  double upper = 0.0;
};

// NIST SP 1065 eq. (45): edf s^2 / chi^2_{1-p/2} <= sigma^2 <= edf s^2 / chi^2_{p/2}, returned as
// deviations; `confidence` is the two-sided level (0.6827 for 1 sigma).
DeviationInterval chi_squared_interval(double deviation, double edf, double confidence);

inline constexpr double kOneSigmaConfidence = 0.6826894921370859;

}  // namespace inertest
