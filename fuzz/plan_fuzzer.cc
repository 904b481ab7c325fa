// Fuzzes the test-plan loader and runner: any bytes, written as plan.toml into a scratch directory
// that holds the data files the seed plans name, must run or give an inertest::Error; never a
// crash, a hang or another exception (which the CLI would report as an internal error).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"

namespace {

namespace fs = std::filesystem;

class Scratch {
 public:
  Scratch() {
    std::string pattern = (fs::temp_directory_path() / "inertest-plan-fuzz-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) std::abort();
    path_ = pattern;
    const fs::path source(INERTEST_SOURCE_DIR);
    for (const char* file : {"examples/scale_factor/points.csv", "data/centrifuge/table3_harmonics.csv",
                             "data/misalignment/gyro_table1.csv", "data/misalignment/accelerometer_table2.csv"}) {
      fs::copy_file(source / file, path_ / fs::path(file).filename());
    }
  }
  ~Scratch() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const Scratch scratch;
  const std::string plan = (scratch.path() / "plan.toml").string();
  {
    std::ofstream file(plan, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  const std::string out = (scratch.path() / "out").string();
  try {
    inertest::validate_plan(plan);
    inertest::run_campaign(plan, out);
  } catch (const inertest::Error&) {
  }
  return 0;
}
