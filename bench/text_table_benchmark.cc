// Text-record parsing throughput (bytes/s) of io/text_table on an in-memory CSV record of
// time,output rows, as a logger writes them. Compare with pandas/numpy in bench/csv_compare.py.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <random>
#include <string>

#include "inertest/io/text_table.h"

namespace {

std::string make_record(std::size_t rows) {
  std::mt19937_64 generator(7);
  std::normal_distribution<double> noise(100.0, 0.5);
  std::string text = "time_s,output\n";
  text.reserve(rows * 24);
  char line[64];
  for (std::size_t i = 0; i < rows; ++i) {
    const int n = std::snprintf(line, sizeof line, "%.6f,%.6f\n", static_cast<double>(i) * 0.01, noise(generator));
    text.append(line, static_cast<std::size_t>(n));
  }
  return text;
}

void parse_csv(benchmark::State& state) {
  const std::string text = make_record(static_cast<std::size_t>(state.range(0)));
  inertest::TextTableOptions options;
  options.record_row_lines = false;
  for (auto _ : state) {
    const inertest::TextTable table = inertest::parse_text_table(text, "bench.csv", options);
    benchmark::DoNotOptimize(table.columns.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(text.size()));
}

}  // namespace

BENCHMARK(parse_csv)->Arg(100'000)->Arg(4'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
