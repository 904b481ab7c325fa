// The gyro's random drift, with the meanings of IEEE Std 952-1997 Annex C (C.1, eqs. C.2-C.12):
// each term is made so that its Allan deviation is the one the standard ascribes to it,
//   quantization Q:          σ(τ) = √3·Q/τ
//   angle random walk N:     σ(τ) = N/√τ
//   bias instability B:      σ(τ) = √(2 ln 2/π)·B ≈ 0.664·B   (flicker floor)
//   rate random walk K:      σ(τ) = K·√(τ/3)
//   rate ramp R:             σ(τ) = R·τ/√2
// All quantities in SI: rad, rad/√s, rad/s, rad/s/√s, rad/s².
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "inertest/sim/random.h"

namespace inertest::sim {

struct NoiseParameters {
  double quantization = 0.0;            // Q, rad
  double angle_random_walk = 0.0;       // N, rad/√s
  double bias_instability = 0.0;        // B, rad/s
  double rate_random_walk = 0.0;        // K, rad/s/√s
  double rate_ramp = 0.0;               // R, rad/s²
  // Range of correlation times of the first-order Gauss-Markov processes whose sum makes the
  // flicker (1/f) noise of B; its Allan floor holds for τ well inside this range.
  double flicker_shortest_s = 1.0;
  double flicker_longest_s = 1.0e5;
};

// Generates, sample after sample, the mean noise rate over each sample interval (rad/s).
//
// Flicker: S(f) = B²/(2π f) (IEEE 952 C.5; S two-sided, as in eq. C.1 σ² = 4∫₀^∞ S sin⁴(πfτ)/(πfτ)² df)
// is approximated by a sum of first-order Gauss-Markov processes with correlation times T_i from
// max(shortest, dt) to longest, spaced by the ratio r (3 per decade). One process of variance s²
// has the two-sided S_i(f) = 2 s² T_i / (1 + (2π f T_i)²); summed over a log-uniform grid of
// spacing Δ = ln r it tends to s²/(2Δ·f), so s² = B²·Δ/π gives the 1/f level.
// Each process is updated every max(1, T_i/(32·dt)) samples (held in between), which keeps the cost
// of the slow ones negligible and changes their spectrum only where it is far below the fast ones.
class NoiseGenerator {
 public:
  NoiseGenerator(const NoiseParameters& parameters, double sample_interval_s, Random random);

  // Mean noise rate over the next sample interval, rad/s. The first interval starts at t = start_s
  // (the rate ramp is R·t).
  double next();

  // Starts the time axis of the ramp at start_s.
  void set_time(double start_s) { time_s_ = start_s; }

 private:
  struct GaussMarkov {
    double phi = 0.0;         // exp(-Δt_update / T)
    double innovation = 0.0;  // s·√(1 - φ²)
    std::size_t every = 1;    // update period in samples
    double value = 0.0;
  };

  NoiseParameters parameters_;
  double dt_;
  Random random_;
  std::vector<GaussMarkov> flicker_;
  double previous_angle_noise_ = 0.0;  // quantization: white angle noise e_k, rate (e_k - e_{k-1})/dt
  double walk_ = 0.0;                  // rate random walk state, rad/s
  // The rate random walk's Brownian-bridge term (noise.cc), when K > 0: a stream of its own, so
  // that adding it left the draws of every other term as they were.
  std::optional<Random> bridge_random_;
  double time_s_ = 0.0;
  std::size_t sample_ = 0;
};

}  // namespace inertest::sim
