// The default demo campaign's output, made once per ctest run for the tests that read it.
#pragma once

#include <string>

#include "test_util/test_util.h"

namespace inertest::testing {

// Runs `inertest demo --out DIRECTORY --json` (the default campaign) into DIRECTORY, emptied first.
CliRun run_demo_campaign(const std::string& directory);

// The directory that ctest's `demo_campaign` fixture fills (tests/CMakeLists.txt): the test
// Demo.EveryTruthCheckIsWithin runs the campaign into $INERTEST_DEMO_DIRECTORY, and the tests that
// only read its output require the fixture. Empty when the variable is not set (outside ctest).
std::string demo_campaign_fixture_directory();

// The default campaign's output directory (results.json, report.*, lab/) for the tests that read
// it: the fixture's under ctest, so the campaign runs once per ctest run and not once per test;
// outside ctest, a scratch directory the first call fills. Throws when the campaign fails.
const std::string& demo_campaign_directory();

}  // namespace inertest::testing
