// Golden outputs: every CLI command that computes a result, and the results.json of a reduced demo
// campaign (every plan kind), compared with JSON recorded before the procedure-spec redesign
// (issue 22) under tests/golden/. A refactor of the glue must not change a key or a figure.
//
// Re-recording (only for an intended change, listed in the commit message; CONTRIBUTING.md):
//   INERTEST_RECORD_GOLDEN=1 build/bin/inertest_tests --gtest_filter='GoldenOutputs*'
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/procedure_spec.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using nlohmann::json;

// Relative tolerance on numbers. The outputs are deterministic (fixed seed, fixed inputs); what
// may differ between builds is the last bits of a double: the JSON text round trip (shortest
// representation) and contraction into fused multiply-adds, which GCC and Clang decide differently
// at -O2. Those move a figure by a few ulp (1e-16 relative) and a least-squares figure or a
// difference of near-equal outputs by a few orders more; 1e-9 allows that and nothing a change of
// formula, unit or input would produce. Not loosened to make a run pass.
constexpr double kRelativeTolerance = 1e-9;

// The placeholders in the command lines below and in the recorded strings.
constexpr const char* kLabPlaceholder = "{lab}";
constexpr const char* kSourcePlaceholder = "{source}";

struct GoldenCommand {
  const char* name;  // tests/golden/<name>.json
  std::vector<std::string> arguments;
};

// One deterministic run of each computing command on the reduced demo's lab records (written by
// the demo's simulator from tests/golden/simulation.toml, seed fixed there) or on data/.
const std::vector<GoldenCommand>& golden_commands() {
  const std::string lab = kLabPlaceholder;
  const std::string bias_runs = lab + "/bias_temperature/bias_";
  const std::string turn_on = "0:" + lab + "/turn_on_time/power_on_1.f64";
  static const std::vector<GoldenCommand> commands = {
      {"scale_factor", {"scale-factor", lab + "/scale_factor/points.csv", "--output-unit", "pulse/s"}},
      {"scale_factor_records",
       {"scale-factor", "--records", lab + "/scale_factor/records.csv", "--sample-rate", "100", "--settling-time", "1",
        "--output-unit", "pulse/s"}},
      {"scale_factor_repeatability",
       {"scale-factor-repeatability", lab + "/scale_factor_repeatability/run_1.csv",
        lab + "/scale_factor_repeatability/run_2.csv", lab + "/scale_factor_repeatability/run_3.csv",
        lab + "/scale_factor_repeatability/run_4.csv", lab + "/scale_factor_repeatability/run_5.csv",
        lab + "/scale_factor_repeatability/run_6.csv", "--output-unit", "pulse/s"}},
      {"scale_factor_temperature",
       {"scale-factor-temperature", lab + "/scale_factor_temperature/runs.csv", "--reference-temperature", "20",
        "--output-unit", "pulse/s"}},
      {"maximum_input_rate",
       {"maximum-input-rate", lab + "/maximum_input_rate/points.csv", "--nonlinearity-limit", "5", "--output-unit",
        "pulse/s"}},
      {"bias",
       {"bias", lab + "/bias_static.f64", "--format", "f64", "--rate", "100", "--scale-factor", "36000", "--smoothing",
        "1,10,100", "--output-unit", "pulse/s"}},
      {"bias_repeatability",
       {"bias-repeatability", lab + "/bias_repeatability/run_1.f64", lab + "/bias_repeatability/run_2.f64",
        lab + "/bias_repeatability/run_3.f64", lab + "/bias_repeatability/run_4.f64",
        lab + "/bias_repeatability/run_5.f64", lab + "/bias_repeatability/run_6.f64", "--format", "f64",
        "--scale-factor", "36000"}},
      {"bias_temperature",
       {"bias-temperature", "--run", "20:" + bias_runs + "20C.f64", "--run", "-40:" + bias_runs + "-40C.f64", "--run",
        "60:" + bias_runs + "60C.f64", "--room-temperature", "20", "--format", "f64", "--scale-factor", "36000"}},
      {"turn_on_time",
       {"turn-on-time", "--run", turn_on, "--format", "f64", "--rate", "100", "--scale-factor", "36000", "--zero",
        "0.24588687142452803", "--rest-band", "0.2", "--smoothing", "60"}},
      {"warm_up_time",
       {"warm-up-time", "--run", turn_on, "--format", "f64", "--rate", "100", "--scale-factor", "36000", "--zero",
        "0.24588687142452803", "--rest-band", "0.2", "--smoothing", "60"}},
      {"polarity",
       {"polarity", "--positive-file", lab + "/polarity/plus.csv", "--negative-file", lab + "/polarity/minus.csv",
        "--column", "output", "--expected", "positive", "--output-unit", "pulse/s"}},
      {"polarity_outputs", {"polarity", "--positive-output", "-3", "--negative-output", "3"}},
      {"threshold",
       {"threshold", lab + "/threshold/positions.csv", "--method", "2", "--scale-factor", "36000", "--latitude",
        "45.75", "--heading", "0"}},
      {"resolution", {"resolution", lab + "/resolution/steps.csv", "--scale-factor", "36000"}},
      {"bandwidth", {"bandwidth", "--records", lab + "/bandwidth/runs.csv"}},
      {"input_axis_misalignment",
       {"input-axis-misalignment", lab + "/input_axis_misalignment/positions.csv", "--scale-factor", "36000", "--rate",
        "100", "--output-unit", "pulse/s"}},
      {"misalignment_gyro", {"misalignment", "gyro", lab + "/gyro_misalignment/positions.csv", "--scale-factor", "36000"}},
      {"misalignment_accelerometer",
       {"misalignment", "accelerometer", lab + "/accelerometer_misalignment/positions.csv", "--scale-factor", "1.3",
        "--output-unit", "V"}},
      {"allan",
       {"allan", lab + "/allan_long_static.f64", "--format", "f64", "--rate", "5", "--scale-factor", "36000", "--taus",
        "8,16,32,64,128,256,512,1024,2048"}},
      {"centrifuge",
       {"centrifuge", lab + "/centrifuge/samples.csv", "--radius", "1", "--latitude", "45.75", "--k1",
        "-1.939254724438144e-05", "--k2", "1.939254724438144e-05", "--delta-omega", "1e-05"}},
      {"centrifuge_table3",
       {"centrifuge", std::string(kSourcePlaceholder) + "/data/centrifuge/table3_harmonics.csv", "--radius", "1",
        "--latitude", "45.75", "--gravity", "9.8", "--k1", "-2e-5", "--k2", "2e-5", "--delta-omega", "1e-5"}},
      {"hand_checks",
       {"hand-checks", "--check", "name=Insulation resistance,value=120,unit=Mohm,min=20", "--check",
        "name=Appearance,value=pass"}},
      {"inspect", {"inspect", lab + "/scale_factor/rate_00.csv"}},
  };
  return commands;
}

// The source tree's root, without the trailing separator.
std::string source_root() {
  std::string root = testing::source_path("");
  root.pop_back();
  return root;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// Paths of this run replaced by placeholders, so that the recorded strings do not depend on where
// the test runs.
json normalised(const json& value, const std::string& lab, const std::string& source) {
  if (value.is_string()) {
    return replace_all(replace_all(value.get<std::string>(), lab, kLabPlaceholder), source, kSourcePlaceholder);
  }
  if (value.is_object()) {
    json out = json::object();
    for (const auto& [key, item] : value.items()) out[key] = normalised(item, lab, source);
    return out;
  }
  if (value.is_array()) {
    json out = json::array();
    for (const auto& item : value) out.push_back(normalised(item, lab, source));
    return out;
  }
  return value;
}

// Every difference between actual and expected, one line each with its JSON pointer.
void compare(const json& actual, const json& expected, const std::string& pointer, std::vector<std::string>& differences) {
  if (expected.is_number() && actual.is_number()) {
    const double a = actual.get<double>();
    const double e = expected.get<double>();
    if (std::abs(a - e) > kRelativeTolerance * std::abs(e)) {
      differences.push_back(fmt::format("{}: {} != golden {}", pointer, actual.dump(), expected.dump()));
    }
    return;
  }
  if (actual.type() != expected.type()) {
    differences.push_back(fmt::format("{}: type {} != golden {}", pointer, actual.type_name(), expected.type_name()));
    return;
  }
  if (expected.is_object()) {
    for (const auto& [key, item] : expected.items()) {
      const std::string child = pointer + "/" + key;
      if (!actual.contains(key)) {
        differences.push_back(child + ": missing");
      } else {
        compare(actual.at(key), item, child, differences);
      }
    }
    for (const auto& [key, item] : actual.items()) {
      if (!expected.contains(key)) differences.push_back(pointer + "/" + key + ": not in the golden file");
    }
    return;
  }
  if (expected.is_array()) {
    if (actual.size() != expected.size()) {
      differences.push_back(fmt::format("{}: {} items != golden {}", pointer, actual.size(), expected.size()));
      return;
    }
    for (std::size_t i = 0; i < expected.size(); ++i) {
      compare(actual.at(i), expected.at(i), fmt::format("{}/{}", pointer, i), differences);
    }
    return;
  }
  if (actual != expected) differences.push_back(fmt::format("{}: {} != golden {}", pointer, actual.dump(), expected.dump()));
}

bool recording() {
  const char* record = std::getenv("INERTEST_RECORD_GOLDEN");
  return record != nullptr && std::string(record) == "1";
}

// Checks (or, when re-recording, writes) tests/golden/<name>.json.
void check_golden(const std::string& name, const json& output, const std::string& lab) {
  const std::string source = source_root();
  const json actual = normalised(output, lab, source);
  const std::string golden_path = testing::source_path("tests/golden/" + name + ".json");
  if (recording()) {
    std::ofstream(golden_path) << actual.dump(1) << "\n";
    return;
  }
  ASSERT_TRUE(std::filesystem::exists(golden_path)) << golden_path << " is missing; see CONTRIBUTING.md";
  const json expected = json::parse(testing::read_file(golden_path));
  std::vector<std::string> differences;
  compare(actual, expected, "", differences);
  std::string listing;
  for (std::size_t i = 0; i < differences.size() && i < 40; ++i) listing += differences[i] + "\n";
  EXPECT_TRUE(differences.empty()) << name << ": " << differences.size() << " differences from " << golden_path
                                   << "\n" << listing;
}

class GoldenOutputs : public ::testing::Test {
 protected:
  // One reduced demo for the whole suite: its lab is the input of every command.
  static void SetUpTestSuite() {
    scratch_ = new testing::ScratchDirectory();
    out_ = scratch_->path() + "/demo";
    demo_ = new testing::CliRun(testing::run_cli(
        {"demo", "--plan", testing::source_path("tests/golden/simulation.toml"), "--out", out_}));
    write_listings(out_ + "/lab");
  }
  // The listings some commands take instead of a plan (the simulator writes records and a plan).
  static void write_listings(const std::string& lab) {
    std::ofstream(lab + "/scale_factor_temperature/runs.csv")
        << "temperature_degC,file\n20,points_20C.csv\n-40,points_-40C.csv\n60,points_60C.csv\n";
    // The rates of the scale-factor test in simulation order (tests/golden/simulation.toml).
    const std::vector<std::string> rates = {"0",    "0.1",  "0.2",  "0.5", "1",   "2",   "5",   "10",  "20",
                                            "50",   "100",  "200",  "300", "-0.1", "-0.2", "-0.5", "-1", "-2",
                                            "-5",   "-10",  "-20",  "-50", "-100", "-200", "-300", "0"};
    std::ofstream records(lab + "/scale_factor/records.csv");
    records << "rate,file\n";
    for (std::size_t i = 0; i < rates.size(); ++i) records << fmt::format("{},rate_{:02d}.csv\n", rates[i], i);
    const std::vector<std::string> frequencies = {"5", "10", "20", "40", "80", "120", "160", "200", "300", "400", "500"};
    std::ofstream runs(lab + "/bandwidth/runs.csv");
    runs << "freq_hz,file\n";
    for (std::size_t i = 0; i < frequencies.size(); ++i) runs << fmt::format("{},vib_{:02d}.csv\n", frequencies[i], i);
  }
  static void TearDownTestSuite() {
    delete demo_;
    delete scratch_;
  }
  static testing::ScratchDirectory* scratch_;
  static testing::CliRun* demo_;
  static std::string out_;
};

testing::ScratchDirectory* GoldenOutputs::scratch_ = nullptr;
testing::CliRun* GoldenOutputs::demo_ = nullptr;
std::string GoldenOutputs::out_;

TEST_F(GoldenOutputs, DemoResultsJson) {
  // The demo's gyro fails two limits on purpose: verdict FAIL, exit status 0 (every figure agrees
  // with the simulated truth).
  ASSERT_EQ(demo_->exit_code, 0) << demo_->err;
  json results = json::parse(testing::read_file(out_ + "/results.json"));
  // The clock's readings, not figures: the date and time of this run.
  for (const char* key : {"processed_at", "tested_on"}) {
    ASSERT_TRUE(results.contains(key)) << key;
    results[key] = "{now}";
  }
  check_golden("demo_results", results, out_);
}

TEST_F(GoldenOutputs, EveryComputingCommand) {
  const std::string lab = out_ + "/lab";
  const std::string source = source_root();
  for (const GoldenCommand& command : golden_commands()) {
    std::vector<std::string> arguments;
    for (const std::string& argument : command.arguments) {
      arguments.push_back(replace_all(replace_all(argument, kLabPlaceholder, lab), kSourcePlaceholder, source));
    }
    arguments.push_back("--json");
    const testing::CliRun run = testing::run_cli(arguments);
    ASSERT_EQ(run.exit_code, 0) << command.name << ": " << run.err;
    check_golden(command.name, json::parse(run.out), lab);
  }
}

// The worked example of every declared procedure that has one (ProcedureSpec::example), against
// tests/golden/<kind>_example.json.
TEST_F(GoldenOutputs, EveryDeclaredExample) {
  std::size_t examples = 0;
  for (const ProcedureSpec& spec : procedure_specs()) {
    if (spec.example.empty()) continue;
    const testing::CliRun run = testing::run_example(spec);
    ASSERT_EQ(run.exit_code, 0) << spec.kind << ": " << run.err;
    check_golden(spec.kind + "_example", json::parse(run.out), out_ + "/lab");
    ++examples;
  }
  RecordProperty("examples", static_cast<int>(examples));
}

}  // namespace
}  // namespace inertest
