// Helpers shared by the tests: relative tolerances, running the CLI, scratch files.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace inertest {
struct ProcedureSpec;
}

namespace inertest::testing {

// |actual - expected| <= tolerance * |expected| (absolute tolerance when expected is 0).
::testing::AssertionResult near_relative(double actual, double expected, double tolerance);

#define EXPECT_NEAR_RELATIVE(actual, expected, tolerance) \
  EXPECT_TRUE(::inertest::testing::near_relative((actual), (expected), (tolerance)))

// Log relative error, as Ceres checks certified data: -log10(|a - e| / |e|), the number of
// matching significant digits.
double log_relative_error(double actual, double expected);

// Names parameterised test cases after their param's `name` member:
//   INSTANTIATE_TEST_SUITE_P(Suite, Fixture, ::testing::Values(...), inertest::testing::NameOfParam());
struct NameOfParam {
  template <typename T>
  std::string operator()(const ::testing::TestParamInfo<T>& param_info) const {
    return std::string(param_info.param.name);
  }
};

struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// The path of build/bin/inertest.
std::string cli_path();

// Runs build/bin/inertest with the arguments (no shell quoting; each is one argv entry), its stdout
// into `stdout_path` when given (run.out is then empty).
CliRun run_cli(const std::vector<std::string>& arguments, const std::string& stdout_path = "");

// `inertest <kind> <example...> --json`, the worked example of a declared procedure
// (ProcedureSpec::example); its arguments that name a file of the source tree are made absolute.
CliRun run_example(const ProcedureSpec& spec);

// Whether `text` names one of the papers by the file name of the developers' text extraction
// ("000_746ebd72f166769f.txt", "paper 001", ".../seeds/"): users cite them as core/citations.h does.
bool names_a_seed_file(const std::string& text);

// The whole content of a file.
std::string read_file(const std::string& path);

// A fresh scratch directory for this test, removed when the object dies.
class ScratchDirectory {
 public:
  ScratchDirectory();
  ~ScratchDirectory();
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const std::string& path() const { return path_; }
  // Writes a file under the directory and returns its path.
  std::string write(const std::string& name, const std::string& content) const;

 private:
  std::string path_;
};

// Uniform numbers in [-0.5, 0.5) from a 64-bit linear congruential generator (Knuth's MMIX
// constants): records that are the same on every platform, unlike <random>'s distributions.
class UniformSequence {
 public:
  explicit UniformSequence(std::uint64_t seed = 12345) : state_(seed) {}
  double next() {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state_ >> 11) / 9007199254740992.0 - 0.5;
  }

 private:
  std::uint64_t state_;
};

// n samples of mean + UniformSequence noise: white noise of variance 1/12 around the mean.
std::vector<double> uniform_noise(double mean, std::size_t n);

// The values as a raw little-endian f64 record holds them.
std::string f64_bytes(const std::vector<double>& values);

// Path of a file in the source tree, e.g. source_path("data/scale_factor/points.csv").
std::string source_path(const std::string& relative);

// The source tree's CSV record `example` (a header, then rows) written as `name` in `directory`, with
// the columns `columns` (0-based) of every row passed through `transform`; returns its path.
std::string write_example_with(const ScratchDirectory& directory, const std::string& example, const std::string& name,
                               const std::vector<std::size_t>& columns, const std::function<double(double)>& transform);

}  // namespace inertest::testing
