#include "test_util/demo_campaign.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace inertest::testing {

CliRun run_demo_campaign(const std::string& directory) {
  std::filesystem::remove_all(directory);
  return run_cli({"demo", "--out", directory, "--json"});
}

std::string demo_campaign_fixture_directory() {
  const char* directory = std::getenv("INERTEST_DEMO_DIRECTORY");
  return directory == nullptr ? std::string() : std::string(directory);
}

const std::string& demo_campaign_directory() {
  static const ScratchDirectory scratch;
  static const std::string directory = [] {
    const std::string fixture = demo_campaign_fixture_directory();
    if (!fixture.empty() && std::filesystem::exists(fixture + "/results.json")) return fixture;
    const std::string made = scratch.path() + "/demo";
    const CliRun run = run_demo_campaign(made);
    if (run.exit_code != 0) throw std::runtime_error("inertest demo failed: " + run.err);
    return made;
  }();
  return directory;
}

}  // namespace inertest::testing
