// The same plan and data give a byte-identical results.json, run after run and whatever the
// number of threads reading the records (INERTEST_THREADS). The processing time stamp is pinned
// with SOURCE_DATE_EPOCH (campaign.cc), the one thing that may differ between two runs.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "inertest/campaign/campaign.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

std::string read_bytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), {}};
}

// results.json of running the plan with the given number of reader threads.
std::string results_with_threads(const std::string& plan, const std::string& out, const char* threads) {
  ::setenv("INERTEST_THREADS", threads, 1);
  ::setenv("SOURCE_DATE_EPOCH", "1700000000", 1);
  run_campaign(plan, out);
  ::unsetenv("INERTEST_THREADS");
  ::unsetenv("SOURCE_DATE_EPOCH");
  return read_bytes(out + "/results.json");
}

// A rest record of 900 000 samples, about 9 MB: above twice the reader's 4 MB minimum chunk, so
// that 2 threads really split it. White noise from a fixed linear congruential generator.
void write_rest_record(const std::string& path) {
  std::string text = "rate\n";
  testing::UniformSequence uniform;
  char line[32];
  for (int i = 0; i < 900000; ++i) {
    const double noise = uniform.next();
    std::snprintf(line, sizeof line, "%.7f\n", 5.0 + 0.01 * noise);
    text += line;
  }
  std::ofstream(path, std::ios::binary) << text;
}

TEST(Determinism, LargeRecordSameBytesWhateverTheThreadCount) {
  testing::ScratchDirectory dir;
  write_rest_record(dir.path() + "/rest.csv");
  ASSERT_GT(std::filesystem::file_size(dir.path() + "/rest.csv"), std::uintmax_t{8} << 20);
  const std::string plan = dir.write("plan.toml",
                                     "[instrument]\nid = \"FOG-9\"\noutput_unit = \"deg/h\"\nsample_rate_hz = 100\n\n"
                                     "[[procedure]]\nkind = \"bias\"\nfile = \"rest.csv\"\ninput = \"deg/h\"\n\n"
                                     "[[procedure]]\nkind = \"allan\"\nfile = \"rest.csv\"\ninput_unit = \"deg/h\"\n");
  const std::string one = results_with_threads(plan, dir.path() + "/one", "1");
  ASSERT_FALSE(one.empty());
  EXPECT_EQ(results_with_threads(plan, dir.path() + "/two", "2"), one);
  EXPECT_EQ(results_with_threads(plan, dir.path() + "/three", "3"), one);
  EXPECT_EQ(results_with_threads(plan, dir.path() + "/again", "2"), one);
}

class ExamplePlans : public ::testing::TestWithParam<const char*> {};

TEST_P(ExamplePlans, SameBytesRunAfterRun) {
  testing::ScratchDirectory dir;
  const std::string plan = testing::source_path(std::string("examples/") + GetParam() + "/plan.toml");
  const std::string one = results_with_threads(plan, dir.path() + "/one", "1");
  ASSERT_FALSE(one.empty());
  EXPECT_EQ(results_with_threads(plan, dir.path() + "/two", "2"), one);
  EXPECT_EQ(results_with_threads(plan, dir.path() + "/again", "1"), one);
}

INSTANTIATE_TEST_SUITE_P(Determinism, ExamplePlans,
                         ::testing::Values("scale_factor", "centrifuge", "misalignment", "bandwidth"));

}  // namespace
}  // namespace inertest
