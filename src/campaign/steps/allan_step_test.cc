// The `allan` plan step: a binary record with the scale factor, the same figures as the library.
#include <nlohmann/json.hpp>

#include "inertest/allan/allan.h"
#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;

TEST(AllanStep, RunsFromAPlanWithScaleFactor) {
  testing::ScratchDirectory dir;
  dir.write("w.f64", testing::f64_bytes(testing::uniform_noise(10.0, 3000)));
  const std::string plan = dir.write("plan.toml", R"(
[plan]
title = "noise"
[instrument]
id = "FOG-1"
output_unit = "pulse/s"
sample_rate_hz = 100.0
[[procedure]]
kind = "allan"
name = "static noise"
file = "w.f64"
format = "f64"
taus = "decade"
scale_factor = 2.0
)");
  const CampaignSummary summary = run_campaign(plan, dir.path() + "/out");
  const std::string text = summary.results.dump();
  EXPECT_THAT(text, HasSubstr("\"oadev\""));
  EXPECT_THAT(text, HasSubstr("deg/sqrt(h)"));
  // The same record through the library: raw / 2 (deg/s) * 3600 = deg/h.
  AllanOptions options;
  options.sample_rate_hz = 100.0;
  options.taus = "decade";
  options.scale = 1800.0;
  const AllanResult direct = allan_variance_of_file({dir.path() + "/w.f64", RateRecordFormat::kFloat64, std::nullopt}, options);
  EXPECT_THAT(text, HasSubstr(nlohmann::json(direct.curves.at(Estimator::kOadev).values[0]).dump()));

  const std::string bad = dir.write("bad.toml", R"(
[plan]
title = "noise"
[instrument]
id = "FOG-1"
[[procedure]]
kind = "allan"
name = "static noise"
file = "w.f64"
format = "f64"
)");
  EXPECT_THROW(validate_plan(bad), Error);  // no sample rate anywhere
}

}  // namespace
}  // namespace inertest
