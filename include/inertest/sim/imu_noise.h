// A six-axis IMU at rest, for the noise analysis of issue 19: each axis carries the random drift of
// IEEE Std 952-1997 Annex C (noise.h: N, B, K in the axis's own unit, e.g. deg/s or m/s^2) and
// optionally a sinusoid, so that the truth of every figure follows from how the record was made.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "inertest/sim/noise.h"

namespace inertest::sim {

struct ImuAxisNoise {
  std::string name;  // e.g. "gx"
  std::string unit;  // the samples' unit, e.g. "deg/s" or "m/s^2"
  // In the axis's unit U: angle_random_walk N in U*sqrt(s), bias_instability B in U,
  // rate_random_walk K in U/sqrt(s) (the field names are the gyro's; noise.h).
  NoiseParameters noise;
  double sine_amplitude = 0.0;  // U, peak
  double sine_frequency_hz = 0.0;
};

// One column per axis, `samples` each at `sample_rate_hz`: the mean over each sample interval of
// the axis's noise (NoiseGenerator) plus A sin(2 pi f t) sampled at the interval's middle. Each axis
// draws from its own stream, seeded from `seed` and its name (Random::stream). Throws Error for a non-positive
// rate or a negative noise term.
std::vector<std::vector<double>> simulate_imu_noise(const std::vector<ImuAxisNoise>& axes, double sample_rate_hz,
                                                    std::size_t samples, std::uint64_t seed);

}  // namespace inertest::sim
