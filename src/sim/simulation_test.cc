#include "inertest/sim/simulation.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

#include "inertest/core/error.h"
#include "inertest/demo/demo.h"
#include "test_util/demo_campaign.h"

namespace inertest::sim {
namespace {

using inertest::testing::ScratchDirectory;

const char* kSmallPlan = R"(seed = 7
[site]
latitude_deg = 45.75
[gyro]
sample_rate_hz = 100
angle_random_walk_deg_rt_h = 0.002
bias_instability_deg_h = 0.003
rate_random_walk_deg_h_rt_h = 0.004
bias_deg_h = 0.02
nonlinearity_ppm = [0, 8]
asymmetry_ppm = 6
bandwidth_hz = 300
delay_ms = 0.8
[gyro.drift]
DI = 0.01
[rate_table]
rate_error_ppm = 0.5
[[test]]
kind = "scale_factor"
rates_deg_s = [1, 10, 100]
seconds_per_rate = 5
static_seconds = 5
[[test]]
kind = "bias"
seconds = 60
[[test]]
kind = "centrifuge"
revolutions = 2
)";

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(SimSimulate, SameSeedGivesByteIdenticalFiles) {
  ScratchDirectory a;
  ScratchDirectory b;
  const SimulationSummary first = simulate_text(kSmallPlan, "small", a.path() + "/out");
  const SimulationSummary second = simulate_text(kSmallPlan, "small", b.path() + "/out");
  ASSERT_EQ(first.written_files.size(), second.written_files.size());
  ASSERT_GT(first.written_files.size(), 10u);
  for (std::size_t i = 0; i < first.written_files.size(); ++i) {
    const auto relative = std::filesystem::relative(first.written_files[i], a.path());
    EXPECT_EQ(relative, std::filesystem::relative(second.written_files[i], b.path()));
    EXPECT_EQ(read(first.written_files[i]), read(second.written_files[i])) << relative;
  }
  std::string other = kSmallPlan;
  other.replace(other.find("seed = 7"), 8, "seed = 8");
  ScratchDirectory c;
  simulate_text(other, "small", c.path() + "/out");
  EXPECT_NE(read(a.path() + "/out/bias.f64"), read(c.path() + "/out/bias.f64"));
}

TEST(SimSimulate, WritesRecordsPlanAndTruth) {
  ScratchDirectory dir;
  const SimulationSummary summary = simulate_text(kSmallPlan, "small", dir.path());
  EXPECT_TRUE(std::filesystem::exists(dir.path() + "/scale_factor/points.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() + "/centrifuge/samples.csv"));
  const std::string plan = read(summary.plan_path);
  EXPECT_NE(plan.find("kind = \"scale_factor\""), std::string::npos);
  EXPECT_NE(plan.find("nominal_scale_factor = 36000"), std::string::npos);
  EXPECT_EQ(summary.truth.at("seed"), 7);
  EXPECT_EQ(summary.truth.at("gyro").at("drift").at("DI"), 0.01);
  bool has_scale_factor = false;
  for (const auto& t : summary.truth.at("truth")) {
    if (t.at("quantity") == "scale factor") {
      has_scale_factor = true;
      EXPECT_EQ(t.at("figure"), "scale_factor");
      EXPECT_GT(t.at("tolerance").get<double>(), 0.0);
    }
  }
  EXPECT_TRUE(has_scale_factor);
  // The points table: 2 static runs and each rate both ways.
  const std::string points = read(dir.path() + "/scale_factor/points.csv");
  EXPECT_EQ(std::count(points.begin(), points.end(), '\n'), 2 + 2 + 6);
}

// One plan, a batch: the seed, the instrument id and the test date come from the options.
TEST(SimSimulate, SeedInstrumentAndDateOverrideThePlan) {
  ScratchDirectory a;
  ScratchDirectory b;
  SimulationOptions options;
  options.seed = 8;
  options.instrument_id = "FOG-0417";
  options.date = "2026-03-04";
  const SimulationSummary overridden = simulate_text(kSmallPlan, "small", a.path(), options);
  EXPECT_EQ(overridden.truth.at("seed"), 8);
  const std::string plan = read(overridden.plan_path);
  EXPECT_NE(plan.find("id = \"FOG-0417\""), std::string::npos) << plan;
  EXPECT_NE(plan.find("date = \"2026-03-04\""), std::string::npos) << plan;
  // The same records as the plan with seed = 8 written in it.
  std::string other = kSmallPlan;
  other.replace(other.find("seed = 7"), 8, "seed = 8");
  simulate_text(other, "small", b.path());
  EXPECT_EQ(read(a.path() + "/bias.f64"), read(b.path() + "/bias.f64"));

  // The id is held to the rules run holds a plan's id to: "LAB2/FOG \"1\"" is one (written escaped),
  // ".." is not.
  SimulationOptions quoted;
  quoted.instrument_id = "LAB2/FOG \"1\"";
  const std::string quoted_plan = read(simulate_text(kSmallPlan, "small", a.path() + "/q", quoted).plan_path);
  EXPECT_NE(quoted_plan.find("id = \"LAB2/FOG \\\"1\\\"\"\n"), std::string::npos) << quoted_plan;
  // The title, a TOML string of the written plan, keeps a newline escaped (run refused the plan).
  std::string titled = kSmallPlan;
  titled.replace(titled.find("seed = 7\n"), 9, "seed = 7\n[plan]\ntitle = \"FOG\\nbatch \\\"7\\\"\"\n");
  const std::string titled_plan = read(simulate_text(titled, "small", a.path() + "/t").plan_path);
  EXPECT_NE(titled_plan.find("title = \"FOG\\u000Abatch \\\"7\\\"\"\n"), std::string::npos) << titled_plan;
  SimulationOptions bad_id;
  bad_id.instrument_id = "..";
  EXPECT_THROW(simulate_text(kSmallPlan, "small", a.path() + "/x", bad_id), Error);
  SimulationOptions bad_date;
  bad_date.date = "04/03/2026";
  EXPECT_THROW(simulate_text(kSmallPlan, "small", a.path() + "/y", bad_date), Error);
  bad_date.date = "2024-02-30";  // written into the plan, then refused by run
  EXPECT_THROW(simulate_text(kSmallPlan, "small", a.path() + "/y", bad_date), Error);
}

void expect_plan_error(const std::string& text, const std::string& fragment, std::size_t line) {
  ScratchDirectory dir;
  try {
    simulate_text(text, "bad.toml", dir.path() + "/out");
    ADD_FAILURE() << "no error for: " << fragment;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    ASSERT_TRUE(e.location().has_value()) << e.what();
    EXPECT_EQ(e.location()->line, line) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path() + "/out")) << "files written despite the error";
}

TEST(SimSimulate, BadPlansNameTheLineAndWriteNothing) {
  expect_plan_error("seed = 1\n[gyro]\n[[test]]\nkind = \"bias\"\nsecnds = 5\n", "secnds", 5);
  expect_plan_error("seed = 1\n[gyro]\n[[test]]\nkind = \"wobble\"\n", "cannot be simulated", 4);
  expect_plan_error("seed = 1\n[gyro]\nbandwidth_hz = -3\n[[test]]\nkind = \"bias\"\n", "bandwidth_hz", 2);
  expect_plan_error("seed = 1\n[gyro]\n[[test]]\nkind = \"bias\"\nseconds = \"long\"\n", "must be a number", 5);
  expect_plan_error("seed = 1.5\n[gyro]\n[[test]]\nkind = \"bias\"\n", "whole number", 1);
  // A step name is a directory and a plan string: no control character (a newline broke the plan).
  expect_plan_error("seed = 1\n[gyro]\n[[test]]\nkind = \"bias\"\nname = \"a\\nb\"\n", "plain file name", 5);
  expect_plan_error("seed = 1\n[gyro]\n[[test]]\nkind = \"scale_factor\"\nrates_deg_s = [1, -2]\n", "positive", 5);
  expect_plan_error("seed = 1\n[gyro]\n[gyro.drift]\nDF = 1\n[[test]]\nkind = \"bias\"\n", "bias_deg_h", 4);
  expect_plan_error("seed = 1\n[gyro]\n[[test]]\nkind = \"bias\"\n[[test]]\nkind = \"bias\"\n", "names two tests", 5);
  expect_plan_error("seed = 1\n[[test]]\nkind = \"bias\"\n", "missing [gyro]", 1);
  expect_plan_error("seed = 1\n[gyro\n", "", 2);
  expect_plan_error("seed = 1\n[gyro]\n[[test]]\nkind = \"bias\"\nseconds = inf\n", "must be a finite number", 5);
}

// Records larger than the simulator makes are the plan's mistake (they were internal errors:
// std::bad_alloc, vector::reserve); the simulation plan is never overwritten by the lab it makes.
TEST(SimSimulate, ThePlansMistakesAboutSizeAndPlaceAreErrors) {
  ScratchDirectory dir;
  for (const char* size : {"[gyro]\n[[test]]\nkind = \"bias\"\nseconds = 1e12\n",
                           "[gyro]\n[[test]]\nkind = \"bias\"\nseconds = 1e20\n",
                           "[gyro]\nsample_rate_hz = 1e12\n[[test]]\nkind = \"bias\"\n"}) {
    try {
      simulate_text(std::string("seed = 1\n") + size, "big.toml", dir.path() + "/out");
      ADD_FAILURE() << "no error for " << size;
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr("samples, more than the simulator makes in one record (1e+09)")) << size;
      EXPECT_THAT(e.what(), ::testing::StartsWith("big.toml: a record of ")) << size;
    }
  }
  const std::string plan = dir.write("lab/plan.toml", kSmallPlan);
  try {
    simulate(plan, dir.path() + "/lab");
    ADD_FAILURE() << "the lab replaced its plan";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("the simulation would write its plan.toml over this plan"));
  }
  EXPECT_EQ(testing::read_file(plan), kSmallPlan);
  // The command line's seed is held to the plan's rule: -1 and 1e23 made one lab (2^64 - 1).
  for (const char* seed : {"-1", "1e23", "2.5"}) {
    const auto run = testing::run_cli({"simulate", plan, "--out", dir.path() + "/seeded", "--seed", seed});
    EXPECT_EQ(run.exit_code, 2) << seed;
    EXPECT_THAT(run.err, ::testing::HasSubstr("must be a whole number from 0 to 2^53")) << seed;
  }
  const auto unnamed = testing::run_cli({"simulate", plan, "--out", dir.path() + "/unnamed", "--instrument", ""});
  EXPECT_EQ(unnamed.exit_code, 2);
  EXPECT_THAT(unnamed.err, ::testing::HasSubstr("--instrument is empty"));
}

// [test.limits] of a simulation plan becomes [procedure.limits] of the processing plan it writes,
// in the plan's order, figure names and JSON pointers quoted; a bad limit is the simulation plan's error.
TEST(SimSimulate, TestLimitsBecomeTheStepsLimits) {
  ScratchDirectory dir;
  simulate_text("seed = 1\n[gyro]\n[[test]]\nkind = \"polarity\"\n[test.limits]\nsign = { min = 0.5 }\n"
                "\"/a/0\" = { min = -1.5, max = 2, unit = \"deg/h\" }\n",
                "limits.toml", dir.path() + "/out");
  EXPECT_NE(read(dir.path() + "/out/plan.toml")
                .find("[procedure.limits]\n\"sign\" = { min = 0.5 }\n\"/a/0\" = { min = -1.5, max = 2, unit = \"deg/h\" }\n"),
            std::string::npos)
      << read(dir.path() + "/out/plan.toml");
  const std::string test = "seed = 1\n[gyro]\n[[test]]\nkind = \"polarity\"\n[test.limits]\n";
  expect_plan_error(test + "sign = { unit = \"1\" }\n", "a limit needs 'min', 'max' or both", 6);
  expect_plan_error(test + "sign = { max = 1, unti = \"1\" }\n", "unti", 6);
  expect_plan_error(test + "sign = { max = 1, unit = \"furlong\" }\n", "furlong", 6);
}

TEST(DemoPlan, BuiltInPlanMatchesTheExample) {
  EXPECT_EQ(demo_simulation_plan(), read(inertest::testing::source_path("examples/demo/simulation.toml")));
}

// Under ctest this test is the `demo_campaign` fixture: the tests that read the campaign's output
// (testing::demo_campaign_directory) read what it wrote.
TEST(Demo, EveryTruthCheckIsWithin) {
  ScratchDirectory dir;
  const std::string fixture = inertest::testing::demo_campaign_fixture_directory();
  const std::string out = fixture.empty() ? dir.path() + "/demo" : fixture;
  const auto run = inertest::testing::run_demo_campaign(out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto results = nlohmann::json::parse(read(out + "/results.json"));
  EXPECT_EQ(results, nlohmann::json::parse(run.out));
  ASSERT_GE(results.at("truth_check").size(), 3u);
  for (const auto& c : results.at("truth_check")) {
    EXPECT_TRUE(c.at("within").get<bool>()) << c.dump();
    EXPECT_GT(c.at("tolerance").get<double>(), 0.0) << c.dump();
  }
  EXPECT_TRUE(std::filesystem::exists(out + "/report.txt"));
  EXPECT_TRUE(std::filesystem::exists(out + "/lab/truth.json"));
}

}  // namespace
}  // namespace inertest::sim
