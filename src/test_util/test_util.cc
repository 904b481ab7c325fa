#include "test_util/test_util.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include "inertest/core/procedure_spec.h"

namespace inertest::testing {

::testing::AssertionResult near_relative(double actual, double expected, double tolerance) {
  const double error = std::abs(actual - expected);
  const double bound = expected == 0.0 ? tolerance : tolerance * std::abs(expected);
  if (error <= bound) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "actual " << actual << " differs from expected " << expected << " by "
                                       << error << " (relative " << error / std::abs(expected) << "), more than "
                                       << tolerance << (expected == 0.0 ? " absolute" : " relative");
}

std::vector<double> uniform_noise(double mean, std::size_t n) {
  UniformSequence uniform;
  std::vector<double> samples(n);
  for (double& v : samples) v = mean + uniform.next();
  return samples;
}

std::string f64_bytes(const std::vector<double>& values) {
  static_assert(std::endian::native == std::endian::little, "the f64 records of the tests are little-endian");
  std::string bytes(values.size() * sizeof(double), '\0');
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

double log_relative_error(double actual, double expected) {
  if (actual == expected) return 17.0;
  return -std::log10(std::abs(actual - expected) / std::abs(expected));
}

CliRun run_example(const ProcedureSpec& spec) {
  std::vector<std::string> arguments = {kebab_case(spec.kind)};
  for (const std::string& argument : spec.example) {
    const std::string path = source_path(argument);
    arguments.push_back(std::filesystem::exists(path) ? path : argument);
  }
  arguments.push_back("--json");
  return run_cli(arguments);
}

std::string cli_path() { return INERTEST_CLI_PATH; }

CliRun run_cli(const std::vector<std::string>& arguments, const std::string& stdout_path) {
  // stdout and stderr go to files, so neither pipe can block the other.
  ScratchDirectory scratch;
  const std::string out_path = stdout_path.empty() ? scratch.path() + "/out" : stdout_path;
  const std::string err_path = scratch.path() + "/err";
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::vector<char*> argv;
    std::string program = cli_path();
    argv.push_back(program.data());
    std::vector<std::string> copies = arguments;
    for (auto& a : copies) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (!std::freopen(out_path.c_str(), "w", stdout) || !std::freopen(err_path.c_str(), "w", stderr)) _exit(127);
    ::execv(program.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  CliRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (stdout_path.empty()) {
    std::ifstream out(out_path, std::ios::binary);
    run.out.assign(std::istreambuf_iterator<char>(out), {});
  }
  std::ifstream err(err_path, std::ios::binary);
  run.err.assign(std::istreambuf_iterator<char>(err), {});
  return run;
}

ScratchDirectory::ScratchDirectory() {
  std::string pattern = (std::filesystem::temp_directory_path() / "inertest-test-XXXXXX").string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  if (::mkdtemp(name.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  path_ = name.data();
}

ScratchDirectory::~ScratchDirectory() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::string ScratchDirectory::write(const std::string& name, const std::string& content) const {
  const std::string path = path_ + "/" + name;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream file(path, std::ios::binary);
  file << content;
  return path;
}

bool names_a_seed_file(const std::string& text) {
  static const std::regex seed_name(R"(\b00[0-2]_[0-9a-f]{8}|\b00[0-2]_\w*\.txt|paper (seed )?00[0-2]\b|seeds/)",
                                    std::regex::icase);
  return std::regex_search(text, seed_name);
}

std::string read_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// Built by appending, not by operator+ on a temporary: g++ 12 at -O2 warns (-Warray-bounds, a
// known false positive) on the temporary's small-string buffer.
std::string source_path(const std::string& relative) {
  std::string path = INERTEST_SOURCE_DIR;
  path.append("/").append(relative);
  return path;
}

std::string write_example_with(const ScratchDirectory& directory, const std::string& example, const std::string& name,
                               const std::vector<std::size_t>& columns,
                               const std::function<double(double)>& transform) {
  const std::string text = read_file(source_path(example));
  std::string record = text.substr(0, text.find('\n') + 1);
  for (std::size_t start = record.size(), end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
    std::vector<std::string> cells;
    for (std::size_t from = start, comma;; from = comma + 1) {
      comma = std::min(text.find(',', from), end);
      cells.push_back(text.substr(from, comma - from));
      if (comma == end) break;
    }
    for (std::size_t column : columns) cells[column] = fmt::format("{:.17g}", transform(std::stod(cells[column])));
    record += fmt::format("{}\n", fmt::join(cells, ","));
  }
  return directory.write(name, record);
}

}  // namespace inertest::testing
