#include "inertest/centrifuge/harmonic_analysis.h"

#include <cmath>
#include <random>
#include <vector>

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest::centrifuge {
namespace {

constexpr double kPi = constants::kPi;
const HarmonicAmplitudes kTruth = {11.3851, 25.4733, -48.2694, -0.0256, 0.0007};

double signal(double gamma) {
  double y = 0.0;
  for (std::size_t h = 0; h < kHarmonicCount; ++h) y += kTruth[h] * harmonic_basis(h, gamma);
  return y;
}

TEST(CentrifugeHarmonicAnalysis, ExactDftOverOneRevolution) {
  std::vector<double> gamma;
  std::vector<double> output;
  for (int i = 0; i < 36; ++i) {
    gamma.push_back(i * 10.0 * constants::kDegree);  // as read from a file in degrees
    output.push_back(signal(gamma.back()));
  }
  const HarmonicFit fit = analyse_harmonics(gamma, output);
  EXPECT_EQ(fit.method, HarmonicFit::Method::kDiscreteFourier);
  EXPECT_EQ(fit.sample_count, 36u);
  EXPECT_DOUBLE_EQ(fit.revolutions, 1.0);
  for (std::size_t h = 0; h < kHarmonicCount; ++h) EXPECT_NEAR(fit.amplitudes[h], kTruth[h], 1e-13);
  EXPECT_LT(fit.residual_rms, 1e-13);
}

TEST(CentrifugeHarmonicAnalysis, ExactDftOverSeveralRevolutionsWithStartAngle) {
  std::vector<double> gamma;
  std::vector<double> output;
  for (int i = 0; i < 21; ++i) {  // 3 revolutions in steps of 360 * 3 / 21 deg, starting at 5 deg
    gamma.push_back((5.0 + i * 360.0 * 3.0 / 21.0) * constants::kDegree);
    output.push_back(signal(gamma.back()));
  }
  const HarmonicFit fit = analyse_harmonics(gamma, output);
  EXPECT_EQ(fit.method, HarmonicFit::Method::kDiscreteFourier);
  EXPECT_DOUBLE_EQ(fit.revolutions, 3.0);
  for (std::size_t h = 0; h < kHarmonicCount; ++h) EXPECT_NEAR(fit.amplitudes[h], kTruth[h], 1e-12);
}

// A third harmonic is orthogonal to the five terms over whole revolutions: the DFT bins ignore it
// and the residual rms is its rms, A3 / sqrt(2).
TEST(CentrifugeHarmonicAnalysis, ResidualRmsOfAnUnmodelledHarmonic) {
  std::vector<double> gamma;
  std::vector<double> output;
  for (int i = 0; i < 36; ++i) {
    gamma.push_back(2.0 * kPi * i / 36.0);
    output.push_back(signal(gamma.back()) + 0.01 * std::cos(3.0 * gamma.back()));
  }
  const HarmonicFit fit = analyse_harmonics(gamma, output);
  for (std::size_t h = 0; h < kHarmonicCount; ++h) EXPECT_NEAR(fit.amplitudes[h], kTruth[h], 1e-13);
  EXPECT_NEAR(fit.residual_rms, 0.01 / std::sqrt(2.0), 1e-14);
}

TEST(CentrifugeHarmonicAnalysis, LeastSquaresForIrregularSampling) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * kPi);
  std::vector<double> gamma;
  std::vector<double> output;
  for (int i = 0; i < 50; ++i) {
    gamma.push_back(angle(random));
    output.push_back(signal(gamma.back()));
  }
  const HarmonicFit fit = analyse_harmonics(gamma, output);
  EXPECT_EQ(fit.method, HarmonicFit::Method::kLeastSquares);
  for (std::size_t h = 0; h < kHarmonicCount; ++h) EXPECT_NEAR(fit.amplitudes[h], kTruth[h], 1e-11);
  EXPECT_LT(fit.residual_rms, 1e-11);
}

// Equally spaced samples that do not close a revolution fall back to least squares.
TEST(CentrifugeHarmonicAnalysis, PartialRevolutionUsesLeastSquares) {
  std::vector<double> gamma;
  std::vector<double> output;
  for (int i = 0; i < 30; ++i) {
    gamma.push_back(i * 10.0 * constants::kDegree);
    output.push_back(signal(gamma.back()));
  }
  const HarmonicFit fit = analyse_harmonics(gamma, output);
  EXPECT_EQ(fit.method, HarmonicFit::Method::kLeastSquares);
  EXPECT_NEAR(fit.revolutions, 30.0 / 36.0, 1e-12);  // 290 deg first to last, and a mean step
  EXPECT_TRUE(fit.part_of_a_revolution);
  for (std::size_t h = 0; h < kHarmonicCount; ++h) EXPECT_NEAR(fit.amplitudes[h], kTruth[h], 1e-10);
}

// Angles wrapped into [0, 360) deg, as a turntable's encoder logs them: two revolutions in steps of
// 10 deg are read as two revolutions (the DFT), in either direction (they read as 0.97 of one).
TEST(CentrifugeHarmonicAnalysis, WrappedAnglesAreUnwrapped) {
  for (const double direction : {1.0, -1.0}) {
    std::vector<double> gamma;
    std::vector<double> output;
    for (int i = 0; i < 72; ++i) {
      const double degrees = std::fmod(360.0 + std::fmod(direction * i * 10.0, 360.0), 360.0);
      gamma.push_back(degrees * constants::kDegree);
      output.push_back(signal(gamma.back()));
    }
    const HarmonicFit fit = analyse_harmonics(gamma, output);
    EXPECT_EQ(fit.method, HarmonicFit::Method::kDiscreteFourier) << direction;
    EXPECT_DOUBLE_EQ(fit.revolutions, 2.0) << direction;
    EXPECT_FALSE(fit.part_of_a_revolution) << direction;
    for (std::size_t h = 0; h < kHarmonicCount; ++h) EXPECT_NEAR(fit.amplitudes[h], kTruth[h], 1e-12) << direction;
  }
}

TEST(CentrifugeHarmonicAnalysis, TooFewSamplesIsAnError) {
  const std::vector<double> gamma = {0.0, 1.0, 2.0, 3.0};
  const std::vector<double> output = {1.0, 2.0, 3.0, 4.0};
  EXPECT_THROW(analyse_harmonics(gamma, output), Error);
  EXPECT_THROW(analyse_harmonics(gamma, std::vector<double>{1.0, 2.0, 3.0}), Error);
}

// Six samples 120 deg apart cover two revolutions but see only three distinct angles: the second
// harmonic aliases onto the first and the fit says so (rank 3 of 5).
TEST(CentrifugeHarmonicAnalysis, AliasedSamplingIsAnErrorNamingHarmonics) {
  std::vector<double> gamma;
  std::vector<double> output;
  for (int i = 0; i < 6; ++i) {
    gamma.push_back(i * 2.0 * kPi / 3.0);
    output.push_back(signal(gamma.back()));
  }
  try {
    analyse_harmonics(gamma, output);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), ::testing::HasSubstr("cannot separate"));
    EXPECT_THAT(e.message(), ::testing::HasSubstr("rank 3 of 5"));
  }
}

}  // namespace
}  // namespace inertest::centrifuge
