#include "inertest/allan/allan_engine.h"

#include <algorithm>
#include <atomic>
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
// fault a page every 512 samples. A thread of its own faults the pages in (MADV_POPULATE_WRITE), a
// huge page at a time from the first, as the reader goes on to fill them: the kernel clears every
// new page, and where a VM's host backs freed memory lazily that clearing runs at about 0.5 GB/s,
// on the reader's path. 3e7 f64 samples, 134 MB of ring, memory left idle 3 s before each run:
// OADEV 0.42 -> 0.35 and 0.43 -> 0.36 s on average in two series; all six and runs back to back
// (the freed pages still warm) unchanged within the noise.
class PhaseBuffer {
 public:
  static constexpr std::size_t kHugePage = std::size_t{2} << 20;

  // Allocates room for `count` values; prefault() then faults it in.
  void reset(std::size_t count) {
    if (prefault_.joinable()) prefault_.join();  // before its pages go
    const std::size_t bytes = (count * sizeof(double) + kHugePage - 1) / kHugePage * kHugePage;
    data_.reset(bytes == 0 ? nullptr : static_cast<double*>(std::aligned_alloc(kHugePage, bytes)));
    if (bytes != 0 && !data_) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (bytes != 0) madvise(data_.get(), bytes, MADV_HUGEPAGE);  // advice only: no huge pages is fine
#endif
    bytes_ = bytes;
  }
  // Starts faulting the pages in. Last in the engine's set-up: while the thread faults, a mapping
  // call of any other thread of the process (a thread's stack, a large allocation) waits for the
  // address space's lock behind it; started before the workers, it held the reader up 0.1 s.
  void prefault() {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
    if (bytes_ > kHugePage) {  // advice only too: a page it has not reached faults as usual
      prefault_ = std::thread([base = reinterpret_cast<char*>(data_.get()), bytes = bytes_] {
        for (std::size_t at = 0; at < bytes; at += kHugePage) madvise(base + at, kHugePage, MADV_POPULATE_WRITE);
      });
    }
#endif
  }
  ~PhaseBuffer() {
    if (prefault_.joinable()) prefault_.join();
  }
  double* data() { return data_.get(); }
  const double* data() const { return data_.get(); }

 private:
  struct Free {
    void operator()(double* p) const { std::free(p); }
  };
  std::unique_ptr<double[], Free> data_;
  std::size_t bytes_ = 0;
  std::thread prefault_;
};

// Where the phase values X_j live: the ring of the streaming pass (X_j at slot j mod capacity), the
// samples' own memory of an engine working in place (X_j, j >= 1, where sample j was; X_0 = 0 apart)
// or, for the factors of the second pass, a few windows [start, start + values.size()) of the phase.
class PhaseStore {
 public:
  struct Window {
    std::size_t start = 0;
    std::vector<double> values;
  };

  PhaseStore(const double* ring, std::size_t capacity) : ring_(ring), capacity_(capacity) {}
  static PhaseStore in_place(const double* samples, std::size_t sample_count) {
    PhaseStore store(samples, sample_count + 1);
    store.in_place_ = true;
    return store;
  }
  explicit PhaseStore(std::span<const Window> windows) : windows_(windows), windowed_(true) {}

  // A pointer to X_index; `forward` values X_index, X_index+1, ... and `backward` values X_index,
  // X_index-1, ... are contiguous from it.
  const double* locate(std::size_t index, std::size_t& forward, std::size_t& backward) const {
    if (in_place_) {
      static constexpr double kOrigin = 0.0;  // X_0
      if (index == 0) {
        forward = backward = 1;
        return &kOrigin;
      }
      forward = capacity_ - index;
      backward = index;
      return ring_ + index - 1;
    }
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
  bool in_place_ = false;
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
  double overlapping_shift = 0.0;  // d_m = X_m: the sums are of d_k - shift (so they do not cancel, whatever the offset)
  CompensatedSum overlapping_sum;
  CompensatedSum overlapping_squares;
};

// The engine's inner loops (marked INERTEST_VECTOR_CLONES) are compiled for the baseline x86-64,
// for x86-64-v3 (AVX2 + FMA) and for x86-64-v4 (AVX-512), and the loader picks the widest the CPU
// runs (GCC function multi-versioning; other compilers build the baseline only). The wider
// registers carry the same kLanes lanes and the same operations in the same order. Nothing is
// contracted behind the code's back (the library builds with -ffp-contract=off): the loops call
// fused_multiply_add where they mean one, which is an instruction in the v3 and v4 clones and
// glibc's correctly rounded fma() in the baseline one, so the sums are bit for bit those of the
// baseline build.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define INERTEST_X86_64_VERSIONS 1  // GCC builds x86-64 functions for several targets
#define INERTEST_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define INERTEST_VECTOR_CLONES
#endif

// x * y + z rounded once (IEEE 754 fusedMultiplyAdd). A term's square added to its lane, and the
// doubled middle value of a second difference, cost an add less each: the loops on phase in L1/L2
// are bound by the FP adds (two pipes; multiplies and FMAs have two more), and OADEV at a small
// factor went from 0.28 to 0.12 ns an anchor with them (a 3-stream kernel measured on its own).
// Other compilers build the baseline only, without clones: there it is fused only where the target
// has the instruction (fma() is a call per term: the sanitizer build, Clang's, ran its two test
// shards in 230 and 191 s with it, 157 and 149 s before), so their sums may differ from GCC's in
// the last bits, as their other roundings may.
[[gnu::always_inline]] inline double fused_multiply_add(double x, double y, double z) {
#if defined(__clang__) && !defined(__FMA__)
  return x * y + z;
#else
  return __builtin_fma(x, y, z);
#endif
}

// x0 - 2 x1 + x2, the second difference of three phase values (NIST SP 1065 eq. 11's a_k), as
// (x0 + x2) - 2 x1 with the product and the subtraction rounded once: an error of the order of an
// ulp of the phase, as the unfused form.
[[gnu::always_inline]] inline double second_difference(double x0, double x1, double x2) {
  return fused_multiply_add(-2.0, x1, x0 + x2);
}

// Independent partial sums per loop: four AVX2 accumulators, so that the loop runs at the rate of
// its loads instead of one FP-add latency per vector (a single accumulator held a factor to about
// one term per cycle). The partial sums are added pairwise, which is also the more accurate order.
constexpr std::size_t kLanes = 16;

// Lanes[l]: the sum of the terms at i = l (mod kLanes) of a run, i counted from its start.
using Lanes = std::array<double, kLanes>;

double lane_total(const double (&lanes)[kLanes]) {
  double level[kLanes];
  std::copy(std::begin(lanes), std::end(lanes), level);
  for (std::size_t width = kLanes / 2; width > 0; width /= 2) {
    for (std::size_t l = 0; l < width; ++l) level[l] = level[2 * l] + level[2 * l + 1];
  }
  return level[0];
}

double lane_total(const Lanes& lanes) {
  double level[kLanes];
  std::copy(lanes.begin(), lanes.end(), level);
  return lane_total(level);
}

// The terms at i = r (mod m) of a run, m dividing kLanes: the lanes r, r + m, ...
double strided_lane_total(const Lanes& lanes, std::size_t r, std::size_t m) {
  double total = 0.0;
  for (std::size_t l = r; l < kLanes; l += m) total += lanes[l];
  return total;
}

Lanes to_lanes(const double (&lanes)[kLanes]) {
  Lanes out;
  std::copy(std::begin(lanes), std::end(lanes), out.begin());
  return out;
}

// Four doubles in a register where the target has 256-bit ones (GCC/Clang vector extension;
// element-wise operations are exactly those of four scalars).
using Quad = double __attribute__((vector_size(4 * sizeof(double))));

// Four values each of four sequences, r_c holding values i .. i+3 of sequence c, to t_j = value i + j
// of every sequence (a 4x4 transpose; applied twice, the identity).
[[gnu::always_inline]] inline void transpose(Quad& r0, Quad& r1, Quad& r2, Quad& r3) {
  const Quad lo01 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6);
  const Quad hi01 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
  const Quad lo23 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6);
  const Quad hi23 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
  r0 = __builtin_shufflevector(lo01, lo23, 0, 1, 4, 5);
  r1 = __builtin_shufflevector(hi01, hi23, 0, 1, 4, 5);
  r2 = __builtin_shufflevector(lo01, lo23, 2, 3, 6, 7);
  r3 = __builtin_shufflevector(hi01, hi23, 2, 3, 6, 7);
}

// Four values each of four sequences, sequence c from row + c * stride, to t[j] = value j of every
// sequence: four rows loaded whole and transposed, eight shuffles.
struct ShuffledLoad {
  [[gnu::always_inline]] static inline void load(const double* row, std::size_t stride, Quad (&t)[4]) {
    for (std::size_t c = 0; c < 4; ++c) std::memcpy(&t[c], row + c * stride, sizeof t[c]);
    transpose(t[0], t[1], t[2], t[3]);
  }
};

#ifdef INERTEST_X86_64_VERSIONS
// The same values for the AVX targets with four shuffles: each register is loaded as two pairs,
// the second inserted from memory (vinsertf128 with a memory operand runs on any vector ALU port),
// and four unpacks finish the transpose. The shuffle port bound the MDEV window at half a shuffle a
// term. GCC does not fold a load into the insert (it inserts from a register, on the shuffle port),
// hence the asm.
struct InsertedLoad {
  using Pair = double __attribute__((vector_size(2 * sizeof(double))));
  // out = lo[0], lo[1], hi[0], hi[1].
  [[gnu::always_inline]] static inline void pairs(const double* lo, const double* hi, Quad& out) {
    Pair low;
    std::memcpy(&low, lo, sizeof low);
    asm("vinsertf128 $1, %2, %t1, %t0" : "=x"(out) : "x"(low), "m"(*reinterpret_cast<const double(*)[2]>(hi)));
  }
  [[gnu::always_inline]] static inline void load(const double* row, std::size_t stride, Quad (&t)[4]) {
    for (std::size_t j = 0; j < 2; ++j) {
      Quad even;  // values 2j, 2j + 1 of sequences 0 and 2
      Quad odd;   // and of sequences 1 and 3
      pairs(row + 2 * j, row + 2 * stride + 2 * j, even);
      pairs(row + stride + 2 * j, row + 3 * stride + 2 * j, odd);
      t[2 * j] = __builtin_shufflevector(even, odd, 0, 4, 2, 6);
      t[2 * j + 1] = __builtin_shufflevector(even, odd, 1, 5, 3, 7);
    }
  }
};
#endif

// Chains of the MDEV window recurrence run side by side, four to a Quad (kChains add latencies
// overlap: four chains a Quad were held to an add latency per four terms).
constexpr std::size_t kChainQuads = 4;
constexpr std::size_t kChains = 4 * kChainQuads;

// The MDEV window over a run: w_k = w_{k-1} + h_k for k in the run, returns sum w_k^2 and leaves
// the last w in `window`. The recurrence is a chain of dependent additions (one FP-add latency per
// term), so the run is cut into kChains chunks of n values, a chain to a lane: four values of four
// chains are loaded and transposed, and each lane adds its chain's next h to its local window l_k
// (the sum of the chunk's h up to k, from 0), and sums l_k and l_k^2. A chunk that starts after the
// window s (the last w before it) then adds
//   sum (s + l_k)^2 = s (n s + 2 sum l_k) + sum l_k^2,
// and passes s + l_{last} on. Starting each chain from s instead needs the chunk sums first, a pass
// over h that cost as much as the chains (0.215 -> 0.145 ns a term without it, one run in L2).
// The rounding error is a few ulp of n s^2 + sum l_k^2 <= 3 n s^2 + 2 sum w_k^2, and s^2 is the
// square of the window before the chunk, itself a term of the sum: relative to the whole sum,
// at most about 5 n ulp (n <= 2048 here: 1e-12), far inside the 1e-9 the estimators are held to.
template <typename TransposedLoad>
[[gnu::always_inline]] inline double mdev_window_loop(const double* __restrict h, std::size_t length, double& window) {
  constexpr std::size_t kMinimumChunk = 64;
  // Chains a multiple of 4 KiB apart fall in the same sets of a 32 KiB 8-way L1: a chunk 8 values
  // short of a multiple of 512 staggers them by a cache line each.
  const std::size_t whole = length / kChains / 4 * 4;
  const std::size_t chunk = whole % 512 == 0 && whole > 0 ? whole - 8 : whole;
  if (chunk < kMinimumChunk) {
    double total = 0.0;
    double w = window;
    for (std::size_t i = 0; i < length; ++i) {
      w += h[i];
      total = fused_multiply_add(w, w, total);
    }
    window = w;
    return total;
  }
  // Lane l of Quad q: chain 4q + l, over [(4q + l) n, (4q + l + 1) n).
  Quad local[kChainQuads] = {};    // l_k
  Quad sums[kChainQuads] = {};     // sum l_k
  Quad squares[kChainQuads] = {};  // sum l_k^2
  for (std::size_t i = 0; i < chunk; i += 4) {
#pragma GCC unroll 4  // the windows and sums stay in registers
    for (std::size_t q = 0; q < kChainQuads; ++q) {
      Quad t[4];
      TransposedLoad::load(h + 4 * q * chunk + i, chunk, t);
      for (const Quad& next : t) {
        local[q] += next;
        for (std::size_t l = 0; l < 4; ++l) squares[q][l] = fused_multiply_add(local[q][l], local[q][l], squares[q][l]);
        sums[q] += local[q];
      }
    }
  }
  const double n = static_cast<double>(chunk);
  double start = window;
  double total = 0.0;
  for (std::size_t c = 0; c < kChains; ++c) {
    const std::size_t q = c / 4;
    const std::size_t l = c % 4;
    total += fused_multiply_add(start, fused_multiply_add(n, start, 2.0 * sums[q][l]), squares[q][l]);
    start += local[q][l];
  }
  for (std::size_t i = kChains * chunk; i < length; ++i) {  // the remainder, after the last chain
    start += h[i];
    total = fused_multiply_add(start, start, total);
  }
  window = start;
  return total;
}

// The loop compiled for each target as INERTEST_VECTOR_CLONES would, with the AVX targets' load.
// All six estimators on 3e7 samples, octave factors, 8 runs alternated: user time 0.52 -> 0.50 s,
// elapsed median 0.37 -> 0.355 s; the same bits (the same values are summed in the same order).
#ifdef INERTEST_X86_64_VERSIONS
[[gnu::target("default")]] double mdev_window_squares(const double* __restrict h, std::size_t length, double& window) {
  return mdev_window_loop<ShuffledLoad>(h, length, window);
}
[[gnu::target("arch=x86-64-v3")]] double mdev_window_squares(const double* __restrict h, std::size_t length,
                                                             double& window) {
  return mdev_window_loop<InsertedLoad>(h, length, window);
}
[[gnu::target("arch=x86-64-v4")]] double mdev_window_squares(const double* __restrict h, std::size_t length,
                                                             double& window) {
  return mdev_window_loop<InsertedLoad>(h, length, window);
}
#else
double mdev_window_squares(const double* __restrict h, std::size_t length, double& window) {
  return mdev_window_loop<ShuffledLoad>(h, length, window);
}
#endif

// The sums of d_k - shift, d_k = X_k - X_{k-m} (m times the overlapping averages), that the B1
// ratio needs for the factors with few non-overlapping averages: summed in the same loop as the
// differences (the streams are already in registers), in kLanes lanes (kAverageLanes alone).
constexpr std::size_t kAverageLanes = 8;

struct AverageSums {
  double sum = 0.0;
  double squares = 0.0;
};

double average_lane_total(const double (&lanes)[kAverageLanes]) {
  return ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) + ((lanes[4] + lanes[5]) + (lanes[6] + lanes[7]));
}

// The lagged streams of a sweep asked of the memory system kPrefetchAhead values (one 4 KiB page)
// before the loop reaches them, two cache lines a step of kLanes values. A worker's far factors
// stream about ten lags from DRAM at once, and the hardware prefetchers stop at each page boundary:
// each page of each stream began with misses. 3e7 f64 samples, octave factors, runs of each
// alternated (medians): OADEV alone 0.236 -> 0.216 s and all six 0.49 -> 0.43 s (4 x 3 runs), 0.250
// -> 0.233 s and 0.564 -> 0.495 s on a busier machine (6 x 3 runs); the factors m <= 2^15 alone, in
// cache, no slower. 128, 256 or 1024 values ahead, or X_k's stream too (just written), no faster.
constexpr std::size_t kPrefetchAhead = 512;

[[gnu::always_inline]] inline void prefetch_ahead(const double* stream) {
  __builtin_prefetch(stream + kPrefetchAhead);
  __builtin_prefetch(stream + kPrefetchAhead + kLanes / 2);
}

struct SecondDifferenceSums {
  Lanes second{};  // sum a_k^2, by lane
  AverageSums averages;
};

// sum a_k^2 over a run, a_k = p0[i] - 2 p1[i] + p2[i] (NIST SP 1065 eq. 11), in kLanes lanes; with
// kAverages also the sums of d_k - shift = p0[i] - p1[i] - shift.
template <bool kAverages>
[[gnu::always_inline]] inline SecondDifferenceSums second_difference_loop(const double* __restrict p0,
                                                                          const double* __restrict p1,
                                                                          const double* __restrict p2,
                                                                          std::size_t length, double shift) {
  double lanes[kLanes] = {};
  double d_sums[kLanes] = {};
  double d_squares[kLanes] = {};
  std::size_t i = 0;
  for (; i + kLanes <= length; i += kLanes) {
    prefetch_ahead(p1 + i);
    prefetch_ahead(p2 + i);
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double a = second_difference(p0[i + l], p1[i + l], p2[i + l]);
      lanes[l] = fused_multiply_add(a, a, lanes[l]);
      if constexpr (kAverages) {
        const double d = (p0[i + l] - p1[i + l]) - shift;
        d_sums[l] += d;
        d_squares[l] = fused_multiply_add(d, d, d_squares[l]);
      }
    }
  }
  for (; i < length; ++i) {  // the last terms in their lanes too (strided_lane_total counts on it)
    const double a = second_difference(p0[i], p1[i], p2[i]);
    lanes[i % kLanes] = fused_multiply_add(a, a, lanes[i % kLanes]);
    if constexpr (kAverages) {
      const double d = (p0[i] - p1[i]) - shift;
      d_sums[0] += d;
      d_squares[0] = fused_multiply_add(d, d, d_squares[0]);
    }
  }
  return {to_lanes(lanes), {lane_total(d_sums), lane_total(d_squares)}};
}

// second_difference_loop, with the average sums when `shift` is not null.
INERTEST_VECTOR_CLONES
SecondDifferenceSums second_difference_sums(const double* __restrict p0, const double* __restrict p1,
                                            const double* __restrict p2, std::size_t length, const double* shift) {
  if (shift == nullptr) return second_difference_loop<false>(p0, p1, p2, length, 0.0);
  return second_difference_loop<true>(p0, p1, p2, length, *shift);
}

// Over the anchors 2m <= k < 3m: sum a_k^2 and (in averages.sum) sum a_k, the first MDEV window.
INERTEST_VECTOR_CLONES
SecondDifferenceSums second_difference_window(const double* __restrict p0, const double* __restrict p1,
                                              const double* __restrict p2, std::size_t length) {
  double lanes[kLanes] = {};
  double window[kLanes] = {};
  std::size_t i = 0;
  for (; i + kLanes <= length; i += kLanes) {
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double a = second_difference(p0[i + l], p1[i + l], p2[i + l]);
      lanes[l] = fused_multiply_add(a, a, lanes[l]);
      window[l] += a;
    }
  }
  for (; i < length; ++i) {
    const double a = second_difference(p0[i], p1[i], p2[i]);
    lanes[i % kLanes] = fused_multiply_add(a, a, lanes[i % kLanes]);
    window[0] += a;
  }
  return {to_lanes(lanes), {lane_total(window), 0.0}};
}

// The sums of d_k - shift alone (the anchors m <= k < 2m, or 3m, before the difference sweeps).
INERTEST_VECTOR_CLONES
AverageSums difference_sums(const double* __restrict p0, const double* __restrict p1, std::size_t length,
                            double shift) {
  double d_sums[kAverageLanes] = {};
  double d_squares[kAverageLanes] = {};
  std::size_t i = 0;
  for (; i + kAverageLanes <= length; i += kAverageLanes) {
    for (std::size_t l = 0; l < kAverageLanes; ++l) {
      const double d = (p0[i + l] - p1[i + l]) - shift;
      d_sums[l] += d;
      d_squares[l] = fused_multiply_add(d, d, d_squares[l]);
    }
  }
  for (; i < length; ++i) {
    const double d = (p0[i] - p1[i]) - shift;
    d_sums[0] += d;
    d_squares[0] = fused_multiply_add(d, d, d_squares[0]);
  }
  return {average_lane_total(d_sums), average_lane_total(d_squares)};
}

struct ThirdDifferenceSquares {
  Lanes second{};  // sum a_k^2, by lane
  Lanes third{};   // sum h_k^2, by lane
  AverageSums averages;
};

// Over a run: a_k = p0 - 2 p1 + p2 and h_k = a_k - (p1 - 2 p2 + p3) = a_k - a_{k-m} (NIST SP 1065
// eqs. 11 and 17); with kStoreH the h_k go to `h` (MDEV needs them, OHDEV alone does not), with
// kAverages the sums of d_k - shift. Inlined into the clones of third_difference_squares, so that
// each is compiled for their targets.
template <bool kStoreH, bool kAverages>
[[gnu::always_inline]] inline ThirdDifferenceSquares third_difference_loop(
    const double* __restrict p0, const double* __restrict p1, const double* __restrict p2,
    const double* __restrict p3, std::size_t length, double* __restrict h, double shift) {
  double lanes_a[kLanes] = {};
  double lanes_h[kLanes] = {};
  double d_sums[kLanes] = {};
  double d_squares[kLanes] = {};
  std::size_t i = 0;
  for (; i + kLanes <= length; i += kLanes) {
    prefetch_ahead(p1 + i);
    prefetch_ahead(p2 + i);
    prefetch_ahead(p3 + i);
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double a = second_difference(p0[i + l], p1[i + l], p2[i + l]);
      const double hk = a - second_difference(p1[i + l], p2[i + l], p3[i + l]);
      if constexpr (kStoreH) h[i + l] = hk;
      lanes_a[l] = fused_multiply_add(a, a, lanes_a[l]);
      lanes_h[l] = fused_multiply_add(hk, hk, lanes_h[l]);
      if constexpr (kAverages) {
        const double d = (p0[i + l] - p1[i + l]) - shift;
        d_sums[l] += d;
        d_squares[l] = fused_multiply_add(d, d, d_squares[l]);
      }
    }
  }
  for (; i < length; ++i) {
    const double a = second_difference(p0[i], p1[i], p2[i]);
    const double hk = a - second_difference(p1[i], p2[i], p3[i]);
    if constexpr (kStoreH) h[i] = hk;
    lanes_a[i % kLanes] = fused_multiply_add(a, a, lanes_a[i % kLanes]);
    lanes_h[i % kLanes] = fused_multiply_add(hk, hk, lanes_h[i % kLanes]);
    if constexpr (kAverages) {
      const double d = (p0[i] - p1[i]) - shift;
      d_sums[0] += d;
      d_squares[0] = fused_multiply_add(d, d, d_squares[0]);
    }
  }
  return {to_lanes(lanes_a), to_lanes(lanes_h), {lane_total(d_sums), lane_total(d_squares)}};
}

// third_difference_loop, storing the h_k unless `h` is null, with the average sums when `shift`
// is not null.
INERTEST_VECTOR_CLONES
ThirdDifferenceSquares third_difference_squares(const double* __restrict p0, const double* __restrict p1,
                                                const double* __restrict p2, const double* __restrict p3,
                                                std::size_t length, double* __restrict h, const double* shift) {
  if (shift == nullptr) {
    if (h == nullptr) return third_difference_loop<false, false>(p0, p1, p2, p3, length, h, 0.0);
    return third_difference_loop<true, false>(p0, p1, p2, p3, length, h, 0.0);
  }
  if (h == nullptr) return third_difference_loop<false, true>(p0, p1, p2, p3, length, h, *shift);
  return third_difference_loop<true, true>(p0, p1, p2, p3, length, h, *shift);
}

// sum term(i)^2 over i < n in four independent partial sums (one chain of dependent additions
// held the strided ADEV/HDEV sums of small factors to an FP-add latency per term). Not a clone: a
// fused_multiply_add here would be a call to fma() per term; a gather of every m-th value is not
// bound by its adds.
template <typename Term>
double strided_squares(std::size_t n, Term&& term) {
  double partial[4] = {};
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    for (std::size_t l = 0; l < 4; ++l) {
      const double t = term(i + l);
      partial[l] += t * t;
    }
  }
  for (; i < n; ++i) {
    const double t = term(i);
    partial[0] += t * t;
  }
  return (partial[0] + partial[1]) + (partial[2] + partial[3]);
}

// The Neumaier state of the running phase: X = sum + compensation.
struct PhaseState {
  double sum = 0.0;
  double compensation = 0.0;
  // Neumaier's step: t = fl(sum + y) and its exact rounding error into the compensation. The
  // error is found by Knuth's TwoSum, without Neumaier's branch on |sum| >= |y| (which chains
  // starting from zero mispredict half the time); both give the exact error, so the same bits.
  void add(double y) {
    const double t = sum + y;
    const double y_part = t - sum;
    compensation += (sum - (t - y_part)) + (y - y_part);
    sum = t;
  }
  double value() const { return sum + compensation; }
};

// Integrates one block of the phase in place: values[j] holds the rate sample y that ends at that
// phase index and becomes X = X_before + sum of (y - offset) up to it (Neumaier summation, so that
// the phase keeps full precision over 1e9 samples). The block is cut into kIntegrationChains
// equal chains, each summed from zero on its own, side by side in the lanes of a vector (the
// single chain cost one FP-add latency per sample); then each chain's values get the state reached
// before it (X = sum + (compensation + local)), and the chains' totals are added to the state in
// order. The cut depends on the block's length only, never on the caller's chunks or the thread
// count: the second pass repeats it on the same blocks and gets the same bits (and each lane does
// the scalar operations of PhaseState::add, in every clone).
constexpr std::size_t kIntegrationChains = 4;

INERTEST_VECTOR_CLONES
void integrate_block(double* __restrict values, std::size_t length, double offset, PhaseState& state) {
  constexpr std::size_t kMinimumChain = 64;
  const std::size_t chain = length / kIntegrationChains / 4 * 4;
  if (chain < kMinimumChain) {
    for (std::size_t j = 0; j < length; ++j) {
      state.add(values[j] - offset);
      values[j] = state.value();
    }
    return;
  }
  static_assert(kIntegrationChains == 4, "one chain per lane of a Quad");
  const Quad shift = Quad{} + offset;
  Quad sum{};
  Quad compensation{};
  double* const row[4] = {values, values + chain, values + 2 * chain, values + 3 * chain};
  const auto step = [&](Quad& t) {  // one sample of every chain: PhaseState::add, lane by lane
    const Quad y = t - shift;
    const Quad total = sum + y;
    const Quad y_part = total - sum;
    compensation += (sum - (total - y_part)) + (y - y_part);
    sum = total;
    t = sum + compensation;
  };
  for (std::size_t i = 0; i < chain; i += 4) {
    // t[c]: samples i .. i+3 of chain c, transposed so that t[j] holds sample i + j of every chain.
    Quad t[4];
    for (std::size_t c = 0; c < 4; ++c) __builtin_memcpy(&t[c], row[c] + i, sizeof t[c]);
    transpose(t[0], t[1], t[2], t[3]);
    for (Quad& sample : t) step(sample);
    // And back: the local phase of chain c to its samples.
    transpose(t[0], t[1], t[2], t[3]);
    for (std::size_t c = 0; c < 4; ++c) __builtin_memcpy(row[c] + i, &t[c], sizeof t[c]);
  }
  PhaseState local[kIntegrationChains];
  for (std::size_t c = 0; c < kIntegrationChains; ++c) local[c] = {sum[c], compensation[c]};
  PhaseState& last = local[kIntegrationChains - 1];
  for (std::size_t j = kIntegrationChains * chain; j < length; ++j) {  // the remainder: the last chain's
    last.add(values[j] - offset);
    values[j] = last.value();
  }
  for (std::size_t c = 0; c < kIntegrationChains; ++c) {
    const std::size_t begin = c * chain;
    const std::size_t end = c + 1 == kIntegrationChains ? length : begin + chain;
    const double before = state.sum;
    const double before_compensation = state.compensation;
    for (std::size_t j = begin; j < end; ++j) values[j] = before + (before_compensation + values[j]);
    state.add(local[c].sum);
    state.add(local[c].compensation);
  }
}

// TOTDEV terms near an end of the record: t_i = p0[i] - 2 p1[i] + (constant - q[-i]), q read
// backwards (the reflected phase, NIST SP 1065 eq. 25); sum t_i^2 in kLanes lanes.
INERTEST_VECTOR_CLONES
double reflected_squares(const double* __restrict p0, const double* __restrict p1, const double* __restrict q,
                         double constant, std::size_t length) {
  double lanes[kLanes] = {};
  std::size_t i = 0;
  for (; i + kLanes <= length; i += kLanes) {
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double t = second_difference(p0[i + l], p1[i + l], constant - q[-static_cast<std::ptrdiff_t>(i + l)]);
      lanes[l] = fused_multiply_add(t, t, lanes[l]);
    }
  }
  for (; i < length; ++i) {
    const double t = second_difference(p0[i], p1[i], constant - q[-static_cast<std::ptrdiff_t>(i)]);
    lanes[0] = fused_multiply_add(t, t, lanes[0]);
  }
  return lane_total(lanes);
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
  double* samples_in_place = nullptr;  // the caller's samples, when the engine works in place
  std::size_t written = 0;     // phase values written: X_0 .. X_{written-1}
  std::size_t dispatched = 0;  // phase indices below this were handed to the workers
  // Whole blocks handed to the workers at a time: each hand-over is a wake-up and a wait on both
  // sides (futex calls, costly on a virtual machine: an eighth of the CPU time of OADEV alone with
  // one block a job). kJobBlocks, fewer where the ring limit leaves no room for twice as many.
  static constexpr std::size_t kJobBlocks = 8;
  std::size_t job_blocks = 1;
  std::size_t integrated = 1;  // phase values integrated: X_0 .. X_{integrated-1} (the slots above hold samples)
  PhaseState phase;            // the state after X_{integrated-1}
  std::vector<PhaseState> checkpoints;  // the state after each block b, for the second pass

  std::vector<FactorState> factors;   // done in the streaming pass, from the ring
  std::vector<FactorState> deferred;  // their span exceeds the ring: done in the second pass
  std::vector<std::vector<double>> scratch;  // per worker, block_size values of h_k
  // The factors are cut into one contiguous group a worker (adjacent factors share their
  // sub-blocks of far lags), of about equal cost: a factor whose lags reach past the caches (8 m
  // bytes beyond 1 MiB) streams from DRAM and counts twice. In each job the workers take the groups
  // one at a time, the costliest first (next_group), instead of worker w always taking group w: the
  // worker that runs first takes the heavier group, and the one that shares its core with the
  // reader's thread the lighter. Which worker sums a factor never changes the order of its terms:
  // the same bits either way. 3e7 f64 samples, 24 octave factors, 4 x 5 runs of each alternated:
  // OADEV alone 0.254 -> 0.213 s, all six 0.475 -> 0.443 s (medians). Balancing the groups by the
  // time each factor took in the last job was slower (0.23 s): a worker's time counts the
  // reader's share of its core.
  std::vector<std::pair<std::size_t, std::size_t>> groups;  // [first, last) of `factors`
  std::atomic<std::size_t> next_group{0};

  // TOTDEV's right ends (finish's last job) in pieces of at most kEndPiece centres, whichever
  // worker takes them: a factor's end has m centres, and the far group's ends held one worker about
  // 20 ms while the other waited. All six on 3e7 f64 samples, 5 x 3 runs alternated: 0.526 ->
  // 0.475 s median. The pieces are cut the same on any thread count, and a factor's piece totals
  // are added in order: the same bits on any number of threads.
  static constexpr std::size_t kEndPiece = std::size_t{1} << 18;
  struct EndPiece {
    std::size_t factor = 0;  // of `factors`
    std::size_t c0 = 0;      // centres [c0, c1)
    std::size_t c1 = 0;
    double total = 0.0;
  };
  std::vector<EndPiece> end_pieces;
  std::atomic<std::size_t> next_end_piece{0};

  void cut_end_pieces() {
    if (!totdev) return;
    for (std::size_t i = 0; i < factors.size(); ++i) {
      if (factors[i].m < 2) continue;
      for (std::size_t c = sample_count + 1 - factors[i].m; c < sample_count; c += kEndPiece) {
        end_pieces.push_back({i, c, std::min(sample_count, c + kEndPiece), 0.0});
      }
    }
  }

  void add_end_pieces() {
    for (std::size_t p = 0; p < end_pieces.size();) {
      const std::size_t i = end_pieces[p].factor;
      double total = 0.0;
      for (; p < end_pieces.size() && end_pieces[p].factor == i; ++p) total += end_pieces[p].total;
      factors[i].reflected.add(total);
    }
  }

  void group_factors() {
    const std::size_t count = std::min(options.worker_count, factors.size());
    std::vector<std::size_t> cost(factors.size() + 1, 0);  // cost[i]: of factors [0, i)
    for (std::size_t i = 0; i < factors.size(); ++i) {
      cost[i + 1] = cost[i] + (factors[i].m * sizeof(double) >= (std::size_t{1} << 20) ? 2 : 1);
    }
    std::size_t first = 0;
    for (std::size_t g = 1; g <= count; ++g) {
      std::size_t last = g == count ? factors.size() : first + 1;
      while (last < factors.size() - (count - g) && cost[last] * count < g * cost.back()) ++last;
      groups.emplace_back(first, last);
      first = last;
    }
    std::stable_sort(groups.begin(), groups.end(), [&](const auto& a, const auto& b) {
      return cost[a.second] - cost[a.first] > cost[b.second] - cost[b.first];
    });
  }

  std::vector<std::thread> workers;
  std::mutex mutex;
  std::condition_variable start;
  std::condition_variable done;
  std::size_t generation = 0;
  std::size_t pending = 0;
  bool stopping = false;
  Job job;

  std::size_t span_of(std::size_t m) const { return (third ? 3 : 2) * m; }

  // Where X_index is, or its sample waits to be integrated.
  double* slot_of(std::size_t index) {
    return samples_in_place != nullptr ? samples_in_place + index - 1 : ring.data() + index % capacity;
  }
  PhaseStore store() const {
    return samples_in_place != nullptr ? PhaseStore::in_place(samples_in_place, sample_count)
                                       : PhaseStore(ring.data(), capacity);
  }

  // Slots free from X_written on: to the block's end, the record's end or the ring's end,
  // whichever is first.
  std::size_t room() const {
    const std::size_t block = options.block_size;
    return std::min({(written / block + 1) * block - written, capacity - written % capacity, sample_count + 1 - written});
  }

  void write_phase(double value) {
    ring.data()[written % capacity] = value;
    ++written;
  }

  // Integrates every whole block and hands them to the workers as push() does (the same blocks and
  // jobs, so the same bits), and leaves the last part to finish().
  void hand_over_in_place() {
    const std::size_t block = options.block_size;
    for (std::size_t end = (written / block + 1) * block; end <= sample_count + 1; end += block) {
      written = end;
      block_written();
    }
    written = sample_count + 1;
  }

  // A block is whole (written is at its end): it is integrated, and handed to the workers with the
  // blocks before it once there are kJobBlocks of them.
  void block_written() {
    integrate_written();
    if (written - dispatched == job_blocks * options.block_size) {
      dispatch({JobKind::kBlock, dispatched, written});
      dispatched = written;
    }
  }

  // Block b holds the phase indices [b * block, (b + 1) * block) (X_0 = 0 is not integrated);
  // capacity is a multiple of the block or the whole record, so a block never wraps in the ring.
  std::size_t block_begin(std::size_t b) const { return std::max<std::size_t>(1, b * options.block_size); }
  std::size_t block_end(std::size_t b) const { return std::min(sample_count + 1, (b + 1) * options.block_size); }

  // Integrates the samples written since the last call (a whole block, or the record's last part).
  void integrate_written() {
    if (integrated == written) return;
    integrate_block(slot_of(integrated), written - integrated, offset, phase);
    integrated = written;
    if (!deferred.empty()) checkpoints.push_back(phase);
  }

  // A job's worker takes groups (contiguous ranges of the factors, sorted by m; TOTDEV's ends in
  // the last job, end pieces). Within a block it sweeps the anchors in sub-blocks of kSweep and,
  // for each, every factor of its group: on an octave grid the lag 2m of factor m is the lag m of
  // the next factor, so each sub-block of a lagged stream comes from DRAM once and serves two
  // factors from cache, and the sub-blocks of small lags are in L2. Each factor is still summed by
  // one worker in the order of its anchors, in the same sub-blocks whatever the thread count: the
  // same bits on any number of threads.
  // 16384 anchors (128 KiB a stream): the streams of a sub-block stay in L2 for the next factor,
  // and a far lag is read in runs long enough for the prefetchers (4096 was measured slower).
  static constexpr std::size_t kSweep = 16384;

  void run(const Job& work, std::size_t worker) {
    const PhaseStore store = this->store();
    if (work.kind == JobKind::kEnds) {
      for (std::size_t p = next_end_piece++; p < end_pieces.size(); p = next_end_piece++) {
        EndPiece& piece = end_pieces[p];
        piece.total = end_squares(factors[piece.factor], piece.c0, piece.c1, store);
      }
      return;
    }
    for (std::size_t g = next_group++; g < groups.size(); g = next_group++) {
      const auto [first, last] = groups[g];
      // Block by block, each in its sweeps: the same sub-blocks as one block a job would give.
      for (std::size_t b = work.begin; b < work.end;) {
        const std::size_t b1 = std::min(work.end, (b / options.block_size + 1) * options.block_size);
        for (std::size_t k = b; k < b1; k += kSweep) {
          const std::size_t k1 = std::min(b1, k + kSweep);
          for (std::size_t i = first; i < last; ++i) process_block(factors[i], k, k1, store, scratch[worker]);
        }
        b = b1;
      }
    }
  }

  // Terms anchored at phase indices k in [k0, k1): every term whose largest phase index is k.
  void process_block(FactorState& f, std::size_t k0, std::size_t k1, const PhaseStore& store,
                     std::vector<double>& h_buffer) {
    const std::size_t m = f.m;
    const std::size_t sweep_start = (third ? 3 : 2) * m;  // the sweeps sum the d_k from here on
    if (f.overlapping_averages) {
      if (k0 <= m && m < k1) f.overlapping_shift = store.at(m) - store.at(0);
      overlapping_average(f, k0, std::min(k1, sweep_start), store);
    }
    if (totdev) {
      // NIST SP 1065 eq. (25), centres c = k - m in [1, m-1]: X*_{c-m} = 2X_0 - X_{2m-k}, X_0 = 0.
      const std::size_t lo = std::max(k0, m + 1);
      const std::size_t hi = std::min(k1, 2 * m);
      if (lo < hi) {
        double total = 0.0;
        for_each_run<3>(store, {lagged(0), lagged(m), mirrored(2 * m)}, lo, hi, 1, [&](const auto& p, std::size_t n) {
          total += reflected_squares(p[0], p[1], p[2], 0.0, n);
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
        double multiples = 0.0;
        std::size_t k = lo;
        for_each_run<3>(store, {lagged(0), lagged(m), lagged(2 * m)}, lo, hi, 1, [&](const auto& p, std::size_t n) {
          const SecondDifferenceSums sums = second_difference_window(p[0], p[1], p[2], n);
          total += lane_total(sums.second);
          if (adev_from_lanes(m)) multiples += at_multiples(sums.second, k, m);
          f.window += sums.averages.sum;
          k += n;
        });
        f.sums[index_of(Estimator::kOadev)].add(total);
        if (adev_from_lanes(m)) f.sums[index_of(Estimator::kAdev)].add(multiples);
        if (hi == 3 * m) f.sums[index_of(Estimator::kMdev)].add(f.window * f.window);  // w_{3m-1}
      }
      sweep_third(f, std::max(k0, 3 * m), k1, store, h_buffer);
    } else {
      sweep_second(f, std::max(k0, 2 * m), k1, store);
    }
    if (adev && !adev_from_lanes(m)) strided(f, Estimator::kAdev, 2 * m, k0, k1, store);
    if (hdev && !hdev_from_lanes(m)) strided(f, Estimator::kHdev, 3 * m, k0, k1, store);
    average(f, k0, k1, store);
  }

  // The ADEV (HDEV) terms are those of OADEV (OHDEV) at the anchors k that are multiples of m (NIST
  // SP 1065 eqs. 7 and 8, 15 and 16). Where m divides kLanes, a lane of a sweep's run holds anchors
  // of one residue mod m, so the sweep's lanes give the ADEV and HDEV sums too: no strided pass
  // (a gather of every m-th phase value; the factors m <= 16 cost N (1 + 1/2 + ...) terms each).
  bool adev_from_lanes(std::size_t m) const { return adev && kLanes % m == 0; }
  bool hdev_from_lanes(std::size_t m) const { return hdev && kLanes % m == 0; }
  // The terms of a run whose first anchor is k at the anchors that are multiples of m.
  static double at_multiples(const Lanes& lanes, std::size_t k, std::size_t m) {
    return strided_lane_total(lanes, (m - k % m) % m, m);
  }

  // d_k = X_k - X_{k-m} at every anchor k in [max(k0, m), k1): m times the overlapping averages
  // (the sweeps sum them past 2m or 3m, with their differences).
  void overlapping_average(FactorState& f, std::size_t k0, std::size_t k1, const PhaseStore& store) {
    const std::size_t m = f.m;
    for_each_run<2>(store, {lagged(0), lagged(m)}, std::max(k0, m), k1, 1, [&](const auto& p, std::size_t n) {
      add_average_sums(f, difference_sums(p[0], p[1], n, f.overlapping_shift));
    });
  }

  static void add_average_sums(FactorState& f, const AverageSums& sums) {
    f.overlapping_sum.add(sums.sum);
    f.overlapping_squares.add(sums.squares);
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
      // Through a buffer: add_all keeps the series' sums in registers (add() one by one kept them
      // in memory, a store-to-load latency per sum and average).
      constexpr std::size_t kBatch = 512;
      double batch[kBatch];
      for (std::size_t i = 0; i < n; i += kBatch) {
        const std::size_t count = std::min(kBatch, n - i);
        for (std::size_t j = 0; j < count; ++j) batch[j] = (p[0][(i + j) * m] - p[1][(i + j) * m]) * inverse;
        f.averages.add_all(std::span<const double>(batch, count));
      }
    });
  }

  // OADEV (and TOTDEV interior) terms a_k for k >= 2m when no third differences are needed.
  void sweep_second(FactorState& f, std::size_t k0, std::size_t k1, const PhaseStore& store) {
    if (k0 >= k1) return;
    const std::size_t m = f.m;
    const double* shift = f.overlapping_averages ? &f.overlapping_shift : nullptr;
    std::size_t k = k0;
    for_each_run<3>(store, {lagged(0), lagged(m), lagged(2 * m)}, k0, k1, 1, [&](const auto& p, std::size_t length) {
      const SecondDifferenceSums sums = second_difference_sums(p[0], p[1], p[2], length, shift);
      f.sums[index_of(Estimator::kOadev)].add(lane_total(sums.second));
      if (adev_from_lanes(m)) f.sums[index_of(Estimator::kAdev)].add(at_multiples(sums.second, k, m));
      if (shift != nullptr) add_average_sums(f, sums.averages);
      k += length;
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
      std::size_t run_start = k;
      for_each_run<4>(store, {lagged(0), lagged(m), lagged(2 * m), lagged(3 * m)}, k, piece_end, 1,
                      [&](const auto& p, std::size_t length) {
                        if (mdev) {
                          third_run<true>(f, p, run_start, length, h_buffer.data());
                        } else {
                          third_run<false>(f, p, run_start, length, h_buffer.data());
                        }
                        run_start += length;
                      });
      k = piece_end;
    }
  }

  // Without MDEV the h_k are not stored: one stream less through the cache.
  // The run's first anchor is k.
  template <bool kWithMdev>
  void third_run(FactorState& f, const std::array<const double*, 4>& p, std::size_t k, std::size_t length,
                 double* h) {
    const std::size_t m = f.m;
    const double* shift = f.overlapping_averages ? &f.overlapping_shift : nullptr;
    const ThirdDifferenceSquares squares =
        third_difference_squares(p[0], p[1], p[2], p[3], length, kWithMdev ? h : nullptr, shift);
    if (shift != nullptr) add_average_sums(f, squares.averages);
    f.sums[index_of(Estimator::kOadev)].add(lane_total(squares.second));
    f.sums[index_of(Estimator::kOhdev)].add(lane_total(squares.third));
    if (adev_from_lanes(m)) f.sums[index_of(Estimator::kAdev)].add(at_multiples(squares.second, k, m));
    if (hdev_from_lanes(m)) f.sums[index_of(Estimator::kHdev)].add(at_multiples(squares.third, k, m));
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
        total += strided_squares(n, [&](std::size_t i) { return p[0][i * m] - 2.0 * p[1][i * m] + p[2][i * m]; });
      });
    } else {
      for_each_run<4>(store, {lagged(0), lagged(m), lagged(2 * m), lagged(3 * m)}, k, k1, m,
                      [&](const auto& p, std::size_t n) {
                        total += strided_squares(n, [&](std::size_t i) {
                          return p[0][i * m] - 3.0 * p[1][i * m] + 3.0 * p[2][i * m] - p[3][i * m];
                        });
                      });
    }
    f.sums[index_of(estimator)].add(total);
  }

  // The sum of the TOTDEV terms at the centres c in [c0, c1) within [N-m+1, N-1]:
  // X*_{c+m} = 2X_N - X_{2N-c-m} (NIST SP 1065 eq. 25).
  double end_squares(const FactorState& f, std::size_t c0, std::size_t c1, const PhaseStore& store) const {
    const std::size_t n = sample_count;
    const std::size_t m = f.m;
    if (!totdev || m < 2 || c0 >= c1) return 0.0;
    const double twice_last = 2.0 * store.at(n);
    double total = 0.0;
    for_each_run<3>(store, {lagged(m), lagged(0), mirrored(2 * n - m)}, c0, c1, 1, [&](const auto& p, std::size_t len) {
      total += reflected_squares(p[0], p[1], p[2], twice_last, len);
    });
    return total;
  }

  // Fills each window with X_j, j in [start, start + size), integrating the samples again from the
  // checkpoint at or before its start with the very operations of push(): the same values.
  void fill_windows(std::span<PhaseStore::Window> windows, const SampleReader& reader,
                    std::vector<double>& samples) const {
    for (PhaseStore::Window& w : windows) {
      const std::size_t end = w.start + w.values.size();
      if (w.start == 0) w.values[0] = 0.0;  // X_0
      const std::size_t block = options.block_size;
      for (std::size_t b = w.start / block; b * block < end; ++b) {
        const std::size_t lo = block_begin(b);
        const std::size_t hi = block_end(b);
        if (lo >= hi) continue;
        // Samples lo - 1 .. hi - 2 give X_lo .. X_{hi-1}, integrated as push() did from the state after block b - 1.
        PhaseState state = b == 0 ? PhaseState{} : checkpoints[b - 1];
        reader(lo - 1, std::span<double>(samples.data(), hi - lo));
        integrate_block(samples.data(), hi - lo, offset, state);
        const std::size_t from = std::max(lo, w.start);
        const std::size_t to = std::min(hi, end);
        std::copy(samples.begin() + static_cast<std::ptrdiff_t>(from - lo),
                  samples.begin() + static_cast<std::ptrdiff_t>(to - lo),
                  w.values.begin() + static_cast<std::ptrdiff_t>(from - w.start));
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
    std::vector<double> samples(options.block_size);
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
          f.reflected.add(end_squares(f, ca, cb, PhaseStore(segment_windows())));
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
    next_group = 0;
    next_end_piece = 0;
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
    : AllanEngine(sample_count, offset, std::move(options), nullptr) {}

AllanEngine::AllanEngine(std::span<double> samples, double offset, AllanEngineOptions options)
    : AllanEngine(samples.size(), offset, std::move(options), samples.data()) {}

AllanEngine::AllanEngine(std::size_t sample_count, double offset, AllanEngineOptions options, double* samples_in_place)
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
  // Factors whose span does not fit the ring limit go to the second pass (in place, none: the
  // whole record is there).
  const std::size_t limit =
      options.ring_capacity_limit == 0 || samples_in_place != nullptr ? sample_count + 1 : options.ring_capacity_limit;
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
  // A multiple of the block, so that a block never wraps (integrate_block works on contiguous blocks),
  // with room for the job the workers sum and the one being written.
  s.job_blocks = State::kJobBlocks;
  while (s.job_blocks > 1 && ring_span + 2 * s.job_blocks * options.block_size > limit) --s.job_blocks;
  const std::size_t blocks_in_ring =
      (ring_span + 2 * s.job_blocks * options.block_size + options.block_size - 1) / options.block_size;
  s.capacity = std::min(sample_count + 1, blocks_in_ring * options.block_size);
  s.samples_in_place = samples_in_place;
  if (samples_in_place == nullptr) s.ring.reset(s.capacity);
  options.worker_count = std::max<std::size_t>(1, std::min(options.worker_count, s.factors.size()));
  s.scratch.assign(options.worker_count, std::vector<double>(options.block_size));
  s.options = std::move(options);
  s.group_factors();
  if (samples_in_place == nullptr) {
    s.write_phase(0.0);  // X_0 = 0
  } else {
    s.written = 1;  // X_0 = 0 is the store's
  }
  if (s.options.worker_count > 1) {
    for (std::size_t w = 0; w < s.options.worker_count; ++w) {
      s.workers.emplace_back([&s, w] { s.worker_loop(w); });
    }
  }
  if (samples_in_place == nullptr) s.ring.prefault();
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
  const State& s = *state_;
  if (s.samples_in_place == nullptr && s.written - 1 + samples.size() > s.sample_count) {
    throw Error("more samples than the " + std::to_string(s.sample_count) + " announced");
  }
  while (!samples.empty()) {
    const std::span<double> slots = room();
    const std::size_t piece = std::min(slots.size(), samples.size());
    std::copy_n(samples.begin(), piece, slots.begin());
    commit(piece);
    samples = samples.subspan(piece);
  }
}

std::span<double> AllanEngine::room() {
  State& s = *state_;
  if (s.samples_in_place != nullptr) throw Error("internal: an engine in place has its samples already");
  const std::size_t slots = s.room();
  if (slots == 0) throw Error("more samples than the " + std::to_string(s.sample_count) + " announced");
  return {s.ring.data() + s.written % s.capacity, slots};
}

void AllanEngine::commit(std::size_t count) {
  State& s = *state_;
  if (count > s.room()) throw Error("internal: more samples committed than room() gave");
  // The samples wait in their slots; the block is integrated in place once it is whole.
  s.written += count;
  if (s.written % s.options.block_size == 0) s.block_written();
}

std::vector<AllanSums> AllanEngine::finish(const SampleReader& reader) {
  State& s = *state_;
  if (s.samples_in_place != nullptr && s.dispatched == 0) s.hand_over_in_place();
  if (s.written != s.sample_count + 1) {
    throw Error("only " + std::to_string(s.written - 1) + " of " + std::to_string(s.sample_count) +
                " samples were pushed");
  }
  if (s.dispatched < s.written) {
    s.integrate_written();
    s.dispatch({State::JobKind::kBlock, s.dispatched, s.written});
    s.dispatched = s.written;
  }
  s.cut_end_pieces();
  s.dispatch({State::JobKind::kEnds, 0, 0});
  s.wait_idle();
  s.add_end_pieces();
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
      // Sample variance of the d_k / m from the sums of d_k - d_m (the first): shifted so, the two
      // sums do not cancel whatever offset the phase was integrated with.
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

double AllanEngine::phase_total() const {
  const State& s = *state_;
  if (s.integrated != s.sample_count + 1) throw Error("internal: the phase total is known after finish()");
  return s.phase.value();
}

std::size_t AllanEngine::ring_bytes() const {
  return state_->samples_in_place != nullptr ? 0 : state_->capacity * sizeof(double);
}

std::size_t AllanEngine::deferred_factor_count() const { return state_->deferred.size(); }

}  // namespace inertest
