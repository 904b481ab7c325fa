#include "inertest/demo/fleet_demo.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "inertest/archive/archive.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

// The batch: 12 instruments × 3 days archived, the pages written; the out-of-specification units
// built into the batch fail their campaigns; a second run adds nothing (same content).
TEST(FleetDemo, ArchivesTheBatchAndWritesThePages) {
  testing::ScratchDirectory dir;
  const FleetDemoSummary summary = run_fleet_demo(dir.path());
  EXPECT_EQ(summary.campaigns_added, 36u);
  ASSERT_EQ(summary.pages.size(), 13u);
  EXPECT_EQ(summary.pages.front(), dir.path() + "/fleet.html");
  for (const auto& page : summary.pages) EXPECT_TRUE(std::filesystem::exists(page)) << page;

  const auto store = archive::open_archive(dir.path() + "/archive.sqlite");
  EXPECT_EQ(store->list(std::nullopt).size(), 36u);
  EXPECT_EQ(store->figures(true), (std::vector<std::string>{"bias/bias", "scale_factor/scale_factor"}));
  // B05 (+80 ppm), B10 (0.09 deg/h) and B12 (−90 ppm) are out of specification on every day.
  for (const char* id : {"FOG-B05", "FOG-B10", "FOG-B12"}) {
    for (const auto& campaign : store->list(std::string(id))) EXPECT_EQ(campaign.verdict, "FAIL") << id;
  }
  for (const auto& campaign : store->list(std::string("FOG-B01"))) EXPECT_EQ(campaign.verdict, "PASS");
  // B08 drifts +6 ppm per test: the history shows it (each point has σ ≈ 0.001 pulse/s/(deg/s)).
  const auto drift = store->history("FOG-B08", "scale_factor/scale_factor");
  ASSERT_EQ(drift.points.size(), 3u);
  ASSERT_TRUE(drift.points[0].value && drift.points[2].value);
  EXPECT_NEAR(*drift.points[2].value - *drift.points[0].value, 2 * 6e-6 * 36000.0, 0.006);  // 4 sigma of the difference
  ASSERT_EQ(summary.fleet.size(), 2u);
  EXPECT_EQ(summary.fleet[0]["instruments"].size(), 12u);

  EXPECT_EQ(run_fleet_demo(dir.path()).campaigns_added, 0u);
}

}  // namespace
}  // namespace inertest
