#include "inertest/allan/allan_engine.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "inertest/core/error.h"
#include "inertest/numerics/compensated_sum.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace inertest {
namespace {

constexpr std::size_t index_of(Estimator e) { return static_cast<std::size_t>(e); }

// The ring's storage: uninitialised doubles on 2 MiB boundaries, offered to the kernel as
// transparent huge pages where it has them. The factors of large m stream from lags megabytes
// apart: with 4 KiB pages every stream runs through the TLB, and filling 8 bytes per sample would
// fault a page every 512 samples.
class PhaseBuffer {
 public:
  void reset(std::size_t count) {
    constexpr std::size_t kHugePage = std::size_t{2} << 20;
    const std::size_t bytes = (count * sizeof(double) + kHugePage - 1) / kHugePage * kHugePage;
    data_.reset(bytes == 0 ? nullptr : static_cast<double*>(std::aligned_alloc(kHugePage, bytes)));
    if (bytes != 0 && !data_) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (bytes != 0) madvise(data_.get(), bytes, MADV_HUGEPAGE);  // advice only: no huge pages is fine
#endif
  }
  double* data() { return data_.get(); }
  const double* data() const { return data_.get(); }

 private:
  struct Free {
    void operator()(double* p) const { std::free(p); }
  };
  std::unique_ptr<double[], Free> data_;
};

// Where the phase values X_j live: the ring of the streaming pass (X_j at slot j mod capacity) or,
// for the factors of the second pass, a few windows [start, start + values.size()) of the phase.
class PhaseStore {
 public:
  struct Window {
    std::size_t start = 0;
    std::vector<double> values;
  };

  PhaseStore(const double* ring, std::size_t capacity) : ring_(ring), capacity_(capacity) {}
  explicit PhaseStore(std::span<const Window> windows) : windows_(windows), windowed_(true) {}

  // A pointer to X_index; `forward` values X_index, X_index+1, ... and `backward` values X_index,
  // X_index-1, ... are contiguous from it.
  const double* locate(std::size_t index, std::size_t& forward, std::size_t& backward) const {
    if (!windowed_) {
      const std::size_t slot = index % capacity_;
      forward = capacity_ - slot;
      backward = slot + 1;
      return ring_ + slot;
    }
    for (const Window& w : windows_) {
      if (index >= w.start && index < w.start + w.values.size()) {
        forward = w.start + w.values.size() - index;
        backward = index - w.start + 1;
        return w.values.data() + (index - w.start);
      }
    }
    throw Error("internal: phase index " + std::to_string(index) + " is in no window");
  }

  double at(std::size_t index) const {
    std::size_t forward = 0;
    std::size_t backward = 0;
    return *locate(index, forward, backward);
  }

 private:
  const double* ring_ = nullptr;
  std::size_t capacity_ = 0;
  std::span<const Window> windows_;
  bool windowed_ = false;
};

// One stream of phase values along the anchors k: X_{k - lag}, or mirrored X_{base - k}.
struct Stream {
  std::size_t offset = 0;
  bool mirrored = false;
  std::size_t index(std::size_t k) const { return mirrored ? offset - k : k - offset; }
};

constexpr Stream lagged(std::size_t lag) { return {lag, false}; }
constexpr Stream mirrored(std::size_t base) { return {base, true}; }

// Calls kernel(p, count) over the anchors k = k0, k0 + step, ... < k1 in runs where every stream
// is contiguous in the store: p[s][i * step] is stream s at the i-th anchor of the run, or
// p[s][-i] for a mirrored stream (step 1).
template <std::size_t S, typename Kernel>
void for_each_run(const PhaseStore& store, const std::array<Stream, S>& streams, std::size_t k0, std::size_t k1,
                  std::size_t step, Kernel&& kernel) {
  std::size_t k = k0;
  while (k < k1) {
    std::size_t count = (k1 - k + step - 1) / step;
    std::array<const double*, S> p{};
    for (std::size_t s = 0; s < S; ++s) {
      std::size_t forward = 0;
      std::size_t backward = 0;
      p[s] = store.locate(streams[s].index(k), forward, backward);
      count = std::min(count, streams[s].mirrored ? backward : (forward + step - 1) / step);
    }
    kernel(p, count);
    k += count * step;
  }
}

// Per averaging factor: the running MDEV window and the compensated sums of squares.
struct FactorState {
  std::size_t m = 0;
  double window = 0.0;  // w_k of MDEV, updated w_k = w_{k-1} + a_k - a_{k-m}
  std::array<CompensatedSum, 6> sums;
  CompensatedSum reflected;  // TOTDEV terms whose centre lies within m of an end
  AveragedFrequencySeries averages;  // ȳ_j at the anchors k = jm, in order
  // Sums of d_k = X_k - X_{k-m}, k = m .. N, where the B1 ratio will need them (overlapping_average_variance).
  bool overlapping_averages = false;
  CompensatedSum overlapping_sum;
  CompensatedSum overlapping_squares;
};

// The engine's inner loops (marked INERTEST_VECTOR_CLONES) are compiled for the baseline x86-64
// and for AVX2, and the loader picks the one the CPU runs (GCC function multi-versioning; other
// compilers build the baseline only). The wider registers carry the same kLanes lanes and the same
// operations in the same order (AVX2 without FMA: nothing is contracted), so the sums are bit for
// bit those of the baseline build.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define INERTEST_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define INERTEST_VECTOR_CLONES
#endif

// Independent partial sums per loop: four AVX2 accumulators, so that the loop runs at the rate of
// its loads instead of one FP-add latency per vector (a single accumulator held a factor to about
// one term per cycle). The partial sums are added pairwise, which is also the more accurate order.
constexpr std::size_t kLanes = 16;

double lane_total(const double (&lanes)[kLanes]) {
  double level[kLanes];
  std::copy(std::begin(lanes), std::end(lanes), level);
  for (std::size_t width = kLanes / 2; width > 0; width /= 2) {
    for (std::size_t l = 0; l < width; ++l) level[l] = level[2 * l] + level[2 * l + 1];
  }
  return level[0];
}

// Sum of values[0..n) in kLanes independent lanes (vectorisable).
double lane_sum(const double* __restrict values, std::size_t n) {
  double lanes[kLanes] = {};
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    for (std::size_t l = 0; l < kLanes; ++l) lanes[l] += values[i + l];
  }
  for (; i < n; ++i) lanes[0] += values[i];
  return lane_total(lanes);
}

// Chains of the MDEV window recurrence run side by side (kChains add latencies overlap).
constexpr std::size_t kChains = 8;

double chain_total(const double (&chains)[kChains]) {
  return ((chains[0] + chains[1]) + (chains[2] + chains[3])) + ((chains[4] + chains[5]) + (chains[6] + chains[7]));
}

// The MDEV window over a run: w_k = w_{k-1} + h_k for k in the run, returns sum w_k^2 and leaves
// the last w in `window`. The recurrence is a chain of dependent additions (one FP-add latency per
// term); the run is cut into kChains chunks whose starting windows come from the chunk sums, and
// each chain advances four terms at a time: the prefix sums of four h in a register (two shifted
// adds), plus the chain's last window. Each w is still a sum of the same h: the rounding differs
// from the single chain by a few ulp of w, far inside the 1e-9 the estimators are held to.
INERTEST_VECTOR_CLONES
double mdev_window_squares(const double* __restrict h, std::size_t length, double& window) {
  // Four doubles in a register where the target has 256-bit ones (GCC/Clang vector extension;
  // element-wise operations are exactly those of four scalars).
  using Quad = double __attribute__((vector_size(4 * sizeof(double))));
  constexpr std::size_t kMinimumChunk = 64;
  const std::size_t chunk = length / kChains / 4 * 4;
  if (chunk < kMinimumChunk) {
    double total = 0.0;
    double w = window;
    for (std::size_t i = 0; i < length; ++i) {
      w += h[i];
      total += w * w;
    }
    window = w;
    return total;
  }
  Quad carry[kChains];  // every lane: the window before the chain's next four terms
  double start = window;
  for (std::size_t c = 0; c < kChains; ++c) {
    carry[c] = Quad{} + start;
    start += lane_sum(h + c * chunk, chunk);
  }
  const Quad zero{};
  Quad squares[kChains] = {};
  for (std::size_t i = 0; i < chunk; i += 4) {
    for (std::size_t c = 0; c < kChains; ++c) {
      Quad x;
      std::memcpy(&x, h + c * chunk + i, sizeof x);
      x += __builtin_shufflevector(zero, x, 0, 4, 5, 6);  // h0, h0+h1, h1+h2, h2+h3
      x += __builtin_shufflevector(zero, x, 0, 1, 4, 5);  // the prefix sums of the four
      const Quad w = carry[c] + x;
      squares[c] += w * w;
      carry[c] = __builtin_shufflevector(w, w, 3, 3, 3, 3);
    }
  }
  double last = carry[kChains - 1][3];
  double tail = 0.0;
  for (std::size_t i = kChains * chunk; i < length; ++i) {
    last += h[i];
    tail += last * last;
  }
  window = last;
  double chains[kChains];
  for (std::size_t c = 0; c < kChains; ++c) chains[c] = (squares[c][0] + squares[c][1]) + (squares[c][2] + squares[c][3]);
  return chain_total(chains) + tail;
}

// sum a_k^2 over a run, a_k = p0[i] - 2 p1[i] + p2[i] (NIST SP 1065 eq. 11), in kLanes lanes.
INERTEST_VECTOR_CLONES
double second_difference_squares(const double* __restrict p0, const double* __restrict p1,
                                 const double* __restrict p2, std::size_t length) {
  double lanes[kLanes] = {};
  std::size_t i = 0;
  for (; i + kLanes <= length; i += kLanes) {
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double a = p0[i + l] - 2.0 * p1[i + l] + p2[i + l];
      lanes[l] += a * a;
    }
  }
  for (; i < length; ++i) {
    const double a = p0[i] - 2.0 * p1[i] + p2[i];
    lanes[0] += a * a;
  }
  return lane_total(lanes);
}

struct ThirdDifferenceSquares {
  double second = 0.0;  // sum a_k^2
  double third = 0.0;   // sum h_k^2
};

// Over a run: a_k = p0 - 2 p1 + p2 and h_k = a_k - (p1 - 2 p2 + p3) = a_k - a_{k-m} (NIST SP 1065
// eqs. 11 and 17); with kStoreH the h_k go to `h` (MDEV needs them, OHDEV alone does not). Inlined
// into the clones of third_difference_squares, so that each is compiled for their targets.
template <bool kStoreH>
[[gnu::always_inline]] inline ThirdDifferenceSquares third_difference_loop(
    const double* __restrict p0, const double* __restrict p1, const double* __restrict p2,
    const double* __restrict p3, std::size_t length, double* __restrict h) {
  double lanes_a[kLanes] = {};
  double lanes_h[kLanes] = {};
  std::size_t i = 0;
  for (; i + kLanes <= length; i += kLanes) {
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double a = p0[i + l] - 2.0 * p1[i + l] + p2[i + l];
      const double hk = a - (p1[i + l] - 2.0 * p2[i + l] + p3[i + l]);
      if constexpr (kStoreH) h[i + l] = hk;
      lanes_a[l] += a * a;
      lanes_h[l] += hk * hk;
    }
  }
  for (; i < length; ++i) {
    const double a = p0[i] - 2.0 * p1[i] + p2[i];
    const double hk = a - (p1[i] - 2.0 * p2[i] + p3[i]);
    if constexpr (kStoreH) h[i] = hk;
    lanes_a[0] += a * a;
    lanes_h[0] += hk * hk;
  }
  return {lane_total(lanes_a), lane_total(lanes_h)};
}

// third_difference_loop, storing the h_k unless `h` is null.
INERTEST_VECTOR_CLONES
ThirdDifferenceSquares third_difference_squares(const double* __restrict p0, const double* __restrict p1,
                                                const double* __restrict p2, const double* __restrict p3,
                                                std::size_t length, double* __restrict h) {
  if (h == nullptr) return third_difference_loop<false>(p0, p1, p2, p3, length, h);
  return third_difference_loop<true>(p0, p1, p2, p3, length, h);
}

}  // namespace

std::string_view estimator_name(Estimator estimator) {
  switch (estimator) {
    case Estimator::kAdev: return "adev";
    case Estimator::kOadev: return "oadev";
    case Estimator::kMdev: return "mdev";
    case Estimator::kHdev: return "hdev";
    case Estimator::kOhdev: return "ohdev";
    case Estimator::kTotdev: return "totdev";
  }
  return "";
}

Estimator parse_estimator(std::string_view name) {
  for (Estimator e : kAllEstimators) {
    if (estimator_name(e) == name) return e;
  }
  throw Error("unknown estimator '" + std::string(name) + "' (expected adev, oadev, mdev, hdev, ohdev or totdev)");
}

EstimatorSet EstimatorSet::all() {
  EstimatorSet set;
  for (Estimator e : kAllEstimators) set.insert(e);
  return set;
}

EstimatorSet EstimatorSet::parse(std::string_view text) {
  if (text == "all") return all();
  EstimatorSet set;
  while (true) {
    const std::size_t comma = text.find(',');
    set.insert(parse_estimator(text.substr(0, comma)));
    if (comma == std::string_view::npos) break;
    text = text.substr(comma + 1);
  }
  return set;
}

std::vector<Estimator> EstimatorSet::members() const {
  std::vector<Estimator> list;
  for (Estimator e : kAllEstimators) {
    if (contains(e)) list.push_back(e);
  }
  return list;
}

bool EstimatorSet::needs_third_differences() const {
  return contains(Estimator::kMdev) || contains(Estimator::kHdev) || contains(Estimator::kOhdev);
}

std::size_t largest_averaging_factor(std::size_t sample_count, const EstimatorSet& estimators) {
  return estimators.needs_third_differences() ? sample_count / 3 : sample_count / 2;
}

double AllanSums::variance(Estimator e) const {
  const double m = static_cast<double>(averaging_factor);
  const double n = static_cast<double>(terms(e));
  switch (e) {
    case Estimator::kAdev:
    case Estimator::kOadev:
    case Estimator::kTotdev: return sum(e) / (2.0 * m * m * n);
    case Estimator::kHdev:
    case Estimator::kOhdev: return sum(e) / (6.0 * m * m * n);
    case Estimator::kMdev: return sum(e) / (2.0 * m * m * m * m * n);
  }
  return 0.0;
}

struct AllanEngine::State {
  enum class JobKind { kBlock, kEnds };
  struct Job {
    JobKind kind = JobKind::kBlock;
    std::size_t begin = 0;  // phase indices [begin, end)
    std::size_t end = 0;
  };
  // The phase X_j = sum + compensation at phase index j (the Neumaier state after it).
  struct Checkpoint {
    std::size_t index = 0;
    double sum = 0.0;
    double compensation = 0.0;
  };

  std::size_t sample_count = 0;
  double offset = 0.0;
  AllanEngineOptions options;
  bool third = false;  // third differences needed (MDEV, HDEV, OHDEV)
  bool mdev = false;
  bool adev = false;
  bool hdev = false;
  bool totdev = false;

  std::size_t capacity = 0;
  PhaseBuffer ring;
  std::size_t written = 0;     // phase values written: X_0 .. X_{written-1}
  std::size_t dispatched = 0;  // phase indices below this were handed to the workers
  double phase_sum = 0.0;      // Neumaier running sum of (y - offset): X = phase_sum + phase_compensation
  double phase_compensation = 0.0;
  std::vector<Checkpoint> checkpoints;  // one per block, for the second pass

  std::vector<FactorState> factors;   // done in the streaming pass, from the ring
  std::vector<FactorState> deferred;  // their span exceeds the ring: done in the second pass
  std::vector<std::vector<double>> scratch;  // per worker, block_size values of h_k

  std::vector<std::thread> workers;
  std::mutex mutex;
  std::condition_variable start;
  std::condition_variable done;
  std::size_t generation = 0;
  std::size_t pending = 0;
  bool stopping = false;
  Job job;

  std::size_t span_of(std::size_t m) const { return (third ? 3 : 2) * m; }

  void write_phase(double value) {
    ring.data()[written % capacity] = value;
    ++written;
  }

  void run(const Job& work, std::size_t worker) {
    const PhaseStore store(ring.data(), capacity);
    for (std::size_t i = worker; i < factors.size(); i += options.worker_count) {
      if (work.kind == JobKind::kBlock) {
        process_block(factors[i], work.begin, work.end, store, scratch[worker]);
      } else {
        process_end(factors[i], sample_count + 1 - factors[i].m, sample_count, store);
      }
    }
  }

  // Terms anchored at phase indices k in [k0, k1): every term whose largest phase index is k.
  void process_block(FactorState& f, std::size_t k0, std::size_t k1, const PhaseStore& store,
                     std::vector<double>& h_buffer) {
    const std::size_t m = f.m;
    if (totdev) {
      // NIST SP 1065 eq. (25), centres c = k - m in [1, m-1]: X*_{c-m} = 2X_0 - X_{2m-k}, X_0 = 0.
      const std::size_t lo = std::max(k0, m + 1);
      const std::size_t hi = std::min(k1, 2 * m);
      if (lo < hi) {
        double total = 0.0;
        for_each_run<3>(store, {lagged(0), lagged(m), mirrored(2 * m)}, lo, hi, 1, [&](const auto& p, std::size_t n) {
          double lanes[kLanes] = {};
          for (std::size_t i = 0; i < n; ++i) {
            const double term = -p[2][-static_cast<std::ptrdiff_t>(i)] - 2.0 * p[1][i] + p[0][i];
            lanes[i % kLanes] += term * term;
          }
          total += lane_total(lanes);
        });
        f.reflected.add(total);
      }
    }
    if (third) {
      // Region 2m <= k < 3m: second differences only; the first MDEV window fills up.
      const std::size_t lo = std::max(k0, 2 * m);
      const std::size_t hi = std::min(k1, 3 * m);
      if (lo < hi) {
        double total = 0.0;
        for_each_run<3>(store, {lagged(0), lagged(m), lagged(2 * m)}, lo, hi, 1, [&](const auto& p, std::size_t n) {
          double lanes[kLanes] = {};
          for (std::size_t i = 0; i < n; ++i) {
            const double a = p[0][i] - 2.0 * p[1][i] + p[2][i];
            lanes[i % kLanes] += a * a;
            f.window += a;
          }
          total += lane_total(lanes);
        });
        f.sums[index_of(Estimator::kOadev)].add(total);
        if (hi == 3 * m) f.sums[index_of(Estimator::kMdev)].add(f.window * f.window);  // w_{3m-1}
      }
      sweep_third(f, std::max(k0, 3 * m), k1, store, h_buffer);
    } else {
      sweep_second(f, std::max(k0, 2 * m), k1, store);
    }
    if (adev) strided(f, Estimator::kAdev, 2 * m, k0, k1, store);
    if (hdev) strided(f, Estimator::kHdev, 3 * m, k0, k1, store);
    average(f, k0, k1, store);
    if (f.overlapping_averages) overlapping_average(f, k0, k1, store);
  }

  // d_k = X_k - X_{k-m} at every anchor k in [max(k0, m), k1): m times the overlapping averages.
  void overlapping_average(FactorState& f, std::size_t k0, std::size_t k1, const PhaseStore& store) {
    const std::size_t m = f.m;
    for_each_run<2>(store, {lagged(0), lagged(m)}, std::max(k0, m), k1, 1, [&](const auto& p, std::size_t n) {
      double sums[kLanes] = {};
      double squares[kLanes] = {};
      for (std::size_t i = 0; i < n; ++i) {
        const double d = p[0][i] - p[1][i];
        sums[i % kLanes] += d;
        squares[i % kLanes] += d * d;
      }
      f.overlapping_sum.add(lane_total(sums));
      f.overlapping_squares.add(lane_total(squares));
    });
  }

  // The averages ȳ_j = (X_{jm} - X_{(j-1)m}) / m at the anchors k = jm in [k0, k1), 1 <= j <=
  // AveragedFrequencySeries::kMaximumAverages (its bounded prefix).
  void average(FactorState& f, std::size_t k0, std::size_t k1, const PhaseStore& store) {
    const std::size_t m = f.m;
    const std::size_t k = (std::max(k0, m) + m - 1) / m * m;
    k1 = std::min(k1, AveragedFrequencySeries::kMaximumAverages * m + 1);
    if (k >= k1) return;
    const double inverse = 1.0 / static_cast<double>(m);
    for_each_run<2>(store, {lagged(0), lagged(m)}, k, k1, m, [&](const auto& p, std::size_t n) {
      for (std::size_t i = 0; i < n; ++i) f.averages.add((p[0][i * m] - p[1][i * m]) * inverse);
    });
  }

  // OADEV (and TOTDEV interior) terms a_k for k >= 2m when no third differences are needed.
  void sweep_second(FactorState& f, std::size_t k0, std::size_t k1, const PhaseStore& store) {
    if (k0 >= k1) return;
    const std::size_t m = f.m;
    for_each_run<3>(store, {lagged(0), lagged(m), lagged(2 * m)}, k0, k1, 1, [&](const auto& p, std::size_t length) {
      f.sums[index_of(Estimator::kOadev)].add(second_difference_squares(p[0], p[1], p[2], length));
    });
  }

  // k >= 3m: a_k (OADEV), h_k = a_k - a_{k-m} (OHDEV), w_k = w_{k-1} + h_k (MDEV).
  void sweep_third(FactorState& f, std::size_t k0, std::size_t k1, const PhaseStore& store,
                   std::vector<double>& h_buffer) {
    if (k0 >= k1) return;
    const std::size_t m = f.m;
    std::size_t k = k0;
    while (k < k1) {
      // Runs of at most the scratch length (the second pass has longer windows than a block).
      const std::size_t piece_end = std::min(k1, k + h_buffer.size());
      for_each_run<4>(store, {lagged(0), lagged(m), lagged(2 * m), lagged(3 * m)}, k, piece_end, 1,
                      [&](const auto& p, std::size_t length) {
                        if (mdev) {
                          third_run<true>(f, p, length, h_buffer.data());
                        } else {
                          third_run<false>(f, p, length, h_buffer.data());
                        }
                      });
      k = piece_end;
    }
  }

  // Without MDEV the h_k are not stored: one stream less through the cache.
  template <bool kWithMdev>
  void third_run(FactorState& f, const std::array<const double*, 4>& p, std::size_t length, double* h) {
    const ThirdDifferenceSquares squares = third_difference_squares(p[0], p[1], p[2], p[3], length, kWithMdev ? h : nullptr);
    f.sums[index_of(Estimator::kOadev)].add(squares.second);
    f.sums[index_of(Estimator::kOhdev)].add(squares.third);
    if constexpr (kWithMdev) f.sums[index_of(Estimator::kMdev)].add(mdev_window_squares(h, length, f.window));
  }

  // ADEV (second differences) or HDEV (third differences) at k = first, first + m, ... (multiples of m).
  void strided(FactorState& f, Estimator estimator, std::size_t first_anchor, std::size_t k0, std::size_t k1,
               const PhaseStore& store) {
    const std::size_t m = f.m;
    std::size_t k = std::max(k0, first_anchor);
    k = (k + m - 1) / m * m;
    if (k >= k1) return;
    double total = 0.0;
    if (estimator == Estimator::kAdev) {
      for_each_run<3>(store, {lagged(0), lagged(m), lagged(2 * m)}, k, k1, m, [&](const auto& p, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) {
          const double a = p[0][i * m] - 2.0 * p[1][i * m] + p[2][i * m];
          total += a * a;
        }
      });
    } else {
      for_each_run<4>(store, {lagged(0), lagged(m), lagged(2 * m), lagged(3 * m)}, k, k1, m,
                      [&](const auto& p, std::size_t n) {
                        for (std::size_t i = 0; i < n; ++i) {
                          const double hk = p[0][i * m] - 3.0 * p[1][i * m] + 3.0 * p[2][i * m] - p[3][i * m];
                          total += hk * hk;
                        }
                      });
    }
    f.sums[index_of(estimator)].add(total);
  }

  // TOTDEV centres c in [c0, c1) within [N-m+1, N-1]: X*_{c+m} = 2X_N - X_{2N-c-m} (NIST SP 1065 eq. 25).
  void process_end(FactorState& f, std::size_t c0, std::size_t c1, const PhaseStore& store) {
    if (!totdev) return;
    const std::size_t n = sample_count;
    const std::size_t m = f.m;
    if (m < 2 || c0 >= c1) return;
    const double twice_last = 2.0 * store.at(n);
    double total = 0.0;
    for_each_run<3>(store, {lagged(m), lagged(0), mirrored(2 * n - m)}, c0, c1, 1, [&](const auto& p, std::size_t len) {
      double lanes[kLanes] = {};
      for (std::size_t i = 0; i < len; ++i) {
        const double term = p[0][i] - 2.0 * p[1][i] + twice_last - p[2][-static_cast<std::ptrdiff_t>(i)];
        lanes[i % kLanes] += term * term;
      }
      total += lane_total(lanes);
    });
    f.reflected.add(total);
  }

  // Fills each window with X_j, j in [start, start + size), integrating the samples again from the
  // checkpoint at or before its start with the very operations of push(): the same values.
  void fill_windows(std::span<PhaseStore::Window> windows, const SampleReader& reader,
                    std::vector<double>& samples) const {
    for (PhaseStore::Window& w : windows) {
      auto checkpoint = std::upper_bound(checkpoints.begin(), checkpoints.end(), w.start,
                                         [](std::size_t index, const Checkpoint& c) { return index < c.index; });
      --checkpoint;
      double sum = checkpoint->sum;
      double compensation = checkpoint->compensation;
      std::size_t index = checkpoint->index;  // X_index = sum + compensation
      std::size_t filled = 0;
      if (index == w.start) w.values[filled++] = sum + compensation;
      const std::size_t last = w.start + w.values.size() - 1;
      while (index < last) {
        // Samples index .. give X_{index+1} ..
        const std::size_t count = std::min(samples.size(), last - index);
        reader(index, std::span<double>(samples.data(), count));
        for (std::size_t j = 0; j < count; ++j) {
          const double y = samples[j] - offset;
          const double t = sum + y;
          compensation += std::abs(sum) >= std::abs(y) ? (sum - t) + y : (y - t) + sum;
          sum = t;
          ++index;
          if (index >= w.start) w.values[filled++] = sum + compensation;
        }
      }
    }
  }

  // The second pass: each deferred factor in segments of anchors, from windows of the phase
  // re-read around k, k - m, k - 2m, k - 3m (and the mirrored indices of TOTDEV).
  void run_deferred(const SampleReader& reader) {
    if (deferred.empty()) return;
    if (!reader) throw Error("internal: the Allan engine needs a second pass over the record and has no reader");
    const std::size_t n = sample_count;
    ring.reset(0);  // the windows take its place
    const std::size_t segment = std::max<std::size_t>(options.block_size, capacity / 6);
    std::vector<double> samples(std::min<std::size_t>(segment, 1u << 16));
    std::vector<double> h_buffer(options.block_size);
    // The windows of one segment are windows[0, used): their buffers are kept from segment to
    // segment (segments are up to a sixth of the ring each: allocating them afresh would have the
    // kernel map and zero gigabytes per segment of a 10^9-sample record).
    std::vector<PhaseStore::Window> windows;
    std::size_t used = 0;
    const auto add_window = [&](std::size_t first, std::size_t end) {  // [first, end) clipped to [0, N]
      end = std::min(end, n + 1);
      if (first >= end) return;
      if (used == windows.size()) windows.emplace_back();
      PhaseStore::Window& w = windows[used++];
      w.start = first;
      w.values.resize(end - first);
    };
    const auto segment_windows = [&] { return std::span<PhaseStore::Window>(windows.data(), used); };
    for (FactorState& f : deferred) {
      const std::size_t m = f.m;
      for (std::size_t ka = m; ka <= n; ka += segment) {  // the first average is anchored at k = m
        const std::size_t kb = std::min(n + 1, ka + segment);
        used = 0;
        for (std::size_t s = 0; s <= (third ? 3u : 2u); ++s) {
          const std::size_t lag = s * m;
          if (kb > lag) add_window(ka > lag ? ka - lag : 0, kb - lag);
        }
        if (totdev && ka < 2 * m) add_window(2 * m - std::min(kb, 2 * m) + 1, 2 * m - ka + 1);
        fill_windows(segment_windows(), reader, samples);
        process_block(f, ka, kb, PhaseStore(segment_windows()), h_buffer);
      }
      if (totdev && m >= 2) {
        for (std::size_t ca = n + 1 - m; ca < n; ca += segment) {
          const std::size_t cb = std::min(n, ca + segment);
          used = 0;
          add_window(ca - m, cb - m);
          add_window(ca, cb);
          add_window(2 * n - m - cb + 1, 2 * n - m - ca + 1);
          add_window(n, n + 1);
          fill_windows(segment_windows(), reader, samples);
          process_end(f, ca, cb, PhaseStore(segment_windows()));
        }
      }
    }
  }

  void worker_loop(std::size_t worker) {
    std::size_t seen = 0;
    while (true) {
      Job work;
      {
        std::unique_lock lock(mutex);
        start.wait(lock, [&] { return stopping || generation != seen; });
        if (stopping) return;
        seen = generation;
        work = job;
      }
      run(work, worker);
      {
        std::lock_guard lock(mutex);
        --pending;
      }
      done.notify_one();
    }
  }

  void wait_idle() {
    if (workers.empty()) return;
    std::unique_lock lock(mutex);
    done.wait(lock, [&] { return pending == 0; });
  }

  void dispatch(const Job& work) {
    wait_idle();
    if (workers.empty()) {
      run(work, 0);
      return;
    }
    {
      std::lock_guard lock(mutex);
      job = work;
      pending = workers.size();
      ++generation;
    }
    start.notify_all();
  }
};

AllanEngine::AllanEngine(std::size_t sample_count, double offset, AllanEngineOptions options)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  if (options.estimators.empty()) throw Error("no estimator selected");
  if (options.block_size == 0) throw Error("the block size must be positive");
  const std::size_t largest = largest_averaging_factor(sample_count, options.estimators);
  for (std::size_t m : options.averaging_factors) {
    if (m == 0 || m > largest) {
      throw Error("averaging factor " + std::to_string(m) + " is not supported by " + std::to_string(sample_count) +
                  " samples (largest " + std::to_string(largest) + ")");
    }
  }
  if (!std::is_sorted(options.averaging_factors.begin(), options.averaging_factors.end())) {
    throw Error("averaging factors must be sorted");
  }
  s.sample_count = sample_count;
  s.offset = offset;
  s.third = options.estimators.needs_third_differences();
  s.mdev = options.estimators.contains(Estimator::kMdev);
  s.adev = options.estimators.contains(Estimator::kAdev);
  s.hdev = options.estimators.contains(Estimator::kHdev);
  s.totdev = options.estimators.contains(Estimator::kTotdev);
  // While workers read X_{k0 - span} .. X_{k1 - 1}, the caller writes up to X_{k1 + block - 1}:
  // span + 2 blocks of capacity keep the two apart. A record shorter than that is held whole.
  // Factors whose span does not fit the ring limit go to the second pass.
  const std::size_t limit = options.ring_capacity_limit == 0 ? sample_count + 1 : options.ring_capacity_limit;
  std::size_t ring_span = 0;
  for (std::size_t m : options.averaging_factors) {
    FactorState f;
    f.m = m;
    f.overlapping_averages = sample_count / m < kLag1MinimumAverages;
    const std::size_t needed = std::min(sample_count + 1, s.span_of(m) + 2 * options.block_size);
    if (needed <= limit || m == options.averaging_factors.front()) {
      ring_span = std::max(ring_span, s.span_of(m));
      s.factors.push_back(f);
    } else {
      s.deferred.push_back(f);
    }
  }
  s.capacity = std::min(sample_count + 1, ring_span + 2 * options.block_size);
  s.ring.reset(s.capacity);
  options.worker_count = std::max<std::size_t>(1, std::min(options.worker_count, s.factors.size()));
  s.scratch.assign(options.worker_count, std::vector<double>(options.block_size));
  s.options = std::move(options);
  s.write_phase(0.0);  // X_0 = 0
  s.checkpoints.push_back({0, 0.0, 0.0});
  if (s.options.worker_count > 1) {
    for (std::size_t w = 0; w < s.options.worker_count; ++w) {
      s.workers.emplace_back([&s, w] { s.worker_loop(w); });
    }
  }
}

AllanEngine::~AllanEngine() {
  State& s = *state_;
  {
    std::lock_guard lock(s.mutex);
    s.stopping = true;
  }
  s.start.notify_all();
  for (std::thread& worker : s.workers) worker.join();
}

void AllanEngine::push(std::span<const double> samples) {
  State& s = *state_;
  if (s.written - 1 + samples.size() > s.sample_count) {
    throw Error("more samples than the " + std::to_string(s.sample_count) + " announced");
  }
  const std::size_t block = s.options.block_size;
  std::size_t i = 0;
  while (i < samples.size()) {
    // The piece ends at the block's end, the samples' end or the ring's end, whichever is first.
    const std::size_t slot = s.written % s.capacity;
    const std::size_t room = std::min(s.dispatched + block - s.written, s.capacity - slot);
    const std::size_t piece = std::min(room, samples.size() - i);
    double sum = s.phase_sum;
    double compensation = s.phase_compensation;
    double* phase = s.ring.data() + slot;
    for (std::size_t j = 0; j < piece; ++j) {
      // Neumaier summation of the mean-removed rate: the phase keeps full precision over 1e9 samples.
      const double y = samples[i + j] - s.offset;
      const double t = sum + y;
      compensation += std::abs(sum) >= std::abs(y) ? (sum - t) + y : (y - t) + sum;
      sum = t;
      phase[j] = sum + compensation;
    }
    s.written += piece;
    s.phase_sum = sum;
    s.phase_compensation = compensation;
    i += piece;
    if (s.written - s.dispatched == block) {
      if (!s.deferred.empty()) s.checkpoints.push_back({s.written - 1, sum, compensation});
      s.dispatch({State::JobKind::kBlock, s.dispatched, s.written});
      s.dispatched = s.written;
    }
  }
}

std::vector<AllanSums> AllanEngine::finish(const SampleReader& reader) {
  State& s = *state_;
  if (s.written != s.sample_count + 1) {
    throw Error("only " + std::to_string(s.written - 1) + " of " + std::to_string(s.sample_count) +
                " samples were pushed");
  }
  if (s.dispatched < s.written) {
    s.dispatch({State::JobKind::kBlock, s.dispatched, s.written});
    s.dispatched = s.written;
  }
  s.dispatch({State::JobKind::kEnds, 0, 0});
  s.wait_idle();
  s.run_deferred(reader);
  std::vector<FactorState> all = std::move(s.factors);
  all.insert(all.end(), s.deferred.begin(), s.deferred.end());
  std::sort(all.begin(), all.end(), [](const FactorState& a, const FactorState& b) { return a.m < b.m; });
  const std::size_t n = s.sample_count;
  std::vector<AllanSums> result;
  for (FactorState& f : all) {
    AllanSums sums;
    const std::size_t m = f.m;
    sums.averaging_factor = m;
    sums.averages = f.averages;
    if (f.overlapping_averages) {
      // Sample variance of the d_k / m; the record's mean is removed, so the d_k are centred near 0
      // and the two sums do not cancel.
      const auto count = static_cast<double>(n + 1 - m);
      const double total = f.overlapping_sum.value();
      sums.overlapping_average_variance = (f.overlapping_squares.value() - total * total / count) /
                                          ((count - 1.0) * static_cast<double>(m) * static_cast<double>(m));
    }
    sums.term_count[index_of(Estimator::kOadev)] = n + 1 - 2 * m;
    sums.sum_of_squares[index_of(Estimator::kOadev)] = f.sums[index_of(Estimator::kOadev)].value();
    for (Estimator e : s.options.estimators.members()) {
      const std::size_t i = index_of(e);
      switch (e) {
        case Estimator::kAdev: sums.term_count[i] = n / m - 1; break;
        case Estimator::kOadev: sums.term_count[i] = n + 1 - 2 * m; break;
        case Estimator::kMdev: sums.term_count[i] = n + 2 - 3 * m; break;
        case Estimator::kHdev: sums.term_count[i] = n / m - 2; break;
        case Estimator::kOhdev: sums.term_count[i] = n + 1 - 3 * m; break;
        case Estimator::kTotdev: sums.term_count[i] = n - 1; break;
      }
      if (e == Estimator::kTotdev) {
        CompensatedSum total = f.sums[index_of(Estimator::kOadev)];
        total.merge(f.reflected);
        sums.sum_of_squares[i] = total.value();
      } else {
        sums.sum_of_squares[i] = f.sums[i].value();
      }
    }
    result.push_back(sums);
  }
  return result;
}

std::size_t AllanEngine::ring_bytes() const { return state_->capacity * sizeof(double); }

std::size_t AllanEngine::deferred_factor_count() const { return state_->deferred.size(); }

}  // namespace inertest
