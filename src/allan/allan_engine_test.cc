// The engine against a straightforward implementation of the NIST SP 1065 definitions, written
// here term by term in long double, and against small cases computed by hand.
#include "inertest/allan/allan_engine.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using Real = long double;

// offset + white noise (sigma 1) + a random walk of steps walk_step * N(0, 1), seeded.
std::vector<double> white_and_random_walk(std::size_t count, double offset, double walk_step, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> white(0.0, 1.0);
  std::vector<double> y(count);
  double walk = 0.0;
  for (double& v : y) {
    walk += walk_step * white(random);
    v = offset + white(random) + walk;
  }
  return y;
}

// NIST SP 1065 definitions on rate data y (frequency form where it is the plainer one).
struct Reference {
  explicit Reference(const std::vector<double>& y) : rate(y.begin(), y.end()), phase(y.size() + 1, 0.0L) {
    for (std::size_t i = 0; i < y.size(); ++i) phase[i + 1] = phase[i] + rate[i];
  }
  std::size_t n() const { return rate.size(); }
  std::vector<Real> averages(std::size_t m) const {  // non-overlapping means of m samples
    std::vector<Real> means;
    for (std::size_t j = 0; (j + 1) * m <= n(); ++j) {
      Real s = 0;
      for (std::size_t i = j * m; i < (j + 1) * m; ++i) s += rate[i];
      means.push_back(s / static_cast<Real>(m));
    }
    return means;
  }
  // eq. (6): 1/(2(M-1)) sum (ybar_{i+1} - ybar_i)^2
  Real adev(std::size_t m) const {
    const auto y = averages(m);
    Real s = 0;
    for (std::size_t i = 0; i + 1 < y.size(); ++i) s += (y[i + 1] - y[i]) * (y[i + 1] - y[i]);
    return s / (2 * static_cast<Real>(y.size() - 1));
  }
  // eq. (11) on phase x (tau0 = 1)
  Real oadev(std::size_t m) const {
    const std::size_t nx = phase.size();
    Real s = 0;
    for (std::size_t i = 0; i + 2 * m < nx; ++i) {
      const Real d = phase[i + 2 * m] - 2 * phase[i + m] + phase[i];
      s += d * d;
    }
    return s / (2 * static_cast<Real>(m * m) * static_cast<Real>(nx - 2 * m));
  }
  // eq. (14)
  Real mdev(std::size_t m) const {
    const std::size_t nx = phase.size();
    Real s = 0;
    for (std::size_t j = 0; j + 3 * m <= nx; ++j) {
      Real inner = 0;
      for (std::size_t i = j; i < j + m; ++i) inner += phase[i + 2 * m] - 2 * phase[i + m] + phase[i];
      s += inner * inner;
    }
    const Real mm = static_cast<Real>(m);
    return s / (2 * mm * mm * mm * mm * static_cast<Real>(nx - 3 * m + 1));
  }
  // eq. (16), frequency form
  Real hdev(std::size_t m) const {
    const auto y = averages(m);
    Real s = 0;
    for (std::size_t i = 0; i + 2 < y.size(); ++i) {
      const Real d = y[i + 2] - 2 * y[i + 1] + y[i];
      s += d * d;
    }
    return s / (6 * static_cast<Real>(y.size() - 2));
  }
  // eq. (17), phase form
  Real ohdev(std::size_t m) const {
    const std::size_t nx = phase.size();
    Real s = 0;
    for (std::size_t i = 0; i + 3 * m < nx; ++i) {
      const Real d = phase[i + 3 * m] - 3 * phase[i + 2 * m] + 3 * phase[i + m] - phase[i];
      s += d * d;
    }
    return s / (6 * static_cast<Real>(m * m) * static_cast<Real>(nx - 3 * m));
  }
  // eq. (25): the phase extended by reflection to 3N_x - 4 points, centres i = 2..N_x-1 (1-based).
  Real totdev(std::size_t m) const {
    const std::size_t nx = phase.size();
    std::vector<Real> extended;
    for (std::size_t j = nx - 2; j >= 1; --j) extended.push_back(2 * phase[0] - phase[j]);  // x*_{1-j}
    const std::size_t first = extended.size();
    extended.insert(extended.end(), phase.begin(), phase.end());
    for (std::size_t j = 1; j <= nx - 2; ++j) extended.push_back(2 * phase[nx - 1] - phase[nx - 1 - j]);
    Real s = 0;
    for (std::size_t i = 1; i + 1 < nx; ++i) {
      const std::size_t c = first + i;
      const Real d = extended[c - m] - 2 * extended[c] + extended[c + m];
      s += d * d;
    }
    return s / (2 * static_cast<Real>(m * m) * static_cast<Real>(nx - 2));
  }
  Real variance(Estimator e, std::size_t m) const {
    switch (e) {
      case Estimator::kAdev: return adev(m);
      case Estimator::kOadev: return oadev(m);
      case Estimator::kMdev: return mdev(m);
      case Estimator::kHdev: return hdev(m);
      case Estimator::kOhdev: return ohdev(m);
      case Estimator::kTotdev: return totdev(m);
    }
    return 0;
  }

  std::vector<Real> rate;
  std::vector<Real> phase;
};

double mean_of(const std::vector<double>& y) {
  Real s = 0;
  for (double v : y) s += static_cast<Real>(v);
  return static_cast<double>(s / static_cast<Real>(y.size()));
}

// The chunk size that runs the engine in place, on a copy of the samples, instead of pushing them.
constexpr std::size_t kInPlace = 0;

std::vector<AllanSums> run_engine(const std::vector<double>& y, std::vector<std::size_t> factors,
                                  std::size_t workers, std::size_t block, std::size_t chunk,
                                  EstimatorSet estimators = EstimatorSet::all(), std::size_t ring_limit = 0,
                                  std::size_t* deferred = nullptr) {
  AllanEngineOptions options;
  options.averaging_factors = std::move(factors);
  options.estimators = estimators;
  options.worker_count = workers;
  options.block_size = block;
  options.ring_capacity_limit = ring_limit;
  if (chunk == kInPlace) {
    std::vector<double> samples = y;
    AllanEngine engine(samples, mean_of(y), options);
    if (deferred != nullptr) *deferred = engine.deferred_factor_count();
    EXPECT_EQ(engine.ring_bytes(), 0U);
    return engine.finish();
  }
  AllanEngine engine(y.size(), mean_of(y), options);
  for (std::size_t i = 0; i < y.size(); i += chunk) {
    engine.push(std::span<const double>(y).subspan(i, std::min(chunk, y.size() - i)));
  }
  if (deferred != nullptr) *deferred = engine.deferred_factor_count();
  return engine.finish([&y](std::size_t first, std::span<double> out) {
    std::copy_n(y.begin() + static_cast<std::ptrdiff_t>(first), out.size(), out.begin());
  });
}

TEST(AllanEngine, HandComputedFourSamples) {
  // y = 1, 3, 2, 6: phase X = 0, 1, 4, 6, 12 (without the mean, which no estimator sees).
  const std::vector<double> y = {1, 3, 2, 6};
  const auto m1 = run_engine(y, {1}, 1, 4, 4);
  // Second differences of X: 2, -1, 4.
  EXPECT_NEAR_RELATIVE(m1[0].variance(Estimator::kOadev), 21.0 / 6.0, 1e-14);
  EXPECT_NEAR_RELATIVE(m1[0].variance(Estimator::kAdev), 21.0 / 6.0, 1e-14);
  EXPECT_NEAR_RELATIVE(m1[0].variance(Estimator::kMdev), 21.0 / 6.0, 1e-14);
  EXPECT_NEAR_RELATIVE(m1[0].variance(Estimator::kTotdev), 21.0 / 6.0, 1e-14);
  // Second differences of y: -3, 5: (9 + 25) / (6 * 2).
  EXPECT_NEAR_RELATIVE(m1[0].variance(Estimator::kHdev), 34.0 / 12.0, 1e-14);
  EXPECT_NEAR_RELATIVE(m1[0].variance(Estimator::kOhdev), 34.0 / 12.0, 1e-14);

  // m = 2 without the third-difference estimators (which need N >= 3m).
  EstimatorSet second;
  for (Estimator e : {Estimator::kAdev, Estimator::kOadev, Estimator::kTotdev}) second.insert(e);
  const auto m2 = run_engine(y, {2}, 1, 4, 4, second);
  // Averages 2 and 4: (4 - 2)^2 / 2.
  EXPECT_NEAR_RELATIVE(m2[0].variance(Estimator::kAdev), 2.0, 1e-14);
  EXPECT_NEAR_RELATIVE(m2[0].variance(Estimator::kOadev), 2.0, 1e-14);
  // Centres 1, 2, 3 of the reflected phase: 3 (X*_-1 = -1), 4, 7 (X*_5 = 2*12 - 6): 74 / (2*4*3).
  EXPECT_NEAR_RELATIVE(m2[0].variance(Estimator::kTotdev), 74.0 / 24.0, 1e-14);
}

TEST(AllanEngine, AgreesWithDefinitionsToOnePartInTenToTheNine) {
  const std::vector<double> y = white_and_random_walk(3001, 5.0, 0.05, 7);
  const Reference reference(y);
  // 1, 2, 4, 8 and 16 divide the engine's lane count: their ADEV and HDEV come from the lanes of the
  // overlapping sweeps; the others from strided passes.
  const std::vector<std::size_t> factors = {1, 2, 3, 4, 5, 8, 16, 100, 333, 640, 1000};
  // Small blocks and odd chunks make the ring wrap and the pieces split; 1 and 2 workers; pushed
  // or in place; with third differences (all six) and without (ADEV and OADEV).
  for (const char* estimators : {"all", "adev,oadev"}) {
    const EstimatorSet set = EstimatorSet::parse(estimators);
    for (std::size_t chunk : {std::size_t{97}, kInPlace}) {
      for (std::size_t workers : {1u, 2u}) {
        for (std::size_t block : {7u, 64u, 1u << 15}) {
          const auto sums = run_engine(y, factors, workers, block, chunk, set);
          ASSERT_EQ(sums.size(), factors.size());
          for (const AllanSums& s : sums) {
            for (Estimator e : set.members()) {
              const double expected = static_cast<double>(reference.variance(e, s.averaging_factor));
              EXPECT_NEAR_RELATIVE(s.variance(e), expected, 1e-9) << estimator_name(e) << " m=" << s.averaging_factor
                                                                    << " block=" << block << " chunk=" << chunk;
            }
          }
        }
      }
    }
  }
}

// A ring limit sends the large factors to the second pass, which re-reads the samples into windows
// of the phase: the sums are those of the definitions, for every estimator and both end regions.
TEST(AllanEngine, SecondPassForFactorsBeyondTheRingLimit) {
  const std::vector<double> y = white_and_random_walk(2000, -3.0, 0.05, 13);
  const Reference reference(y);
  const std::vector<std::size_t> factors = {1, 3, 50, 200, 333, 500, 640, 666};
  for (std::size_t workers : {1u, 2u}) {
    for (std::size_t block : {16u, 100u}) {
      std::size_t deferred = 0;
      // 700 phase values: factors with 3m + 2 blocks > 700 are deferred.
      const auto sums = run_engine(y, factors, workers, block, 33, EstimatorSet::all(), 700, &deferred);
      EXPECT_GE(deferred, 4u);
      ASSERT_EQ(sums.size(), factors.size());
      for (std::size_t i = 0; i < sums.size(); ++i) {
        EXPECT_EQ(sums[i].averaging_factor, factors[i]);
        for (Estimator e : kAllEstimators) {
          const double expected = static_cast<double>(reference.variance(e, sums[i].averaging_factor));
          EXPECT_NEAR_RELATIVE(sums[i].variance(e), expected, 1e-9)
              << estimator_name(e) << " m=" << sums[i].averaging_factor << " block=" << block;
        }
      }
    }
  }
  // Second differences only: the span is 2m.
  EstimatorSet second;
  for (Estimator e : {Estimator::kAdev, Estimator::kOadev, Estimator::kTotdev}) second.insert(e);
  std::size_t deferred = 0;
  const auto sums = run_engine(y, {2, 999, 1000}, 2, 64, 500, second, 300, &deferred);
  EXPECT_EQ(deferred, 2u);
  for (const AllanSums& s : sums) {
    for (Estimator e : second.members()) {
      EXPECT_NEAR_RELATIVE(s.variance(e), static_cast<double>(reference.variance(e, s.averaging_factor)), 1e-9);
    }
  }
}

TEST(AllanEngine, SecondPassNeedsAReader) {
  const std::vector<double> y(100, 1.0);
  AllanEngineOptions options;
  options.averaging_factors = {1, 30};
  options.block_size = 8;
  options.ring_capacity_limit = 40;
  AllanEngine engine(y.size(), 1.0, options);
  engine.push(y);
  EXPECT_EQ(engine.deferred_factor_count(), 1u);
  EXPECT_THROW(engine.finish(), Error);
}

// The MDEV window is summed in parallel chains over long runs: the same sums as one chain.
TEST(AllanEngine, ModifiedAllanOverLongRunsAgreesWithTheDefinition) {
  std::mt19937_64 random(21);
  std::normal_distribution<double> white(0.0, 1.0);
  std::vector<double> y(20000);
  for (double& v : y) v = 1e3 + white(random);
  const Reference reference(y);
  EstimatorSet modified;
  modified.insert(Estimator::kMdev);
  const auto sums = run_engine(y, {1, 7, 64, 1000, 6000}, 2, 1u << 15, 20000, modified);
  for (const AllanSums& s : sums) {
    EXPECT_NEAR_RELATIVE(s.variance(Estimator::kMdev),
                         static_cast<double>(reference.variance(Estimator::kMdev, s.averaging_factor)), 1e-9)
        << s.averaging_factor;
  }
}

// MDEV's chains sum each chunk's windows as s (n s + 2 sum l_k) + sum l_k^2, s the window before the
// chunk and l_k the chunk's own. A window that falls from large to small inside a chunk cancels
// there: spikes of 1e7 over white noise of 1, and a step of 1e5 in the rate, at factors whose
// windows leave the spike inside a chunk, still agree with the definition.
TEST(AllanEngine, ModifiedAllanWindowsThatCollapseInAChunk) {
  std::mt19937_64 random(5);
  std::normal_distribution<double> white(0.0, 1.0);
  std::vector<double> y(40000);
  for (double& v : y) v = white(random);
  for (std::size_t at : {5000u, 5001u, 17003u, 33333u}) y[at] += 1e7;
  for (std::size_t i = 25000; i < y.size(); ++i) y[i] += 1e5;
  const Reference reference(y);
  EstimatorSet modified;
  modified.insert(Estimator::kMdev);
  for (std::size_t workers : {1u, 2u}) {
    for (const AllanSums& s : run_engine(y, {1, 2, 3, 10, 100, 900, 5000}, workers, 1u << 15, 40000, modified)) {
      EXPECT_NEAR_RELATIVE(s.variance(Estimator::kMdev),
                           static_cast<double>(reference.variance(Estimator::kMdev, s.averaging_factor)), 1e-9)
          << s.averaging_factor << " on " << workers << " workers";
    }
  }
}

TEST(AllanEngine, LargestFactorsOfEachEstimator) {
  std::mt19937_64 random(3);
  std::normal_distribution<double> white(0.0, 1.0);
  std::vector<double> y(301);
  for (double& v : y) v = white(random);
  const Reference reference(y);
  EstimatorSet second;
  for (Estimator e : {Estimator::kAdev, Estimator::kOadev, Estimator::kTotdev}) second.insert(e);
  EXPECT_EQ(largest_averaging_factor(301, second), 150u);
  EXPECT_EQ(largest_averaging_factor(301, EstimatorSet::all()), 100u);
  const auto sums = run_engine(y, {149, 150}, 2, 16, 50, second);
  for (const AllanSums& s : sums) {
    for (Estimator e : second.members()) {
      EXPECT_NEAR_RELATIVE(s.variance(e), static_cast<double>(reference.variance(e, s.averaging_factor)), 1e-9);
    }
  }
  const auto third = run_engine(y, {99, 100}, 2, 16, 50);
  for (const AllanSums& s : third) {
    for (Estimator e : kAllEstimators) {
      EXPECT_NEAR_RELATIVE(s.variance(e), static_cast<double>(reference.variance(e, s.averaging_factor)), 1e-9);
    }
  }
}

// Each factor's sums are formed by one worker in the order of the anchors whatever the number of
// workers, so the results are the same bits on 1, 2, 3 or more threads than factors, in the
// streaming pass and in the second pass alike (a record of 10^9 samples gives the same curve on
// any machine's thread count).
TEST(AllanEngine, SameBitsOnEveryThreadCount) {
  const std::vector<double> y = white_and_random_walk(60000, 250.0, 0.01, 31);
  std::vector<std::size_t> factors;
  for (std::size_t m = 1; m <= y.size() / 3; m *= 2) factors.push_back(m);
  factors.push_back(y.size() / 3);
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  // Pushed (with and without a second pass) and in place.
  for (const auto& [chunk, ring_limit] : {std::pair<std::size_t, std::size_t>{1000, 0}, {1000, 30000}, {kInPlace, 0}}) {
    std::size_t deferred = 0;
    const auto one = run_engine(y, factors, 1, 4096, chunk, EstimatorSet::all(), ring_limit, &deferred);
    EXPECT_EQ(deferred > 0, ring_limit > 0);
    for (std::size_t workers : {2u, 3u, 40u}) {
      const auto many = run_engine(y, factors, workers, 4096, chunk, EstimatorSet::all(), ring_limit);
      ASSERT_EQ(many.size(), one.size());
      for (std::size_t i = 0; i < one.size(); ++i) {
        for (Estimator e : kAllEstimators) {
          EXPECT_EQ(bits(many[i].sum(e)), bits(one[i].sum(e)))
              << estimator_name(e) << " m=" << one[i].averaging_factor << " workers=" << workers;
        }
        for (std::size_t d = 0; d < AveragedFrequencySeries::kOrders; ++d) {
          const double r1 = one[i].averages.series(d).autocorrelation();
          EXPECT_EQ(bits(many[i].averages.series(d).autocorrelation()), bits(r1)) << "d=" << d;
        }
      }
    }
  }
}

// TOTDEV's right end of a factor (its m - 1 last centres) is summed in pieces of 2^18 centres that
// either worker takes: ends of one and of two pieces agree with the definition and give the same
// bits on any thread count.
TEST(AllanEngine, TotalDeviationEndsInPiecesOnEveryThreadCount) {
  const std::vector<double> y = white_and_random_walk(700001, 40.0, 0.01, 53);
  const Reference reference(y);
  EstimatorSet total;
  total.insert(Estimator::kTotdev);
  const std::vector<std::size_t> factors = {3, std::size_t{1} << 18, (std::size_t{1} << 18) + 2, 350000};
  const auto one = run_engine(y, factors, 1, 1u << 15, 1u << 16, total);
  for (const AllanSums& s : one) {
    EXPECT_NEAR_RELATIVE(s.variance(Estimator::kTotdev),
                         static_cast<double>(reference.variance(Estimator::kTotdev, s.averaging_factor)), 1e-9)
        << "m=" << s.averaging_factor;
  }
  for (std::size_t workers : {2u, 3u}) {
    const auto many = run_engine(y, factors, workers, 1u << 15, 1u << 16, total);
    ASSERT_EQ(many.size(), one.size());
    for (std::size_t i = 0; i < one.size(); ++i) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(many[i].sum(Estimator::kTotdev)),
                std::bit_cast<std::uint64_t>(one[i].sum(Estimator::kTotdev)))
          << "m=" << one[i].averaging_factor << " workers=" << workers;
    }
  }
}

// A reader writing the samples into the ring (room, then commit, in pieces of any size up to the
// room given) gives the bits of push(), with and without a second pass; past N samples, room() and
// commit() refuse.
TEST(AllanEngine, RoomAndCommitGiveTheBitsOfPush) {
  const std::vector<double> y = white_and_random_walk(20000, 50.0, 0.01, 43);
  const std::vector<std::size_t> factors = {1, 2, 4, 8, 64, 1000, 6000};
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  for (std::size_t ring_limit : {std::size_t{0}, std::size_t{9000}}) {
    const auto pushed = run_engine(y, factors, 2, 1024, 333, EstimatorSet::all(), ring_limit);
    AllanEngineOptions options;
    options.averaging_factors = factors;
    options.block_size = 1024;
    options.ring_capacity_limit = ring_limit;
    AllanEngine engine(y.size(), mean_of(y), options);
    for (std::size_t done = 0, piece = 1; done < y.size(); piece = piece % 777 + 1) {
      const std::span<double> slots = engine.room();
      ASSERT_GE(slots.size(), 1U);
      const std::size_t count = std::min({piece, slots.size(), y.size() - done});
      std::copy_n(y.begin() + static_cast<std::ptrdiff_t>(done), count, slots.begin());
      engine.commit(count);
      done += count;
    }
    EXPECT_THROW(engine.room(), Error);
    EXPECT_THROW(engine.commit(1), Error);  // more than room() could have given
    EXPECT_EQ(engine.deferred_factor_count() > 0, ring_limit > 0);
    const auto written = engine.finish([&y](std::size_t first, std::span<double> out) {
      std::copy_n(y.begin() + static_cast<std::ptrdiff_t>(first), out.size(), out.begin());
    });
    ASSERT_EQ(written.size(), pushed.size());
    for (std::size_t i = 0; i < pushed.size(); ++i) {
      for (Estimator e : kAllEstimators) {
        EXPECT_EQ(bits(written[i].sum(e)), bits(pushed[i].sum(e))) << estimator_name(e) << " m=" << pushed[i].averaging_factor;
      }
    }
  }
}

// Long runs (the 16 lanes, the 8 MDEV chains and the vector kernels) on a record with a large
// offset and a rate random walk: every estimator still within 1e-9 of the long-double definitions.
TEST(AllanEngine, LongRunsAgreeWithTheDefinitions) {
  const std::vector<double> y = white_and_random_walk(30011, 1e4, 0.02, 37);
  const Reference reference(y);
  const std::vector<std::size_t> factors = {1, 2, 4, 17, 256, 1000, 2500};
  for (std::size_t block : {4093u, 1u << 15}) {
    for (const AllanSums& s : run_engine(y, factors, 2, block, 30011)) {
      for (Estimator e : kAllEstimators) {
        EXPECT_NEAR_RELATIVE(s.variance(e), static_cast<double>(reference.variance(e, s.averaging_factor)), 1e-9)
            << estimator_name(e) << " m=" << s.averaging_factor << " block=" << block;
      }
    }
  }
}

// A record streamed once is integrated about a provisional offset (the mean of its first chunk):
// no estimator depends on it, and offset + X_N / N is the mean.
TEST(AllanEngine, ProvisionalOffsetGivesTheSameSumsAndTheMean) {
  const std::vector<double> y = white_and_random_walk(20011, 50.0, 0.02, 41);
  const Reference reference(y);
  const double mean = mean_of(y);
  std::vector<std::size_t> factors = {1, 2, 7, 64, 700, 1000, 6000, 6670};
  AllanEngineOptions options;
  options.averaging_factors = factors;
  options.block_size = 4096;
  const auto exact = run_engine(y, factors, 2, 4096, 1000);
  for (double offset : {y[0], mean + 0.5, mean - 3.0}) {
    for (std::size_t ring_limit : {std::size_t{0}, std::size_t{12000}}) {
      options.ring_capacity_limit = ring_limit;
      AllanEngine engine(y.size(), offset, options);
      for (std::size_t i = 0; i < y.size(); i += 777) {
        engine.push(std::span<const double>(y).subspan(i, std::min<std::size_t>(777, y.size() - i)));
      }
      const auto sums = engine.finish([&y](std::size_t first, std::span<double> out) {
        std::copy_n(y.begin() + static_cast<std::ptrdiff_t>(first), out.size(), out.begin());
      });
      EXPECT_NEAR_RELATIVE(offset + engine.phase_total() / static_cast<double>(y.size()), mean, 1e-14);
      ASSERT_EQ(sums.size(), factors.size());
      for (std::size_t i = 0; i < sums.size(); ++i) {
        for (Estimator e : kAllEstimators) {
          EXPECT_NEAR_RELATIVE(sums[i].variance(e), static_cast<double>(reference.variance(e, factors[i])), 1e-9)
              << estimator_name(e) << " m=" << factors[i] << " offset=" << offset;
        }
        // The B1 ratio's variance of the overlapping averages (the factors with fewer than 30 averages).
        EXPECT_EQ(std::isnan(sums[i].overlapping_average_variance), std::isnan(exact[i].overlapping_average_variance));
        if (!std::isnan(exact[i].overlapping_average_variance)) {
          EXPECT_NEAR_RELATIVE(sums[i].overlapping_average_variance, exact[i].overlapping_average_variance, 1e-9)
              << "m=" << factors[i];
        }
        for (std::size_t d = 1; d < AveragedFrequencySeries::kOrders; ++d) {
          const double r1 = exact[i].averages.series(d).autocorrelation();  // NaN below 2 values
          if (std::isnan(r1)) continue;
          EXPECT_NEAR(sums[i].averages.series(d).autocorrelation(), r1, 1e-9) << "m=" << factors[i] << " d=" << d;
        }
      }
    }
  }
}

// The phase is integrated block by block, each block in four chains side by side (their carries
// added after), and swept in sub-blocks: lengths that are no multiple of the block, of the four
// chains or of the sweep, the shortest records and the largest factors give the definitions.
TEST(AllanEngine, BlockedIntegrationOnAwkwardLengths) {
  for (std::size_t n : {3u, 4u, 7u, 257u, 1031u, 4099u, 9001u}) {
    const std::vector<double> y = white_and_random_walk(n, -20.0, 0.03, 50 + n);
    const Reference reference(y);
    std::vector<std::size_t> factors = {1};
    if (n / 3 > 2) factors.push_back(n / 3 - 1);
    if (n / 3 > 1) factors.push_back(n / 3);
    for (std::size_t block : {1u, 5u, 256u, 300u, 1024u, 4096u, 5000u}) {
      for (std::size_t workers : {1u, 2u}) {
        for (std::size_t chunk : {std::size_t{333}, kInPlace}) {
          const auto sums = run_engine(y, factors, workers, block, chunk);
          ASSERT_EQ(sums.size(), factors.size());
          for (const AllanSums& s : sums) {
            for (Estimator e : kAllEstimators) {
              EXPECT_NEAR_RELATIVE(s.variance(e), static_cast<double>(reference.variance(e, s.averaging_factor)), 1e-9)
                  << estimator_name(e) << " n=" << n << " m=" << s.averaging_factor << " block=" << block
                  << " chunk=" << chunk;
            }
          }
        }
      }
    }
    // Second differences only: 2m up to N.
    EstimatorSet second;
    for (Estimator e : {Estimator::kAdev, Estimator::kOadev, Estimator::kTotdev}) second.insert(e);
    if (n / 2 > 1) {
      const auto sums = run_engine(y, {1, n / 2}, 2, 256, 100, second);
      for (const AllanSums& s : sums) {
        for (Estimator e : second.members()) {
          EXPECT_NEAR_RELATIVE(s.variance(e), static_cast<double>(reference.variance(e, s.averaging_factor)), 1e-9)
              << estimator_name(e) << " n=" << n << " m=" << s.averaging_factor;
        }
      }
    }
  }
}

// Hand-computed: y = 1, 3, 2, 6 integrated about the offset 2 (not the mean 3): X = 0, -1, 0, 0, 4.
TEST(AllanEngine, PhaseTotalIsTheSumAboutTheOffset) {
  const std::vector<double> y = {1, 3, 2, 6};
  AllanEngineOptions options;
  options.averaging_factors = {1};
  AllanEngine engine(y.size(), 2.0, options);
  engine.push(y);
  EXPECT_THROW((void)engine.phase_total(), Error);
  const auto sums = engine.finish();
  EXPECT_EQ(engine.phase_total(), 4.0);
  // Second differences of X: 2, -1, 4, as about the mean.
  EXPECT_NEAR_RELATIVE(sums[0].variance(Estimator::kOadev), 21.0 / 6.0, 1e-14);
}

TEST(AllanEngine, RejectsUnsupportedFactorsAndMissingSamples) {
  AllanEngineOptions options;
  options.averaging_factors = {4};
  EXPECT_THROW(AllanEngine(10, 0.0, options), Error);
  options.averaging_factors = {1};
  AllanEngine engine(10, 0.0, options);
  const std::vector<double> five(5, 1.0);
  engine.push(five);
  EXPECT_THROW(engine.finish(), Error);
  const std::vector<double> six(6, 1.0);
  EXPECT_THROW(engine.push(six), Error);
}

}  // namespace
}  // namespace inertest
