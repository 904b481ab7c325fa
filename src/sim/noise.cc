#include "inertest/sim/noise.h"

#include <algorithm>
#include <cmath>

#include "inertest/core/error.h"
#include "inertest/core/units.h"

namespace inertest::sim {

NoiseGenerator::NoiseGenerator(const NoiseParameters& parameters, double sample_interval_s, Random random)
    : parameters_(parameters), dt_(sample_interval_s), random_(random) {
  if (!(dt_ > 0.0)) throw Error("noise: the sample interval must be positive");
  if (parameters_.quantization < 0 || parameters_.angle_random_walk < 0 || parameters_.bias_instability < 0 ||
      parameters_.rate_random_walk < 0) {
    throw Error("noise: Q, N, B and K must not be negative");
  }
  if (parameters_.bias_instability > 0.0) {
    if (!(parameters_.flicker_shortest_s > 0.0) || parameters_.flicker_longest_s <= parameters_.flicker_shortest_s) {
      throw Error("noise: the flicker correlation-time range must be positive and increasing");
    }
    const double ratio = std::pow(10.0, 1.0 / 3.0);
    const double spacing = std::log(ratio);
    const double variance = parameters_.bias_instability * parameters_.bias_instability * spacing / constants::kPi;
    const double sigma = std::sqrt(variance);
    // Processes faster than the sampling would alias into white noise: the band starts at dt.
    for (double t = std::max(parameters_.flicker_shortest_s, dt_); t <= parameters_.flicker_longest_s * 1.0001; t *= ratio) {
      GaussMarkov process;
      process.every = std::max<std::size_t>(1, static_cast<std::size_t>(t / (32.0 * dt_)));
      process.phi = std::exp(-static_cast<double>(process.every) * dt_ / t);
      process.innovation = sigma * std::sqrt(1.0 - process.phi * process.phi);
      process.value = sigma * random_.normal();  // start in the stationary distribution
      flicker_.push_back(process);
    }
  }
  if (parameters_.quantization > 0.0) previous_angle_noise_ = parameters_.quantization * random_.normal();
  if (parameters_.rate_random_walk > 0.0) bridge_random_ = random_.stream("rate random walk bridge");
}

double NoiseGenerator::next() {
  double rate = 0.0;
  // Angle random walk: white rate noise of PSD N², mean over dt has σ = N/√dt (IEEE 952 C.3).
  if (parameters_.angle_random_walk > 0.0) rate += parameters_.angle_random_walk / std::sqrt(dt_) * random_.normal();
  // Quantization: white angle noise of σ = Q, whose Allan variance is 3Q²/τ² (IEEE 952 C.2).
  if (parameters_.quantization > 0.0) {
    const double angle_noise = parameters_.quantization * random_.normal();
    rate += (angle_noise - previous_angle_noise_) / dt_;
    previous_angle_noise_ = angle_noise;
  }
  for (auto& process : flicker_) {
    if (sample_ % process.every == 0 && sample_ > 0) {
      process.value = process.phi * process.value + process.innovation * random_.normal();
    }
    rate += process.value;
  }
  // Rate random walk: dΩ = K·dW, sampled as its mean over the interval. Given the ends Ω0 and
  // Ω0 + step, that mean is (Ω0 + step/2) plus the mean of a Brownian bridge pinned at both ends,
  // which is independent of the ends and normal with variance dt/12 per unit diffusion (∫∫ of the
  // bridge covariance min(s,u) − s·u/dt over the interval, divided by dt²): K·√(dt/12)·z. Without
  // it the Allan variance at τ = m·dt falls short of K²τ/3 (IEEE Std 952-1997 Annex C, C.7) by the
  // factor 1 − 1/(4m²), 25 % at τ0; with it σ²(τ) = K²τ/3 holds down to τ0. z comes from a stream
  // of its own (bridge_random_, made only when K > 0), so the other terms' draws are unchanged.
  if (parameters_.rate_random_walk > 0.0) {
    const double step = parameters_.rate_random_walk * std::sqrt(dt_) * random_.normal();
    const double bridge = parameters_.rate_random_walk * std::sqrt(dt_ / 12.0) * bridge_random_->normal();
    rate += walk_ + 0.5 * step + bridge;
    walk_ += step;
  }
  // Rate ramp: Ω = R·t, mean over the interval at its centre (IEEE 952 C.8).
  rate += parameters_.rate_ramp * (time_s_ + 0.5 * dt_);
  time_s_ += dt_;
  ++sample_;
  return rate;
}

}  // namespace inertest::sim
