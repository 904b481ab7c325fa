// The record reader, the `allan` command and the `allan` plan step on small files.
#include "inertest/allan/rate_record.h"

#include <cstring>
#include <nlohmann/json.hpp>

#include "inertest/allan/allan.h"
#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::vector<double> read_all(const RateRecordSource& source) {
  std::vector<double> all;
  read_rate_record(source, [&](std::span<const double> s) { all.insert(all.end(), s.begin(), s.end()); });
  return all;
}

std::string bytes_of(const std::vector<double>& values) {
  std::string bytes(values.size() * 8, '\0');
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

TEST(RateRecord, TextWithHeaderCommentsAndColumns) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("r.csv", "# comment\ntime,rate\n0,1.5\n\n1, 2.5\r\n2,-3e-1\n");
  RateRecordSource source{path, RateRecordFormat::kCsv, ColumnSelector::parse("rate")};
  EXPECT_THAT(read_all(source), ElementsAre(1.5, 2.5, -0.3));
  source.column = ColumnSelector::parse("1");
  EXPECT_THAT(read_all(source), ElementsAre(0, 1, 2));
  const std::string spaced = dir.write("s.txt", "  1 10\n2   20\n");
  EXPECT_THAT(read_all({spaced, RateRecordFormat::kCsv, ColumnSelector::parse("2")}), ElementsAre(10, 20));
  const std::string single = dir.write("one.csv", "4\n5\n6");
  EXPECT_THAT(read_all({single, RateRecordFormat::kCsv, std::nullopt}), ElementsAre(4, 5, 6));
}

TEST(RateRecord, BadTextNamesFileLineAndColumn) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("bad.csv", "t,rate\n0,1\n1,abc\n");
  try {
    read_all({path, RateRecordFormat::kCsv, ColumnSelector::parse("rate")});
    FAIL() << "no error";
  } catch (const Error& e) {
    ASSERT_TRUE(e.location().has_value());
    EXPECT_EQ(e.location()->line, 3u);
    EXPECT_EQ(e.location()->column, 3u);
  }
  EXPECT_THROW(read_all({path, RateRecordFormat::kCsv, std::nullopt}), Error);           // two columns
  EXPECT_THROW(read_all({path, RateRecordFormat::kCsv, ColumnSelector::parse("x")}), Error);  // no such name
  EXPECT_THROW(read_all({path, RateRecordFormat::kCsv, ColumnSelector::parse("3")}), Error);
  const std::string missing = dir.write("short.csv", "1,2\n3\n");
  EXPECT_THROW(read_all({missing, RateRecordFormat::kCsv, ColumnSelector::parse("2")}), Error);
  const std::string empty = dir.write("empty.csv", "# nothing\n");
  EXPECT_THROW(read_all({empty, RateRecordFormat::kCsv, std::nullopt}), Error);
  EXPECT_THROW(parse_rate_record_format("f16"), Error);
}

TEST(RateRecord, BinaryRecords) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("r.f64", bytes_of({1.0, -2.0, 0.5}));
  EXPECT_THAT(read_all({path, RateRecordFormat::kFloat64, std::nullopt}), ElementsAre(1.0, -2.0, 0.5));
  const float narrow[2] = {1.5F, 2.5F};
  const std::string f32 = dir.write("r.f32", std::string(reinterpret_cast<const char*>(narrow), sizeof narrow));
  EXPECT_THAT(read_all({f32, RateRecordFormat::kFloat32, std::nullopt}), ElementsAre(1.5, 2.5));
  const std::string ragged = dir.write("ragged.f64", bytes_of({1.0}) + "abc");
  EXPECT_THROW(read_all({ragged, RateRecordFormat::kFloat64, std::nullopt}), Error);
  const std::string nan = dir.write("nan.f64", bytes_of({1.0, NAN}));
  EXPECT_THROW(read_all({nan, RateRecordFormat::kFloat64, std::nullopt}), Error);
}

std::string white_record(std::size_t n) {
  std::vector<double> y(n);
  std::uint64_t state = 12345;
  for (double& v : y) {  // a small LCG: reproducible without <random> distributions
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    v = 10.0 + static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5;
  }
  return bytes_of(y);
}

TEST(AllanCommand, JsonOfAnF64Record) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("w.f64", white_record(4096));
  const auto run = testing::run_cli({"allan", path, "--rate", "100", "--format", "f64", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["tau"].size(), 11u);  // m = 1 .. 1024 <= 4096/3
  EXPECT_DOUBLE_EQ(json["tau"][0].get<double>(), 0.01);
  for (const char* name : {"adev", "oadev", "mdev", "hdev", "ohdev", "totdev"}) {
    ASSERT_TRUE(json.contains(name)) << name;
    EXPECT_EQ(json[name]["values"].size(), json["tau"].size());
    EXPECT_EQ(json[name]["lower"].size(), json["tau"].size());
    EXPECT_EQ(json[name]["upper"].size(), json["tau"].size());
    EXPECT_EQ(json[name]["unit"], "deg/h");
  }
  for (const char* name : {"quantization", "angle_random_walk", "bias_instability", "rate_random_walk", "rate_ramp"}) {
    EXPECT_TRUE(json["noise"][name].contains("unit")) << name;
  }
  EXPECT_EQ(json["noise"]["angle_random_walk"]["unit"], "deg/sqrt(h)");
  EXPECT_TRUE(json["noise"]["slope_method"].contains("angle_random_walk"));
}

TEST(AllanCommand, ClearErrors) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("w.f64", white_record(64));
  auto run = testing::run_cli({"allan", path, "--rate", "0", "--format", "f64", "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("sample rate"));
  run = testing::run_cli({"allan", path, "--rate", "1", "--format", "f64", "--taus", "fortnightly"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("tau specification"));
  const std::string tiny = dir.write("tiny.f64", white_record(2));
  run = testing::run_cli({"allan", tiny, "--rate", "1", "--format", "f64"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("too few samples"));
}

TEST(AllanStep, RunsFromAPlanWithScaleFactor) {
  testing::ScratchDirectory dir;
  dir.write("w.f64", white_record(3000));
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
