// The papers are cited to users as they can find them (core/citations.h), never by the file names
// of the developers' text extractions ("000_746ebd72f166769f.txt", "paper 001", ".../seeds/"): not in
// the --help of any command, nor in the JSON, the text report or the HTML report of a run.
#include <filesystem>
#include <regex>
#include <sstream>

#include "inertest/core/citations.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using testing::names_a_seed_file;
using testing::run_cli;
using testing::source_path;

// The subcommands listed under "Subcommands:" in a --help text.
std::vector<std::string> subcommands(const std::string& help) {
  std::vector<std::string> names;
  std::istringstream lines(help);
  std::string line;
  bool listing = false;
  const std::regex entry(R"(^  ([a-z][a-z0-9-]*)\s)");
  while (std::getline(lines, line)) {
    if (line.rfind("Subcommands:", 0) == 0) {
      listing = true;
      continue;
    }
    std::smatch match;
    if (listing && std::regex_search(line, match, entry)) names.push_back(match[1]);
  }
  return names;
}

TEST(Citations, TheTestCatchesASeedFileName) {
  EXPECT_TRUE(names_a_seed_file("(paper 000_746ebd72f166769f, eqs. 2, 5-16)"));
  EXPECT_TRUE(names_a_seed_file("see shared/seeds/001_f52f57be498b5161.txt"));
  EXPECT_TRUE(names_a_seed_file("(paper 001, HIT)"));
  EXPECT_FALSE(names_a_seed_file(citations::kMisalignmentPaper));
  EXPECT_FALSE(names_a_seed_file(citations::kCentrifugePaper));
}

TEST(Citations, NoCommandHelpNamesASeedFile) {
  const auto root = run_cli({"--help"});
  ASSERT_EQ(root.exit_code, 0) << root.err;
  EXPECT_FALSE(names_a_seed_file(root.out));
  std::vector<std::vector<std::string>> pending;
  for (const auto& name : subcommands(root.out)) pending.push_back({name});
  ASSERT_GT(pending.size(), 20u);
  std::size_t checked = 0;
  while (!pending.empty()) {
    std::vector<std::string> command = pending.back();
    pending.pop_back();
    command.push_back("--help");
    const auto help = run_cli(command);
    command.pop_back();
    ASSERT_EQ(help.exit_code, 0) << command.front() << ": " << help.err;
    EXPECT_FALSE(names_a_seed_file(help.out + help.err)) << command.front() << " --help:\n" << help.out;
    for (const auto& name : subcommands(help.out)) {
      pending.push_back(command);
      pending.back().push_back(name);
    }
    ++checked;
  }
  EXPECT_GT(checked, 22u);  // misalignment's gyro and accelerometer too
  const auto centrifuge = run_cli({"centrifuge", "--help"});
  EXPECT_NE(centrifuge.out.find(citations::kCentrifugePaper), std::string::npos);
  const auto misalignment = run_cli({"misalignment", "--help"});
  EXPECT_NE(misalignment.out.find(citations::kMisalignmentPaper), std::string::npos);
}

// The example plans of the two papers: results.json and the report cite them by title.
TEST(Citations, NoResultOrReportNamesASeedFile) {
  for (const char* plan : {"examples/misalignment/plan.toml", "examples/centrifuge/plan.toml"}) {
    testing::ScratchDirectory scratch;
    const std::string out = scratch.path() + "/out";
    const auto run = run_cli({"run", source_path(plan), "--out", out});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_FALSE(names_a_seed_file(run.out + run.err)) << plan;
    std::string everything;
    for (const auto& entry : std::filesystem::directory_iterator(out)) {
      const std::string text = testing::read_file(entry.path().string());
      EXPECT_FALSE(names_a_seed_file(text)) << entry.path();
      everything += text;
    }
    const bool centrifuge = std::string(plan).find("centrifuge") != std::string::npos;
    const std::string citation = centrifuge ? citations::kCentrifugePaper : citations::kMisalignmentPaper;
    EXPECT_NE(everything.find(citation), std::string::npos) << plan;
  }
  for (const auto& command : std::vector<std::vector<std::string>>{
           {"misalignment", "gyro", source_path("data/misalignment/gyro_table1.csv"), "--scale-factor", "-2.9222"},
           {"misalignment", "accelerometer", source_path("data/misalignment/accelerometer_table2.csv"),
            "--scale-factor", "1.299"},
           {"centrifuge", source_path("data/centrifuge/table3_harmonics.csv"), "--latitude", "45.75"}}) {
    for (const bool json : {false, true}) {
      std::vector<std::string> arguments = command;
      if (json) arguments.push_back("--json");
      const auto run = run_cli(arguments);
      ASSERT_EQ(run.exit_code, 0) << command.front() << ": " << run.err;
      EXPECT_FALSE(names_a_seed_file(run.out + run.err)) << command.front() << (json ? " --json" : "");
    }
  }
}

}  // namespace
}  // namespace inertest
