// The `allan` plan step: a binary record with the scale factor, the same figures as the library.
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/allan/allan.h"
#include "inertest/allan/allan_channels.h"
#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A plan of one allan step on w.f64, 3000 samples of white noise at 10 Hz written beside it; `keys`
// (TOML lines) follow the step's file and format, from line 11 on.
std::string error_of_validation(const std::string& plan) {
  try {
    validate_plan(plan);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

std::string white_noise_plan(testing::ScratchDirectory& dir, const std::string& name, const std::string& keys) {
  dir.write("w.f64", testing::f64_bytes(testing::uniform_noise(10.0, 3000)));
  return dir.write(name, R"(
[plan]
title = "noise"
[instrument]
id = "FOG-1"
sample_rate_hz = 10.0
[[procedure]]
kind = "allan"
file = "w.f64"
format = "f64"
)" + keys + "\n");
}

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
  const AllanResult direct = allan_variance_of_file({dir.path() + "/w.f64", RateRecordFormat::kBinary, std::nullopt}, options);
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

// A step that gives neither input_unit nor scale_factor reads the record as its [instrument] says:
// a MEMS gyro's deg/s output is in deg/s, a FOG's pulse/s divided by its nominal scale factor
// (both were read as deg/h: the angle random walk 60 and 10 times off, and a limit passed). The
// step's own key wins; the columns of an IMU record keep their own units.
TEST(AllanStep, TakesTheInstrumentsOutputUnitOrNominalScaleFactor) {
  testing::ScratchDirectory dir;
  dir.write("w.f64", testing::f64_bytes(testing::uniform_noise(10.0, 3000)));
  const auto oadev_of_plan = [&](const std::string& instrument, const std::string& keys) {
    const std::string plan = dir.write("plan.toml", "[plan]\ntitle = \"noise\"\n[instrument]\nid = \"G-1\"\n"
                                                    "sample_rate_hz = 10.0\n" + instrument +
                                                    "[[procedure]]\nkind = \"allan\"\nname = \"noise\"\n"
                                                    "file = \"w.f64\"\nformat = \"f64\"\ntaus = \"decade\"\n" + keys);
    const nlohmann::json result = run_campaign(plan, dir.path() + "/out").results.at("procedures").at(0).at("result");
    return std::pair(result.at("oadev").at("values").at(0).get<double>(), result.at("oadev").at("unit").get<std::string>());
  };
  const auto oadev_direct = [&](double scale) {
    AllanOptions options;
    options.sample_rate_hz = 10.0;
    options.taus = "decade";
    options.scale = scale;
    return allan_variance_of_file({dir.path() + "/w.f64", RateRecordFormat::kBinary, std::nullopt}, options)
        .curves.at(Estimator::kOadev).values[0];
  };
  const auto [in_deg_s, unit_deg_s] = oadev_of_plan("output_unit = \"deg/s\"\n", "");
  EXPECT_DOUBLE_EQ(in_deg_s, oadev_direct(1.0));  // deg/s samples, the curve in deg/s (the noise terms converted)
  EXPECT_EQ(unit_deg_s, "deg/s");
  EXPECT_EQ(oadev_of_plan("", "").second, "deg/h");
  EXPECT_DOUBLE_EQ(oadev_of_plan("output_unit = \"pulse/s\"\nnominal_scale_factor = 36000.0\n", "").first,
                   oadev_direct(0.1));  // pulse/s / 36000 (pulse/s)/(deg/s) * 3600 = deg/h
  // Pulses counted per sample interval: times 10 Hz, pulse/s.
  EXPECT_DOUBLE_EQ(oadev_of_plan("output_unit = \"pulse\"\nnominal_scale_factor = 36000.0\n", "").first,
                   oadev_direct(1.0));
  // The step's keys win over the instrument's; an accelerometer's nominal scale factor is per g,
  // no gyro's K: not taken; neither is the dimensionless default output unit.
  EXPECT_DOUBLE_EQ(oadev_of_plan("output_unit = \"deg/s\"\n", "input_unit = \"deg/h\"\n").first, oadev_direct(1.0));
  EXPECT_DOUBLE_EQ(oadev_of_plan("output_unit = \"pulse/s\"\nnominal_scale_factor = 36000.0\n", "scale_factor = 2.0\n").first,
                   oadev_direct(1800.0));
  EXPECT_DOUBLE_EQ(oadev_of_plan("output_unit = \"pulse/s\"\nnominal_scale_factor = 36000.0\n", "input_unit = \"deg/h\"\n").first,
                   oadev_direct(1.0));
  EXPECT_DOUBLE_EQ(oadev_of_plan("type = \"accelerometer\"\noutput_unit = \"V\"\nnominal_scale_factor = 2.0\n", "").first,
                   oadev_direct(1.0));
  EXPECT_DOUBLE_EQ(oadev_of_plan("nominal_scale_factor = 36000.0\n", "").first, oadev_direct(0.1));
  EXPECT_DOUBLE_EQ(oadev_of_plan("", "").first, oadev_direct(1.0));
  // A record that stores its unit (HDF5 units) keeps it: the instrument's deg/s contradicted its
  // deg/h, and its K was refused as scaling a stored rate, with no key of the step to blame.
  const std::string h5 = testing::source_path("data/lab_formats/record.h5");
  for (const std::string& instrument : {std::string("output_unit = \"deg/s\"\n"),
                                        std::string("output_unit = \"pulse/s\"\nnominal_scale_factor = 36000.0\n")}) {
    const std::string plan = dir.write("h5.toml", "[plan]\ntitle = \"noise\"\n[instrument]\nid = \"G-1\"\n" + instrument +
                                                      "[[procedure]]\nkind = \"allan\"\nfile = \"" + h5 +
                                                      "\"\ncolumn = \"imu/gyro_x\"\ntaus = \"decade\"\n");
    const nlohmann::json result = run_campaign(plan, dir.path() + "/h5").results.at("procedures").at(0).at("result");
    EXPECT_EQ(result.at("input_unit"), "deg/h") << instrument;
    EXPECT_EQ(result.at("oadev").at("unit"), "deg/h") << instrument;
  }
}

// fit_range = [tau_min, tau_max] sets the taus of the eq. (30) fit (a list of numbers, as Python's
// fit_range=(0.2, 25.6); the command line writes it --fit-range 0.2:25.6).
TEST(AllanStep, FitRangeKey) {
  testing::ScratchDirectory dir;
  const auto plan_with = [&](const std::string& name, const std::string& range) {
    return white_noise_plan(dir, name, "fit_range = " + range);
  };
  const CampaignSummary summary = run_campaign(plan_with("plan.toml", "[0.2, 25.6]"), dir.path() + "/out");
  const nlohmann::json& fit = summary.results["procedures"][0]["result"]["noise"]["fit"];
  EXPECT_EQ(fit["fit_range"]["chosen_by"], "user");
  EXPECT_DOUBLE_EQ(fit["fit_range"]["tau_min_s"].get<double>(), 0.2);
  try {
    validate_plan(plan_with("bad.toml", "[5.0]"));
    ADD_FAILURE() << "a one-element fit range was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.toml:11"));
    EXPECT_THAT(e.what(), HasSubstr("[tau_min, tau_max]"));
  }
  EXPECT_THROW(validate_plan(plan_with("bad2.toml", "[5.0, 1.0]")), Error);
}

// A spec limit on a noise term the fit could not identify (R of white noise) is judged by its
// upper bound: the term (never negative) lies in [0, bound], so a maximum above the bound passes,
// one below it fails, and a minimum passes only at or below 0 (a range of 0 to 0.01 failed).
TEST(AllanStep, LimitOnAnUnidentifiedTermUsesItsUpperBound) {
  testing::ScratchDirectory dir;
  const auto verdict_for = [&](const std::string& limit) {
    const std::string plan =
        white_noise_plan(dir, "plan.toml", "input_unit = \"deg/h\"\n[procedure.limits]\n\"/noise/rate_ramp\" = " + limit);
    const CampaignSummary summary = run_campaign(plan, dir.path() + "/out");
    const nlohmann::json& b = summary.results["procedures"][0]["result"]["noise"]["rate_ramp"];
    EXPECT_EQ(b["identified"], false);
    return std::pair{summary.results["verdicts"][0], b["upper_bound"].get<double>()};
  };
  const auto [loose, bound] = verdict_for("{ max = 1e3 }");
  EXPECT_TRUE(loose["pass"].get<bool>());
  EXPECT_EQ(loose["identified"], false);
  EXPECT_DOUBLE_EQ(loose["value"].get<double>(), bound);
  EXPECT_FALSE(verdict_for("{ max = " + std::to_string(bound / 2.0) + " }").first["pass"].get<bool>());
  EXPECT_TRUE(verdict_for("{ min = 0 }").first["pass"].get<bool>());
  EXPECT_TRUE(verdict_for("{ min = 0, max = 1e3 }").first["pass"].get<bool>());
  EXPECT_FALSE(verdict_for("{ min = 1e-12 }").first["pass"].get<bool>());
  EXPECT_FALSE(verdict_for("{ min = 0, max = " + std::to_string(bound / 2.0) + " }").first["pass"].get<bool>());
}

// columns (issue 19): every channel of a record in one step, each with its unit; the result is the
// library's {"channels": ...} for the same file.
TEST(AllanStep, ColumnsAnalyseEveryChannelWithItsUnit) {
  testing::ScratchDirectory dir;
  const std::vector<double> a = testing::uniform_noise(1.0, 2000);
  const std::vector<double> b = testing::uniform_noise(0.01, 2000);
  std::string text = "t,gx,ax\n";
  for (std::size_t i = 0; i < a.size(); ++i) text += fmt::format("{},{:.17g},{:.17g}\n", i, a[i], b[(i * 7) % b.size()]);
  dir.write("imu.csv", text);
  const std::string plan_text = R"(
[plan]
title = "IMU noise"
[instrument]
id = "IMU-1"
output_unit = "deg/s"
sample_rate_hz = 100.0
[[procedure]]
kind = "allan"
name = "IMU at rest"
file = "imu.csv"
columns = ["gx", "ax"]
input_unit = "deg/s,ax=m/s^2"
taus = "decade"
)";
  const std::string plan = dir.write("plan.toml", plan_text);
  const CampaignSummary summary = run_campaign(plan, dir.path() + "/out");
  const nlohmann::json& result = summary.results["procedures"][0]["result"];
  AllanOptions options;
  options.sample_rate_hz = 100.0;
  options.taus = "decade";
  const AllanChannels expected = allan_variance_of_channels_in_file(
      RateRecordSource{dir.path() + "/imu.csv", RateRecordFormat::kAuto, std::nullopt},
      {ColumnSelector::parse("gx"), ColumnSelector::parse("ax")}, "deg/s,ax=m/s^2", options, false);
  EXPECT_EQ(result, expected.to_json());
  EXPECT_EQ(result["channels"]["ax"]["noise"]["velocity_random_walk"]["unit"], "m/s/sqrt(h)");
  const std::string both = dir.write("both.toml", R"(
[plan]
title = "IMU noise"
[instrument]
id = "IMU-1"
output_unit = "deg/s"
sample_rate_hz = 100.0
[[procedure]]
kind = "allan"
name = "IMU at rest"
file = "imu.csv"
column = "gx"
columns = ["gx", "ax"]
)");
  try {
    run_campaign(both, dir.path() + "/out2");
    FAIL() << "column and columns together were accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("column and columns exclude each other"));
  }
  // A unit for a channel not asked for is said in the plan's words (the key, not the CLI's flag).
  std::string wrong_unit = plan_text;
  wrong_unit.replace(wrong_unit.find("ax=m/s^2"), 8, "az=m/s^2");
  try {
    run_campaign(dir.write("wrong_unit.toml", wrong_unit), dir.path() + "/out3");
    FAIL() << "a unit for a channel not asked for was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("input_unit names 'az', which is not a channel asked for (gx, ax)"));
    EXPECT_THAT(e.what(), Not(HasSubstr("--input-unit")));
  }
}

// A plan takes every parameter of the command under its snake_case name: the estimators, and the
// export, whose relative FILE lands beside results.json (not in the working directory).
TEST(AllanStep, EstimatorsAndExportAsTheCommandTakesThem) {
  testing::ScratchDirectory dir;
  const std::string plan =
      white_noise_plan(dir, "plan.toml", "estimators = \"oadev,mdev\"\nexport = [\"json\", \"filter.json\"]");
  const CampaignSummary summary = run_campaign(plan, dir.path() + "/out");
  const nlohmann::json& result = summary.results["procedures"][0]["result"];
  EXPECT_TRUE(result.contains("oadev") && result.contains("mdev"));
  EXPECT_FALSE(result.contains("adev") || result.contains("totdev"));
  std::ifstream exported(dir.path() + "/out/filter.json");
  ASSERT_TRUE(exported.good()) << "the export is not beside results.json";
  const nlohmann::json filter = nlohmann::json::parse(exported);
  // The command that gives these numbers again, the plan's keys as its options.
  EXPECT_EQ(filter.at("command"), "inertest allan " + dir.path() +
                                      "/w.f64 --format f64 --rate 10.0 --estimators oadev,mdev --export json filter.json");
  EXPECT_EQ(filter.at("sensors").at("rate").at("white_noise_density").at("unit"), "rad/s/sqrt(Hz)");
  EXPECT_FALSE(std::ifstream("filter.json").good());
  // A bad value is an error at its key, before anything runs.
  for (const std::string keys :
       {"estimators = \"oadev,foo\"", "export = [\"yaml\", \"filter.yaml\"]", "column = \"0\"", "columns = []",
        "columns = [\"gx\", \"gx\"]", "fit_range = [10, 0.1]", "taus = \"foo\"", "input_unit = \"furlong\"",
        "input_unit = \"deg/s,ax=m/s^2\"", "column = \"2\""}) {
    try {
      validate_plan(white_noise_plan(dir, "bad.toml", keys));
      ADD_FAILURE() << keys << " was accepted";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("bad.toml:11")) << keys;
    }
  }

  // Two exports of one name (the first was silently replaced), or one named as the run's own files.
  const std::string twice = white_noise_plan(dir, "twice.toml",
                                             "export = [\"json\", \"noise.json\"]\n"
                                             "[[procedure]]\nkind = \"allan\"\nname = \"second\"\nfile = \"w.f64\"\n"
                                             "format = \"f64\"\nexport = [\"json\", \"./noise.json\"]");
  EXPECT_THAT(error_of_validation(twice), HasSubstr("twice.toml:17:10: plan.procedure[2]: 'export' names "
                                                    "'./noise.json', which the procedure at "));
  EXPECT_THAT(error_of_validation(white_noise_plan(dir, "own.toml", "export = [\"json\", \"results.json\"]")),
              HasSubstr("own.toml:11:10: plan.procedure[1]: 'export' names 'results.json', which the run writes itself"));

  // A later step that fails takes the output directory and the earlier export with it: no partial
  // output.
  std::vector<double> with_nan = testing::uniform_noise(10.0, 3000);
  with_nan[1500] = std::numeric_limits<double>::quiet_NaN();
  dir.write("nan.f64", testing::f64_bytes(with_nan));
  const std::string failing = white_noise_plan(dir, "failing.toml",
                                               "export = [\"json\", \"filter.json\"]\n"
                                               "[[procedure]]\nkind = \"allan\"\nname = \"second\"\nfile = \"nan.f64\"\n"
                                               "format = \"f64\"");
  EXPECT_THROW(run_campaign(failing, dir.path() + "/failed"), Error);
  EXPECT_FALSE(std::filesystem::exists(dir.path() + "/failed"));
  // Into the directory of an earlier run: its files stay as they were, and nothing is added.
  EXPECT_THROW(run_campaign(failing, dir.path() + "/out"), Error);
  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path() + "/out")) {
    left.push_back(entry.path().filename().string());
  }
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{".inertest-written", "filter.json", "results.json"}));
  std::ifstream earlier(dir.path() + "/out/filter.json");
  EXPECT_EQ(nlohmann::json::parse(earlier), filter);
}

// A plan run into its own directory whose export names the step's record: an error at the export
// before anything runs, the record and the directory as they were (the export replaced the data it
// was made from).
TEST(AllanStep, AnExportOntoTheStepsRecordIsRefused) {
  testing::ScratchDirectory dir;
  const std::string plan = white_noise_plan(dir, "plan.toml", "export = [\"json\", \"w.f64\"]");
  const std::string before = testing::read_file(dir.path() + "/w.f64");
  try {
    run_campaign(plan, dir.path());
    ADD_FAILURE() << "the run replaced its record";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("plan.toml:11:10: the run would write 'w.f64' over '" + dir.path() +
                                    "/w.f64', which the plan reads (at " + dir.path() + "/plan.toml:9:8)"));
  }
  EXPECT_EQ(testing::read_file(dir.path() + "/w.f64"), before);
  EXPECT_FALSE(std::filesystem::exists(dir.path() + "/results.json"));
  EXPECT_EQ(run_campaign(plan, dir.path() + "/elsewhere").written_files.size(), 2u);  // results.json, w.f64
  // Nor over the plan itself, named by the export or as results.json.
  const std::string over_plan = white_noise_plan(dir, "results.json", "export = [\"json\", \"filter.json\"]");
  EXPECT_THROW(run_campaign(over_plan, dir.path()), Error);
  std::filesystem::remove(over_plan);
  const std::string named = white_noise_plan(dir, "own.toml", "export = [\"json\", \"own.toml\"]");
  const std::string plan_text = testing::read_file(named);
  EXPECT_THROW(run_campaign(named, dir.path()), Error);
  EXPECT_EQ(testing::read_file(named), plan_text);
}

// The same plan run again into its directory: what its last run exported and this one does not (the
// plan no longer names it) is removed, and said; not a file the plan now reads, nor one edited since.
// Another campaign's directory (another instrument, or the same one's results of another plan file)
// is refused before anything runs, its files as they were.
TEST(AllanStep, ARunReplacesItsOwnCampaignAndNoOther) {
  testing::ScratchDirectory dir;
  const std::string out = dir.path() + "/out";
  const std::string plan = white_noise_plan(dir, "plan.toml", "export = [\"json\", \"filter.json\"]");
  run_campaign(plan, out);
  ASSERT_TRUE(std::filesystem::exists(out + "/filter.json"));
  const CampaignSummary again = run_campaign(white_noise_plan(dir, "plan.toml", "export = [\"json\", \"noise.json\"]"), out);
  EXPECT_FALSE(std::filesystem::exists(out + "/filter.json"));
  EXPECT_TRUE(std::filesystem::exists(out + "/noise.json"));
  EXPECT_EQ(again.removed_files, std::vector<std::string>{out + "/filter.json"});
  const auto list = nlohmann::json::parse(testing::read_file(out + "/.inertest-written"));
  EXPECT_EQ(list["plan"], std::filesystem::weakly_canonical(plan).string());
  ASSERT_EQ(list["files"].size(), 2u);
  EXPECT_EQ(list["files"][1]["path"], "noise.json");
  EXPECT_EQ(list["files"][1]["size"], std::filesystem::file_size(out + "/noise.json"));
  const auto cli = testing::run_cli({"run", plan, "--out", out});
  EXPECT_EQ(cli.exit_code, 0) << cli.err;
  EXPECT_THAT(cli.err, Not(HasSubstr("removed")));
  // An export edited since stays, and so does a file listed as the last run's that the plan now reads.
  dir.write("out/noise.json", "edited by hand");
  std::filesystem::copy_file(dir.path() + "/w.f64", out + "/w.f64");
  nlohmann::json listed = nlohmann::json::parse(testing::read_file(out + "/.inertest-written"));
  listed["files"].push_back({{"path", "w.f64"}, {"size", std::filesystem::file_size(out + "/w.f64")},
                             {"modified", std::filesystem::last_write_time(out + "/w.f64").time_since_epoch().count()}});
  dir.write("out/.inertest-written", listed.dump());
  const std::string reading = white_noise_plan(dir, "plan.toml", "export = [\"json\", \"filter.json\"]\n[[procedure]]\n"
                                                                 "kind = \"allan\"\nname = \"again\"\nfile = \"out/w.f64\"\n"
                                                                 "format = \"f64\"");
  // (The command line's run wrote the report; this one, without one, leaves no earlier report beside its results.)
  EXPECT_EQ(run_campaign(reading, out).removed_files, std::vector<std::string>{out + "/report.html"});
  EXPECT_TRUE(std::filesystem::exists(out + "/w.f64"));
  EXPECT_EQ(testing::read_file(out + "/noise.json"), "edited by hand");

  const std::string results = testing::read_file(out + "/results.json");
  const std::string other =
      dir.write("other.toml", std::regex_replace(testing::read_file(plan), std::regex("FOG-1"), "FOG-2"));
  try {
    run_campaign(other, out);
    ADD_FAILURE() << "a run replaced another campaign's results";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("out/results.json: holds the results of another campaign (instrument 'FOG-1', "
                                    "title 'noise', date ''; this one is instrument 'FOG-2', title 'noise', date '')"));
  }
  // The same instrument, title and date from another plan file: another campaign too.
  const std::string copy = dir.write("copy.toml", testing::read_file(plan));
  EXPECT_THAT([&] { run_campaign(copy, out); },
              ::testing::ThrowsMessage<Error>(HasSubstr(", of the plan " + std::filesystem::weakly_canonical(plan).string() +
                                                        "; this one is instrument 'FOG-1', title 'noise', date '', of the plan " +
                                                        std::filesystem::weakly_canonical(copy).string() + ")")));
  EXPECT_EQ(testing::read_file(out + "/results.json"), results);
  EXPECT_TRUE(std::filesystem::exists(out + "/filter.json"));
  // Its results moved away, the directory takes another campaign, but not over the last one's export
  // (it was replaced), and removes nothing of the last.
  std::filesystem::rename(out + "/results.json", dir.path() + "/kept.json");
  EXPECT_THAT([&] { run_campaign(other, out); },
              ::testing::ThrowsMessage<Error>(HasSubstr("the run would write 'filter.json' over '" + out +
                                                        "/filter.json', which no earlier run of this plan wrote")));
  std::filesystem::rename(out + "/filter.json", dir.path() + "/kept_filter.json");
  EXPECT_TRUE(run_campaign(other, out).removed_files.empty());
  EXPECT_TRUE(std::filesystem::exists(out + "/filter.json"));
  EXPECT_TRUE(std::filesystem::exists(out + "/noise.json"));
  dir.write("elsewhere/results.json", "[1, 2]");  // not inertest's: not replaced either
  EXPECT_THAT(testing::run_cli({"run", other, "--out", dir.path() + "/elsewhere"}).err,
              HasSubstr("holds the results of another campaign (not an inertest results file;"));
}

// An export over a file of the output directory that no run of the plan wrote (a raw record kept
// there) is refused before anything runs, as is one inside the run's own bookkeeping (it was staged
// there and removed with the staging directory, exit 0).
TEST(AllanStep, AnExportOverAFileNoRunWroteIsRefused) {
  testing::ScratchDirectory dir;
  const std::string out = dir.path() + "/out";
  dir.write("out/rate_00.csv", "raw record\n");
  EXPECT_THAT([&] { run_campaign(white_noise_plan(dir, "plan.toml", "export = [\"json\", \"rate_00.csv\"]"), out); },
              ::testing::ThrowsMessage<Error>(HasSubstr("the run would write 'rate_00.csv' over '" + out +
                                                        "/rate_00.csv', which no earlier run of this plan wrote")));
  EXPECT_EQ(testing::read_file(out + "/rate_00.csv"), "raw record\n");
  EXPECT_FALSE(std::filesystem::exists(out + "/results.json"));
  EXPECT_THAT(
      [&] { run_campaign(white_noise_plan(dir, "plan.toml", "export = [\"json\", \".inertest-exports/x.json\"]"), out); },
      ::testing::ThrowsMessage<Error>(HasSubstr("'.inertest-exports/x.json' is inside the run's own files")));
}

// A file where an export's directory is to be made: an error before anything moves, the earlier
// run's results.json as it was (it had been replaced, then an internal error, exit 3).
TEST(AllanStep, AFileWhereAnExportsDirectoryGoesLeavesTheEarlierRun) {
  testing::ScratchDirectory dir;
  const std::string plan = white_noise_plan(dir, "plan.toml", "export = [\"json\", \"coefficients/filter.json\"]");
  const std::string text = "{\"instrument\": {\"id\": \"FOG-1\"}, \"plan\": {\"title\": \"noise\"}}\n";  // the same campaign's
  const std::string earlier = dir.write("out/results.json", text);
  dir.write("out/coefficients", "a file");
  try {
    run_campaign(plan, dir.path() + "/out");
    ADD_FAILURE() << "the run moved its files over a file";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("out/coefficients: a file is where the directory of 'coefficients/filter.json' is to be made"));
  }
  EXPECT_EQ(testing::read_file(earlier), text);
  EXPECT_FALSE(std::filesystem::exists(dir.path() + "/out/.inertest-exports"));
}

}  // namespace
}  // namespace inertest
