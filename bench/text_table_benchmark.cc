// Text-record parsing throughput (bytes/s) of io/text_table on a CSV record in memory: the row
// parser alone, without the process, the file's mapping or anything done with the columns after.
//   parse_csv/N: N synthetic time,output rows, as a logger writes them;
//   parse_record: the file given by --record=PATH, read into memory first (bench/csv_compare.py
//   passes its record, so that pandas.read_csv parses the same bytes from memory beside it).
// The columns are allocated in every iteration, as a run of inertest allocates them.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

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

void parse(benchmark::State& state, const std::string& text) {
  inertest::TextTableOptions options;
  options.record_row_lines = false;
  for (auto _ : state) {
    const inertest::TextTable table = inertest::parse_text_table(text, "bench.csv", options);
    benchmark::DoNotOptimize(table.columns.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(text.size()));
}

void parse_csv(benchmark::State& state) { parse(state, make_record(static_cast<std::size_t>(state.range(0)))); }

}  // namespace

BENCHMARK(parse_csv)->Arg(100'000)->Arg(4'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();

int main(int argc, char** argv) {
  // --record=PATH is this program's own flag; the rest are Google Benchmark's.
  std::vector<char*> rest;
  static std::string record;
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], "--record=", 9) == 0) {
      std::ifstream file(argv[i] + 9, std::ios::binary);
      if (!file) {
        std::fprintf(stderr, "cannot read %s\n", argv[i] + 9);
        return 1;
      }
      std::ostringstream content;
      content << file.rdbuf();
      record = content.str();
    } else {
      rest.push_back(argv[i]);
    }
  }
  if (!record.empty()) {
    benchmark::RegisterBenchmark("parse_record", [](benchmark::State& state) { parse(state, record); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  int count = static_cast<int>(rest.size());
  benchmark::Initialize(&count, rest.data());
  if (benchmark::ReportUnrecognizedArguments(count, rest.data())) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
