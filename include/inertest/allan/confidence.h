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
// walk FM; phase noises fall back to Table 5.
double edf_total(double sample_count, double m, NoiseType type);

// The edf used for each estimator on N rate samples at averaging factor m:
//   OADEV  Table 5 with N + 1 phase points;
//   ADEV   Table 5 on the decimated record (floor(N/m) + 1 phase points, factor 1), which is exact
//          because ADEV at m is the OADEV at 1 of the decimated phase;
//   HDEV, OHDEV, MDEV  the Table 5 formula of ADEV and OADEV respectively: an approximation (NIST
//          gives no simple formula for them; Greenhall's general algorithm is not implemented);
//   TOTDEV Table 7.
// The result is at least 1 and at most the number of terms of the estimator.
double equivalent_degrees_of_freedom(Estimator estimator, std::size_t sample_count, std::size_t m,
                                     std::size_t term_count, NoiseType type);

struct DeviationInterval {
  double lower = 0.0;
  double upper = 0.0;
};

// NIST SP 1065 eq. (45): edf s^2 / chi^2_{1-p/2} <= sigma^2 <= edf s^2 / chi^2_{p/2}, returned as
// deviations; `confidence` is the two-sided level (0.6827 for 1 sigma).
DeviationInterval chi_squared_interval(double deviation, double edf, double confidence);

inline constexpr double kOneSigmaConfidence = 0.6826894921370859;

}  // namespace inertest
