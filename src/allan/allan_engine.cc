#include "inertest/allan/allan_engine.h"

#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "inertest/core/error.h"
#include "inertest/numerics/compensated_sum.h"

namespace inertest {
namespace {

constexpr std::size_t index_of(Estimator e) { return static_cast<std::size_t>(e); }

// A position in the ring buffer of the phase that moves by whole steps (step < capacity).
class Cursor {
 public:
  Cursor(const double* ring, std::size_t capacity, std::size_t phase_index)
      : ring_(ring), capacity_(capacity), slot_(phase_index % capacity) {}
  double operator*() const { return ring_[slot_]; }
  void advance(std::size_t step) {
    slot_ += step;
    if (slot_ >= capacity_) slot_ -= capacity_;
  }
  void retreat() { slot_ = slot_ == 0 ? capacity_ - 1 : slot_ - 1; }

 private:
  const double* ring_;
  std::size_t capacity_;
  std::size_t slot_;
};

// Per averaging factor: the running MDEV window and the compensated sums of squares.
struct FactorState {
  std::size_t m = 0;
  double window = 0.0;  // w_k of MDEV, updated w_k = w_{k-1} + a_k - a_{k-m}
  std::array<CompensatedSum, 6> sums;
  CompensatedSum reflected;  // TOTDEV terms whose centre lies within m of an end
};

constexpr std::size_t kLanes = 4;

double lane_total(const double (&lanes)[kLanes]) { return (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]); }

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
  std::vector<double> ring;
  std::size_t written = 0;     // phase values written: X_0 .. X_{written-1}
  std::size_t dispatched = 0;  // phase indices below this were handed to the workers
  double phase_sum = 0.0;      // Neumaier running sum of (y - offset): X = phase_sum + phase_compensation
  double phase_compensation = 0.0;

  std::vector<FactorState> factors;
  std::vector<std::vector<double>> scratch;  // per worker, block_size values of h_k

  std::vector<std::thread> workers;
  std::mutex mutex;
  std::condition_variable start;
  std::condition_variable done;
  std::size_t generation = 0;
  std::size_t pending = 0;
  bool stopping = false;
  Job job;

  double x(std::size_t k) const { return ring[k % capacity]; }

  void write_phase(double value) {
    ring[written % capacity] = value;
    ++written;
  }

  void run(const Job& work, std::size_t worker) {
    for (std::size_t i = worker; i < factors.size(); i += options.worker_count) {
      if (work.kind == JobKind::kBlock) {
        process_block(factors[i], work.begin, work.end, scratch[worker]);
      } else {
        process_end(factors[i]);
      }
    }
  }

  // Terms anchored at phase indices k in [k0, k1): every term whose largest phase index is k.
  void process_block(FactorState& f, std::size_t k0, std::size_t k1, std::vector<double>& h_buffer) {
    const std::size_t m = f.m;
    const double* base = ring.data();
    if (totdev) {
      // NIST SP 1065 eq. (25), centres c = k - m in [1, m-1]: X*_{c-m} = 2X_0 - X_{2m-k}, X_0 = 0.
      const std::size_t lo = std::max(k0, m + 1);
      const std::size_t hi = std::min(k1, 2 * m);
      if (lo < hi) {
        Cursor newest(base, capacity, lo), centre(base, capacity, lo - m), mirrored(base, capacity, 2 * m - lo);
        double lanes[kLanes] = {};
        for (std::size_t k = lo; k < hi; ++k) {
          const double term = -*mirrored - 2.0 * *centre + *newest;
          lanes[k % kLanes] += term * term;
          newest.advance(1);
          centre.advance(1);
          mirrored.retreat();
        }
        f.reflected.add(lane_total(lanes));
      }
    }
    if (third) {
      // Region 2m <= k < 3m: second differences only; the first MDEV window fills up.
      const std::size_t lo = std::max(k0, 2 * m);
      const std::size_t hi = std::min(k1, 3 * m);
      if (lo < hi) {
        Cursor c0(base, capacity, lo), c1(base, capacity, lo - m), c2(base, capacity, lo - 2 * m);
        double lanes[kLanes] = {};
        for (std::size_t k = lo; k < hi; ++k) {
          const double a = *c0 - 2.0 * *c1 + *c2;
          lanes[k % kLanes] += a * a;
          f.window += a;
          if (k == 3 * m - 1) f.sums[index_of(Estimator::kMdev)].add(f.window * f.window);
          c0.advance(1);
          c1.advance(1);
          c2.advance(1);
        }
        f.sums[index_of(Estimator::kOadev)].add(lane_total(lanes));
      }
      sweep_third(f, std::max(k0, 3 * m), k1, h_buffer);
    } else {
      sweep_second(f, std::max(k0, 2 * m), k1);
    }
    if (adev) strided(f, Estimator::kAdev, 2 * m, k0, k1);
    if (hdev) strided(f, Estimator::kHdev, 3 * m, k0, k1);
  }

  // Calls kernel(pointers, length) over [k0, k1) in pieces where no stream wraps around the ring;
  // stream s reads X_{k - s m}.
  template <std::size_t Streams, typename Kernel>
  void for_each_piece(std::size_t m, std::size_t k0, std::size_t k1, Kernel&& kernel) {
    std::size_t k = k0;
    while (k < k1) {
      std::size_t length = k1 - k;
      std::array<const double*, Streams> p{};
      for (std::size_t s = 0; s < Streams; ++s) {
        const std::size_t slot = (k - s * m) % capacity;
        p[s] = ring.data() + slot;
        length = std::min(length, capacity - slot);
      }
      kernel(p, length);
      k += length;
    }
  }

  // OADEV (and TOTDEV interior) terms a_k for k >= 2m when no third differences are needed.
  void sweep_second(FactorState& f, std::size_t k0, std::size_t k1) {
    if (k0 >= k1) return;
    for_each_piece<3>(f.m, k0, k1, [&](const std::array<const double*, 3>& p, std::size_t length) {
      double lanes[kLanes] = {};
      std::size_t i = 0;
      for (; i + kLanes <= length; i += kLanes) {
        for (std::size_t l = 0; l < kLanes; ++l) {
          const double a = p[0][i + l] - 2.0 * p[1][i + l] + p[2][i + l];
          lanes[l] += a * a;
        }
      }
      for (; i < length; ++i) {
        const double a = p[0][i] - 2.0 * p[1][i] + p[2][i];
        lanes[0] += a * a;
      }
      f.sums[index_of(Estimator::kOadev)].add(lane_total(lanes));
    });
  }

  // k >= 3m: a_k (OADEV), h_k = a_k - a_{k-m} (OHDEV), w_k = w_{k-1} + h_k (MDEV).
  void sweep_third(FactorState& f, std::size_t k0, std::size_t k1, std::vector<double>& h_buffer) {
    if (k0 >= k1) return;
    for_each_piece<4>(f.m, k0, k1, [&](const std::array<const double*, 4>& p, std::size_t length) {
      double lanes_a[kLanes] = {};
      double lanes_h[kLanes] = {};
      // Restrict-qualified copies let the compiler vectorise across the lanes.
      const double* __restrict p0 = p[0];
      const double* __restrict p1 = p[1];
      const double* __restrict p2 = p[2];
      const double* __restrict p3 = p[3];
      double* __restrict h = h_buffer.data();
      std::size_t i = 0;
      for (; i + kLanes <= length; i += kLanes) {
        for (std::size_t l = 0; l < kLanes; ++l) {
          const double a = p0[i + l] - 2.0 * p1[i + l] + p2[i + l];
          const double hk = a - (p1[i + l] - 2.0 * p2[i + l] + p3[i + l]);
          h[i + l] = hk;
          lanes_a[l] += a * a;
          lanes_h[l] += hk * hk;
        }
      }
      for (; i < length; ++i) {
        const double a = p0[i] - 2.0 * p1[i] + p2[i];
        const double hk = a - (p1[i] - 2.0 * p2[i] + p3[i]);
        h[i] = hk;
        lanes_a[0] += a * a;
        lanes_h[0] += hk * hk;
      }
      f.sums[index_of(Estimator::kOadev)].add(lane_total(lanes_a));
      f.sums[index_of(Estimator::kOhdev)].add(lane_total(lanes_h));
      if (mdev) {
        // The window is a running sum: its rounding error grows like sqrt(N) ulp of w, about
        // 1e-12 relative for N = 1e9, far inside the 1e-9 the estimators are held to.
        double window = f.window;
        double lanes_w[kLanes] = {};
        std::size_t j = 0;
        for (; j + kLanes <= length; j += kLanes) {
          for (std::size_t l = 0; l < kLanes; ++l) {
            window += h[j + l];
            lanes_w[l] += window * window;
          }
        }
        for (; j < length; ++j) {
          window += h[j];
          lanes_w[0] += window * window;
        }
        f.window = window;
        f.sums[index_of(Estimator::kMdev)].add(lane_total(lanes_w));
      }
    });
  }

  // ADEV (second differences) or HDEV (third differences) at k = first, first + m, ... (multiples of m).
  void strided(FactorState& f, Estimator estimator, std::size_t first_anchor, std::size_t k0, std::size_t k1) {
    const std::size_t m = f.m;
    std::size_t k = std::max(k0, first_anchor);
    k = (k + m - 1) / m * m;
    if (k >= k1) return;
    const double* base = ring.data();
    Cursor c0(base, capacity, k), c1(base, capacity, k - m), c2(base, capacity, k - 2 * m);
    double total = 0.0;
    if (estimator == Estimator::kAdev) {
      for (; k < k1; k += m) {
        const double a = *c0 - 2.0 * *c1 + *c2;
        total += a * a;
        c0.advance(m);
        c1.advance(m);
        c2.advance(m);
      }
    } else {
      Cursor c3(base, capacity, k - 3 * m);
      for (; k < k1; k += m) {
        const double h = *c0 - 3.0 * *c1 + 3.0 * *c2 - *c3;
        total += h * h;
        c0.advance(m);
        c1.advance(m);
        c2.advance(m);
        c3.advance(m);
      }
    }
    f.sums[index_of(estimator)].add(total);
  }

  // TOTDEV centres c in [N-m+1, N-1]: X*_{c+m} = 2X_N - X_{2N-c-m} (NIST SP 1065 eq. 25).
  void process_end(FactorState& f) {
    if (!totdev) return;
    const std::size_t n = sample_count;
    const std::size_t m = f.m;
    if (m < 2) return;
    const double* base = ring.data();
    const double twice_last = 2.0 * x(n);
    Cursor before(base, capacity, n + 1 - 2 * m), centre(base, capacity, n + 1 - m), mirrored(base, capacity, n - 1);
    double lanes[kLanes] = {};
    for (std::size_t c = n + 1 - m; c < n; ++c) {
      const double term = *before - 2.0 * *centre + twice_last - *mirrored;
      lanes[c % kLanes] += term * term;
      before.advance(1);
      centre.advance(1);
      mirrored.retreat();
    }
    f.reflected.add(lane_total(lanes));
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
  options.worker_count = std::max<std::size_t>(1, std::min(options.worker_count, options.averaging_factors.size()));
  s.sample_count = sample_count;
  s.offset = offset;
  s.third = options.estimators.needs_third_differences();
  s.mdev = options.estimators.contains(Estimator::kMdev);
  s.adev = options.estimators.contains(Estimator::kAdev);
  s.hdev = options.estimators.contains(Estimator::kHdev);
  s.totdev = options.estimators.contains(Estimator::kTotdev);
  const std::size_t m_max = options.averaging_factors.empty() ? 1 : options.averaging_factors.back();
  const std::size_t span = (s.third ? 3 : 2) * m_max;
  // While workers read X_{k0 - span} .. X_{k1 - 1}, the caller writes up to X_{k1 + block - 1}:
  // span + 2 blocks of capacity keep the two apart. A record shorter than that is held whole.
  s.capacity = std::min(sample_count + 1, span + 2 * options.block_size);
  s.ring.assign(s.capacity, 0.0);
  s.factors.resize(options.averaging_factors.size());
  for (std::size_t i = 0; i < s.factors.size(); ++i) s.factors[i].m = options.averaging_factors[i];
  s.scratch.assign(options.worker_count, std::vector<double>(options.block_size));
  s.options = std::move(options);
  s.write_phase(0.0);  // X_0 = 0
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
    const std::size_t room = s.dispatched + block - s.written;
    const std::size_t piece = std::min(room, samples.size() - i);
    double sum = s.phase_sum;
    double compensation = s.phase_compensation;
    for (std::size_t j = i; j < i + piece; ++j) {
      // Neumaier summation of the mean-removed rate: the phase keeps full precision over 1e9 samples.
      const double y = samples[j] - s.offset;
      const double t = sum + y;
      compensation += std::abs(sum) >= std::abs(y) ? (sum - t) + y : (y - t) + sum;
      sum = t;
      s.write_phase(sum + compensation);
    }
    s.phase_sum = sum;
    s.phase_compensation = compensation;
    i += piece;
    if (s.written - s.dispatched == block) {
      s.dispatch({State::JobKind::kBlock, s.dispatched, s.written});
      s.dispatched = s.written;
    }
  }
}

std::vector<AllanSums> AllanEngine::finish() {
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
  const std::size_t n = s.sample_count;
  std::vector<AllanSums> result;
  for (FactorState& f : s.factors) {
    AllanSums sums;
    const std::size_t m = f.m;
    sums.averaging_factor = m;
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

std::size_t AllanEngine::ring_bytes() const { return state_->ring.size() * sizeof(double); }

}  // namespace inertest
