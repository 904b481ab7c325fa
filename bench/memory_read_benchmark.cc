// The machine's read bandwidth from DRAM, beside which `make bench` puts the Allan engine's: one
// pass over 1 GiB of doubles, summed in 8 independent lanes (no dependency chain limits it), on 1
// thread and on 2 threads each reading half. bytes_per_second is the bandwidth.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <thread>
#include <vector>

namespace {

constexpr std::size_t kDoubles = std::size_t{1} << 27;  // 1 GiB: far beyond any cache
constexpr std::size_t kLanes = 8;

const std::vector<double>& block() {
  static const std::vector<double> values(kDoubles, 1.0);
  return values;
}

double lane_sum(const double* values, std::size_t count) {
  double lanes[kLanes] = {};
  for (std::size_t i = 0; i + kLanes <= count; i += kLanes) {
    for (std::size_t l = 0; l < kLanes; ++l) lanes[l] += values[i + l];
  }
  double total = 0.0;
  for (double lane : lanes) total += lane;
  return total;
}

void BM_MemoryRead(benchmark::State& state) {
  const std::vector<double>& values = block();
  const auto threads = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) {
    std::vector<double> totals(threads);
    std::vector<std::thread> helpers;
    const std::size_t share = kDoubles / threads;
    for (std::size_t t = 1; t < threads; ++t) {
      helpers.emplace_back([&, t] { totals[t] = lane_sum(values.data() + t * share, share); });
    }
    totals[0] = lane_sum(values.data(), share);
    for (std::thread& helper : helpers) helper.join();
    benchmark::DoNotOptimize(totals.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * kDoubles * sizeof(double)));
}

BENCHMARK(BM_MemoryRead)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
