// Each noise term's Allan signature matches its IEEE Std 952-1997 Annex C meaning. The overlapping
// Allan deviation is computed here by a small direct implementation (IEEE 952 Annex C / IEEE 1139),
// independent of the library's Allan engine.
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/sim/noise.h"
#include "inertest/sim/random.h"

namespace inertest::sim {
namespace {

// Overlapping Allan deviation of a rate record (rad/s, interval dt) at τ = m·dt:
// σ²(τ) = Σ (θ_{k+2m} − 2θ_{k+m} + θ_k)² / (2τ²(N − 2m)), θ the integrated angle.
double allan_deviation(const std::vector<double>& angle, double dt, std::size_t m) {
  const std::size_t n = angle.size();
  long double sum = 0.0L;
  for (std::size_t k = 0; k + 2 * m < n; ++k) {
    const long double d = static_cast<long double>(angle[k + 2 * m]) - 2.0L * static_cast<long double>(angle[k + m]) +
                          static_cast<long double>(angle[k]);
    sum += d * d;
  }
  const double tau = static_cast<double>(m) * dt;
  return std::sqrt(static_cast<double>(sum / (n - 2 * m)) / (2.0 * tau * tau));
}

std::vector<double> integrate(NoiseGenerator& noise, std::size_t samples, double dt) {
  std::vector<double> angle(samples + 1, 0.0);
  for (std::size_t i = 0; i < samples; ++i) angle[i + 1] = angle[i] + noise.next() * dt;
  return angle;
}

TEST(SimNoise, AngleRandomWalkGivesNOverRootTau) {
  NoiseParameters p;
  p.angle_random_walk = 1e-5;  // rad/√s
  const double dt = 0.01;
  NoiseGenerator noise(p, dt, Random(1));
  const auto angle = integrate(noise, 1'000'000, dt);
  for (const std::size_t m : {1, 10, 100, 1000}) {
    const double tau = static_cast<double>(m) * dt;
    const double n_measured = allan_deviation(angle, dt, m) * std::sqrt(tau);
    EXPECT_NEAR(n_measured / p.angle_random_walk, 1.0, 0.10) << "tau " << tau;
  }
}

TEST(SimNoise, QuantizationGivesRootThreeQOverTau) {
  NoiseParameters p;
  p.quantization = 1e-6;  // rad
  const double dt = 0.01;
  NoiseGenerator noise(p, dt, Random(2));
  const auto angle = integrate(noise, 200'000, dt);
  for (const std::size_t m : {1, 10, 100}) {
    const double tau = static_cast<double>(m) * dt;
    const double q_measured = allan_deviation(angle, dt, m) * tau / std::sqrt(3.0);
    EXPECT_NEAR(q_measured / p.quantization, 1.0, 0.10) << "tau " << tau;
  }
}

TEST(SimNoise, BiasInstabilityFloorIsPoint664B) {
  NoiseParameters p;
  p.bias_instability = 1e-6;  // rad/s
  p.flicker_shortest_s = 1.0;
  p.flicker_longest_s = 1e5;
  const double dt = 1.0;
  NoiseGenerator noise(p, dt, Random(3));
  const auto angle = integrate(noise, 2'000'000, dt);
  const double floor = std::sqrt(2.0 * std::log(2.0) / constants::kPi);  // 0.664, IEEE 952 C.5
  for (const std::size_t m : {10, 30, 100, 300, 1000, 3000}) {
    const double b_measured = allan_deviation(angle, dt, m) / floor;
    EXPECT_NEAR(b_measured / p.bias_instability, 1.0, 0.10) << "tau " << m;
  }
}

TEST(SimNoise, RateRandomWalkGivesKRootTauOverThree) {
  NoiseParameters p;
  p.rate_random_walk = 1e-7;  // rad/s/√s
  const double dt = 1.0;
  NoiseGenerator noise(p, dt, Random(4));
  const auto angle = integrate(noise, 2'000'000, dt);
  for (const std::size_t m : {10, 100, 1000, 10000}) {
    const double tau = static_cast<double>(m) * dt;
    const double k_measured = allan_deviation(angle, dt, m) / std::sqrt(tau / 3.0);
    EXPECT_NEAR(k_measured / p.rate_random_walk, 1.0, 0.10) << "tau " << tau;
  }
}

// Equivalent degrees of freedom of the overlapping Allan variance of a random walk FM record
// (NIST SP 1065 Table 5): N phase points, τ = m·τ0.
double random_walk_fm_edf(std::size_t phase_points, std::size_t m) {
  const double n = static_cast<double>(phase_points);
  const double mm = static_cast<double>(m);
  return (n - 2.0) / (mm * (n - 3.0) * (n - 3.0)) * ((n - 1.0) * (n - 1.0) - 3.0 * mm * (n - 1.0) + 4.0 * mm * mm);
}

// Each sample is the mean of the walk over its interval, so σ²(τ) = K²τ/3 (IEEE 952 C.7) holds
// down to τ = τ0. The mean of the endpoints alone, without the Brownian bridge's part, gives
// K²τ/3·(1 − 1/(4m²)) at τ = m·τ0: 25 % low in variance (13 % in deviation) at τ0, 6 % at 2τ0.
// Tolerance: 5 standard deviations of the estimate, sd(σ̂²)/σ² = √(2/edf) with the edf above
// (at m = 1 about N; the exact value for these samples, an MA(1) of second differences with
// autocovariances 2/3 and 1/6 K²τ0³, is 2.25/N in relative variance, so 5 edf-sigma is 4.7 true
// sigma). 10⁶ samples: the bound is 0.7 % in variance at τ0, 1.0 % at 2τ0, 2.2 % at 10τ0.
TEST(SimNoise, RateRandomWalkIsTheIntervalMeanDownToTheSampleInterval) {
  NoiseParameters p;
  p.rate_random_walk = 2e-6;  // rad/s/√s
  const double dt = 0.01;
  const std::size_t samples = 1'000'000;
  NoiseGenerator noise(p, dt, Random(11));
  const auto angle = integrate(noise, samples, dt);
  for (const std::size_t m : {1, 2, 10}) {
    const double tau = static_cast<double>(m) * dt;
    const double sigma = allan_deviation(angle, dt, m);
    const double expected = p.rate_random_walk * p.rate_random_walk * tau / 3.0;
    const double tolerance = 5.0 * std::sqrt(2.0 / random_walk_fm_edf(angle.size(), m));
    EXPECT_NEAR(sigma * sigma / expected, 1.0, tolerance) << "tau " << tau << " s";
  }
}

// The bridge term has a stream of its own: with a rate random walk, every other draw is the one it
// was (the generator's stream gives, per sample, the angle random walk's normal, then the walk's
// step), and what the bridge adds is independent of the step with variance K²dt/12 (5 sigma:
// sd of the mean of r² is √(2/n) of K²dt/12, of the correlation 1/√n). Without a rate random walk
// the record is N/√dt times the stream's normals, exactly.
TEST(SimNoise, TheBridgeTermLeavesTheOtherDrawsAsTheyWere) {
  NoiseParameters p;
  p.angle_random_walk = 1e-5;  // rad/√s
  p.rate_random_walk = 1e-4;   // rad/s/√s
  const double dt = 0.01;
  const int n = 100'000;
  NoiseGenerator noise(p, dt, Random(12));
  Random reference(12);
  const double bridge_variance = p.rate_random_walk * p.rate_random_walk * dt / 12.0;
  double walk = 0.0;
  double sum_r2 = 0.0;
  double sum_rz = 0.0;
  for (int i = 0; i < n; ++i) {
    const double white = p.angle_random_walk / std::sqrt(dt) * reference.normal();
    const double z = reference.normal();
    const double step = p.rate_random_walk * std::sqrt(dt) * z;
    const double r = noise.next() - (white + walk + 0.5 * step);
    walk += step;
    sum_r2 += r * r;
    sum_rz += r * z;
  }
  EXPECT_NEAR(sum_r2 / n / bridge_variance, 1.0, 5.0 * std::sqrt(2.0 / n));
  EXPECT_NEAR(sum_rz / n / std::sqrt(bridge_variance), 0.0, 5.0 / std::sqrt(n));

  NoiseParameters white_only;
  white_only.angle_random_walk = 1e-5;
  NoiseGenerator white_noise(white_only, dt, Random(13));
  Random white_reference(13);
  for (int i = 0; i < 1000; ++i) {
    ASSERT_EQ(white_noise.next(), white_only.angle_random_walk / std::sqrt(dt) * white_reference.normal());
  }
}

TEST(SimNoise, RateRampGivesRTauOverRootTwo) {
  NoiseParameters p;
  p.rate_ramp = 1e-9;  // rad/s²
  const double dt = 1.0;
  NoiseGenerator noise(p, dt, Random(5));
  const auto angle = integrate(noise, 100'000, dt);
  for (const std::size_t m : {10, 1000}) {
    const double tau = static_cast<double>(m) * dt;
    EXPECT_NEAR(allan_deviation(angle, dt, m) / (p.rate_ramp * tau / std::sqrt(2.0)), 1.0, 1e-6);
  }
}

TEST(SimNoise, RejectsNegativeParameters) {
  NoiseParameters p;
  p.angle_random_walk = -1.0;
  EXPECT_THROW(NoiseGenerator(p, 0.01, Random(1)), Error);
  EXPECT_THROW(NoiseGenerator(NoiseParameters{}, 0.0, Random(1)), Error);
}

TEST(SimRandom, SameSeedSameNumbersAndKnownFirstDraws) {
  Random a(42);
  Random b(42);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a.normal(), b.normal());
  Random c(43);
  EXPECT_NE(Random(42).uniform(), c.uniform());
  EXPECT_NE(Random(42).stream("x").uniform(), Random(42).stream("y").uniform());
}

TEST(SimRandom, NormalHasUnitMomentsAndUniformIsOpen) {
  Random r(7);
  double sum = 0.0;
  double sum2 = 0.0;
  const int n = 1'000'000;
  for (int i = 0; i < n; ++i) {
    const double x = r.normal();
    sum += x;
    sum2 += x * x;
  }
  EXPECT_NEAR(sum / n, 0.0, 5.0 / std::sqrt(n));
  EXPECT_NEAR(sum2 / n, 1.0, 5.0 * std::sqrt(2.0 / n));
  for (int i = 0; i < 1000; ++i) {
    const double u = r.uniform();
    ASSERT_GT(u, 0.0);
    ASSERT_LT(u, 1.0);
  }
}

}  // namespace
}  // namespace inertest::sim
