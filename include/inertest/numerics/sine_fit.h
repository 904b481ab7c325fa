// Least-squares fit of a sine of known frequency: y(t) = A·sin(ω·t + φ) + c, linearised as
// y = s·sin(ωt) + k·cos(ωt) + c (three-parameter sine fit, IEEE Std 1057-2017 4.1.3.1), so that
// A = √(s² + k²) and φ = atan2(k, s). Used for the angular-vibration records of GJB 2426A-2004
// 5.13-5.14 (eqs. 32 and 34: the amplitude and phase of the interferometer angle and of the gyro
// output at the vibration frequency).
#pragma once

#include <span>

namespace inertest {

struct SineFit {
  double amplitude = 0.0;              // A >= 0
  double phase = 0.0;                  // φ in rad, in (-π, π]
  double offset = 0.0;                 // c
  double amplitude_standard_error = 0.0;
  double phase_standard_error = 0.0;   // rad
  double residual_rms = 0.0;
};

// Fits y(t) at the angular frequency omega (rad/s). Times in s. Throws Error when the sizes
// differ, fewer than four samples are given, a time or sample is not finite, or the samples do
// not determine the sine (e.g. all taken at the same phase).
SineFit fit_sine(std::span<const double> time, std::span<const double> samples, double omega);

}  // namespace inertest
