// Greenhall's edf against Stable32, which implements the same algorithm: the bounds Stable32 1.60
// printed for PHASE.DAT (1001 phase points, white FM, alpha = 0; the allantools test data
// tests/phasedat/phase_dat_{mdev,hdev,ohdev}_octave.txt), recomputed from its deviation with our edf.
#include "inertest/allan/confidence.h"

#include <cmath>

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

struct Stable32Row {
  double m;
  double lower;
  double deviation;
  double upper;
};

// Stable32 prints 5 significant digits. Below an edf of 100 its bounds and ours agree to 1.6e-4
// relative (the edf to about 0.05 %, the bounds being printed to 7e-6); above 100 Stable32 uses an
// approximation of the chi-squared quantiles, which moves its bounds by up to 4e-4.
void expect_stable32_bounds(const Stable32Row& row, int d, bool overlapping, bool modified) {
  const double edf = edf_greenhall(NoiseType::kWhiteFrequency, d, row.m, 1001.0, overlapping, modified);
  const DeviationInterval interval = chi_squared_interval(row.deviation, edf, kOneSigmaConfidence);
  const double tolerance = edf > 100.0 ? 5e-4 : 2e-4;
  EXPECT_NEAR_RELATIVE(interval.lower, row.lower, tolerance) << "m=" << row.m << " edf=" << edf;
  EXPECT_NEAR_RELATIVE(interval.upper, row.upper, tolerance) << "m=" << row.m << " edf=" << edf;
}

TEST(GreenhallEdf, ModifiedAllanMatchesStable32) {
  for (const Stable32Row& row : {Stable32Row{1, 2.8515e-01, 2.9223e-01, 2.9987e-01},
                                 Stable32Row{2, 1.5336e-01, 1.5821e-01, 1.6355e-01},
                                 Stable32Row{4, 1.0322e-01, 1.0780e-01, 1.1304e-01},
                                 Stable32Row{8, 6.9840e-02, 7.4192e-02, 7.9481e-02},
                                 Stable32Row{16, 3.8022e-02, 4.1376e-02, 4.5809e-02},
                                 Stable32Row{32, 3.0466e-02, 3.4255e-02, 3.9933e-02},
                                 Stable32Row{64, 2.3687e-02, 2.7871e-02, 3.5511e-02},
                                 Stable32Row{128, 1.4874e-02, 1.8669e-02, 2.8584e-02}}) {
    expect_stable32_bounds(row, 2, true, true);
  }
}

TEST(GreenhallEdf, OverlappingHadamardMatchesStable32) {
  for (const Stable32Row& row : {Stable32Row{1, 2.8635e-01, 2.9439e-01, 3.0315e-01},
                                 Stable32Row{2, 1.9491e-01, 2.0125e-01, 2.0825e-01},
                                 Stable32Row{4, 1.3777e-01, 1.4368e-01, 1.5043e-01},
                                 Stable32Row{8, 1.0388e-01, 1.0987e-01, 1.1704e-01},
                                 Stable32Row{16, 5.6173e-02, 6.0638e-02, 6.6369e-02},
                                 Stable32Row{32, 4.0664e-02, 4.5095e-02, 5.1382e-02},
                                 Stable32Row{64, 2.9271e-02, 3.3824e-02, 4.1477e-02},
                                 Stable32Row{128, 2.3761e-02, 2.9147e-02, 4.1367e-02}}) {
    expect_stable32_bounds(row, 3, true, false);
  }
}

TEST(GreenhallEdf, HadamardMatchesStable32) {
  for (const Stable32Row& row : {Stable32Row{1, 2.8635e-01, 2.9439e-01, 3.0315e-01},
                                 Stable32Row{2, 1.9887e-01, 2.0716e-01, 2.1659e-01},
                                 Stable32Row{4, 1.4054e-01, 1.4890e-01, 1.5896e-01},
                                 Stable32Row{8, 1.0744e-01, 1.1649e-01, 1.2829e-01},
                                 Stable32Row{16, 5.3296e-02, 5.9589e-02, 6.8811e-02},
                                 Stable32Row{32, 4.6987e-02, 5.4697e-02, 6.8092e-02},
                                 Stable32Row{64, 2.4870e-02, 3.0569e-02, 4.3652e-02},
                                 Stable32Row{128, 2.8841e-02, 3.8060e-02, 7.3807e-02}}) {
    expect_stable32_bounds(row, 3, false, false);
  }
}

// White PM, unmodified: the basic sum is exact and equals Greenhall's case 4 closed form
// 1/edf = (1/M)(a0 - a1/r), a0 = C(4d,2d)/C(2d,d)^2, a1 = d/2, r = M/S.
TEST(GreenhallEdf, WhitePhaseClosedForm) {
  const double n = 100001.0;
  for (double m : {1.0, 7.0, 64.0, 1000.0}) {
    // OHVAR: d = 3, S = m, M = N - 3m; a0 = 924/400.
    const double big_m = n - 3.0 * m;
    const double expected = big_m / (924.0 / 400.0 - 1.5 / (big_m / m));
    EXPECT_NEAR_RELATIVE(edf_greenhall(NoiseType::kWhitePhase, 3, m, n, true, false), expected, 1e-12) << m;
    // AVAR: d = 2, S = 1, M = floor((N - 1)/m) - 1; a0 = 70/36.
    const double terms = std::floor((n - 1.0) / m) - 1.0;
    EXPECT_NEAR_RELATIVE(edf_greenhall(NoiseType::kWhitePhase, 2, m, n, false, false),
                         terms / (70.0 / 36.0 - 1.0 / terms), 1e-12)
        << m;
  }
}

// Far into the table regime the tables agree with the basic sum they summarise.
TEST(GreenhallEdf, TablesContinueTheBasicSum) {
  const double n = 1e6 + 1.0;
  // Modified, d = 2, flicker FM: J = 3m crosses Jmax = 100 between m = 33 and m = 34.
  const double below = edf_greenhall(NoiseType::kFlickerFrequency, 2, 33, n, true, true);
  const double above = edf_greenhall(NoiseType::kFlickerFrequency, 2, 34, n, true, true);
  EXPECT_NEAR_RELATIVE(above, below * 33.0 / 34.0, 0.02);
  // Unmodified, d = 3, random walk FM: J = 4m crosses Jmax between m = 25 and 26.
  const double h_below = edf_greenhall(NoiseType::kRandomWalkFrequency, 3, 25, n, true, false);
  const double h_above = edf_greenhall(NoiseType::kRandomWalkFrequency, 3, 26, n, true, false);
  EXPECT_NEAR_RELATIVE(h_above, h_below * 25.0 / 26.0, 0.02);
}

TEST(GreenhallEdf, RejectsPointsOutsideTheAlgorithm) {
  EXPECT_THROW(edf_greenhall(NoiseType::kRandomWalkFrequency, 1, 4, 1000, true, false), Error);  // alpha + 2d = 0
  EXPECT_THROW(edf_greenhall(NoiseType::kWhiteFrequency, 4, 4, 1000, true, false), Error);
  EXPECT_THROW(edf_greenhall(NoiseType::kWhiteFrequency, 2, 0.5, 1000, true, false), Error);
  EXPECT_THROW(edf_greenhall(NoiseType::kWhiteFrequency, 3, 400, 1000, true, false), Error);  // no term
}

TEST(EquivalentDegreesOfFreedom, EveryEstimatorNamesItsMethod) {
  for (Estimator e : kAllEstimators) EXPECT_FALSE(edf_method(e).empty());
  // Every Allan and Hadamard variance uses Greenhall's algorithm with N + 1 phase points; ADEV and
  // OADEV used the simple formulae of Table 5 before, which differ (here by 3 %).
  const NoiseType white = NoiseType::kWhiteFrequency;
  EXPECT_DOUBLE_EQ(equivalent_degrees_of_freedom(Estimator::kMdev, 1000, 16, white),
                   edf_greenhall(white, 2, 16, 1001, true, true));
  EXPECT_DOUBLE_EQ(equivalent_degrees_of_freedom(Estimator::kOadev, 1000, 16, white),
                   edf_greenhall(white, 2, 16, 1001, true, false));
  EXPECT_DOUBLE_EQ(equivalent_degrees_of_freedom(Estimator::kAdev, 1000, 16, white),
                   edf_greenhall(white, 2, 16, 1001, false, false));
  EXPECT_GT(std::abs(equivalent_degrees_of_freedom(Estimator::kOadev, 1000, 16, white) /
                         edf_overlapping_allan(1001, 16, white) - 1.0),
            0.01);
  // TOTDEV: Table 7 with T/tau = N_x / m; white PM takes Table 5.
  EXPECT_DOUBLE_EQ(equivalent_degrees_of_freedom(Estimator::kTotdev, 1000, 16, white), 1.5 * 1001.0 / 16.0);
  EXPECT_DOUBLE_EQ(equivalent_degrees_of_freedom(Estimator::kTotdev, 1000, 16, NoiseType::kWhitePhase),
                   edf_overlapping_allan(1001, 16, NoiseType::kWhitePhase));
}

}  // namespace
}  // namespace inertest
