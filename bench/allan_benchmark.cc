// Throughput of the Allan engine on 2^22 samples in memory, octave taus: all six estimators and
// OADEV alone, on 1 and 2 worker threads.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "inertest/allan/allan_engine.h"

namespace {

const std::vector<double>& record() {
  static const std::vector<double> samples = [] {
    std::mt19937_64 random(1);
    std::normal_distribution<double> white(0.0, 1.0);
    std::vector<double> y(1u << 22);
    double walk = 0.0;
    for (double& v : y) {
      walk += 1e-3 * white(random);
      v = white(random) + walk;
    }
    return y;
  }();
  return samples;
}

void run(benchmark::State& state, const char* estimators) {
  const std::vector<double>& y = record();
  inertest::AllanEngineOptions options;
  options.estimators = inertest::EstimatorSet::parse(estimators);
  options.worker_count = static_cast<std::size_t>(state.range(0));
  const std::size_t largest = inertest::largest_averaging_factor(y.size(), options.estimators);
  for (std::size_t m = 1; m <= largest; m *= 2) options.averaging_factors.push_back(m);
  for (auto _ : state) {
    inertest::AllanEngine engine(y.size(), 0.0, options);
    engine.push(y);
    benchmark::DoNotOptimize(engine.finish());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * y.size()));
}

void BM_AllanAllSixOctave(benchmark::State& state) { run(state, "all"); }
void BM_AllanOadevOctave(benchmark::State& state) { run(state, "oadev"); }

BENCHMARK(BM_AllanAllSixOctave)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AllanOadevOctave)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
