// Harmonic analysis of a gyro's output over platform revolutions: the amplitudes k0, k1c, k1s,
// k2c, k2s of w_d = k0 + k1c cos g + k1s sin g + k2c cos 2g + k2s sin 2g + sigma (paper eq. 11).
#pragma once

#include <cstddef>
#include <span>

#include "inertest/centrifuge/centrifuge_model.h"

namespace inertest::centrifuge {

struct HarmonicFit {
  enum class Method {
    kDiscreteFourier,  // equally spaced samples over whole revolutions: exact DFT bins
    kLeastSquares,     // any other sampling: least-squares fit of the five terms
  };
  HarmonicAmplitudes amplitudes{};  // in the unit of the outputs
  // rms of the samples about the five-term fit, sqrt(sum r^2 / N), in the unit of the outputs.
  double residual_rms = 0.0;
  std::size_t sample_count = 0;
  double revolutions = 0.0;  // span covered by the samples, angles unwrapped (N * step / 2 pi for the DFT;
                             // the first to the last sample plus a mean step for least squares)
  Method method = Method::kLeastSquares;
  // The angles advance one way (a rotation, unwrapped) over less than one revolution: harmonics
  // fitted over part of a turn. Angles in any order (irregular sampling) are not judged.
  bool part_of_a_revolution = false;
  // Every sample equal (a stuck channel): the harmonics k1..k2 are 0 by construction, not measured.
  bool constant_output = false;
};

// "dft" or "least_squares".
const char* to_string(HarmonicFit::Method method);

// Fits eq. (11) to (gamma_i, output_i). When the gamma_i are equally spaced, in order, and N steps
// cover a whole number R of revolutions, with no harmonic 1..4 aliased onto zero (m * step not a
// multiple of 2 pi for m = 1..4), the amplitudes are the exact DFT bins
//   k0 = (1/N) sum y,  k_mc = (2/N) sum y cos(m g),  k_ms = (2/N) sum y sin(m g);
// otherwise they are the least-squares fit of the five terms (which equals the DFT in the first
// case). Throws Error with fewer than 5 samples, sizes that differ, or a sampling that cannot
// separate the five terms (naming the harmonics it cannot identify).
HarmonicFit analyse_harmonics(std::span<const double> gamma_rad, std::span<const double> output);

}  // namespace inertest::centrifuge
