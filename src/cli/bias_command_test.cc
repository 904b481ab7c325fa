#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <random>

#include "test_util/test_util.h"

namespace inertest {
namespace {

using testing::run_cli;
using testing::ScratchDirectory;

// 10 Hz, 200 s: bias + square wave of 1 s half-period + nothing else. With K = 5 output per deg/s,
// output b gives b/5·3600 deg/h.
std::vector<double> square_wave_record() {
  std::vector<double> output(2000);
  for (std::size_t i = 0; i < output.size(); ++i) output[i] = 2.0 + ((i / 10) % 2 == 0 ? 0.01 : -0.01);
  return output;
}

std::string as_text(const std::vector<double>& values) {
  std::string text;
  for (double v : values) text += nlohmann::json(v).dump() + "\n";
  return text;
}

TEST(BiasCommandTest, ExactContract) {
  ScratchDirectory scratch;
  const std::string file = scratch.write("rest.txt", as_text(square_wave_record()));
  const auto run = run_cli({"bias", file, "--rate", "10", "--scale-factor", "5", "--smoothing", "1,10,100", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json.at("bias").at("unit"), "deg/h");
  EXPECT_NEAR(json.at("bias").at("value").get<double>(), 2.0 / 5.0 * 3600.0, 1e-9);
  const auto& stability = json.at("bias_stability");
  ASSERT_EQ(stability.size(), 3u);
  // 1 s windows alternate 2 ± 0.01 (200 windows): 0.01·sqrt(200/199) output = ·720 deg/h.
  EXPECT_EQ(stability[0].at("smoothing_s"), 1.0);
  EXPECT_EQ(stability[0].at("unit"), "deg/h");
  EXPECT_EQ(stability[0].size(), 3u);
  EXPECT_NEAR(stability[0].at("value").get<double>(), 0.01 * std::sqrt(200.0 / 199.0) * 720.0, 1e-9);
  EXPECT_NEAR(stability[1].at("value").get<double>(), 0.0, 1e-9);  // 10 s windows: equal means
  EXPECT_EQ(stability[2].at("smoothing_s"), 100.0);
  EXPECT_EQ(json.at("random_walk_coefficient").at("unit"), "deg/sqrt(h)");
  EXPECT_NEAR(json.at("random_walk_coefficient").at("value").get<double>(),
              stability[0].at("value").get<double>() / 60.0, 1e-12);
}

TEST(BiasCommandTest, NamedColumnAndBinaryFormat) {
  ScratchDirectory scratch;
  const std::vector<double> output = square_wave_record();
  std::string text = "time,gyro\n";
  for (std::size_t i = 0; i < output.size(); ++i) text += fmt::format("{:.1f},", static_cast<double>(i) / 10.0) + nlohmann::json(output[i]).dump() + "\n";
  const std::string csv = scratch.write("rest.csv", text);  // at 10 Hz, as --rate says
  std::string bytes(output.size() * sizeof(float), '\0');
  for (std::size_t i = 0; i < output.size(); ++i) {
    const float f = static_cast<float>(output[i]);
    std::memcpy(bytes.data() + i * sizeof(float), &f, sizeof(float));
  }
  const std::string binary = scratch.write("rest.f32", bytes);
  const auto by_name = run_cli({"bias", csv, "--rate", "10", "--scale-factor", "5", "--column", "gyro", "--json"});
  ASSERT_EQ(by_name.exit_code, 0) << by_name.err;
  const auto by_index = run_cli({"bias", csv, "--rate", "10", "--scale-factor", "5", "--column", "2", "--json"});
  ASSERT_EQ(by_index.exit_code, 0) << by_index.err;
  EXPECT_EQ(nlohmann::json::parse(by_name.out), nlohmann::json::parse(by_index.out));
  const auto f32 = run_cli({"bias", binary, "--rate", "10", "--scale-factor", "5", "--format", "f32", "--json"});
  ASSERT_EQ(f32.exit_code, 0) << f32.err;
  EXPECT_NEAR(nlohmann::json::parse(f32.out).at("bias").at("value").get<double>(), 1440.0, 1e-3);
  // No column chosen in a record of several: the one headed "output", else an error (the first
  // column, the time here, was taken and its mean reported as the bias).
  const auto unchosen = run_cli({"bias", csv, "--rate", "10", "--scale-factor", "5"});
  EXPECT_EQ(unchosen.exit_code, 2);
  EXPECT_THAT(unchosen.err, ::testing::HasSubstr("rest.csv:1:1: the record has 2 columns (time, gyro): choose the "
                                                 "output with --column"));
  std::string headed = "time,output\n";
  for (std::size_t i = 0; i < output.size(); ++i) headed += fmt::format("{:.1f},", static_cast<double>(i) / 10.0) + nlohmann::json(output[i]).dump() + "\n";
  const auto by_header = run_cli({"bias", scratch.write("headed.csv", headed), "--rate", "10", "--scale-factor", "5", "--json"});
  ASSERT_EQ(by_header.exit_code, 0) << by_header.err;
  EXPECT_EQ(nlohmann::json::parse(by_header.out).at("bias"), nlohmann::json::parse(by_name.out).at("bias"));
  // The text says which smoothing time each bias stability is of.
  const auto printed = run_cli({"bias", csv, "--rate", "10", "--scale-factor", "5", "--column", "gyro"});
  EXPECT_THAT(printed.out, ::testing::HasSubstr("    smoothing_s 1: "));
}

TEST(BiasCommandTest, ClearErrors) {
  ScratchDirectory scratch;
  const std::string file = scratch.write("short.txt", as_text(std::vector<double>(50, 1.0)));
  // A smoothing time longer than the record: the bias, and a warning instead of that stability.
  const auto too_long = run_cli({"bias", file, "--rate", "10", "--scale-factor", "5", "--smoothing", "10", "--json"});
  ASSERT_EQ(too_long.exit_code, 0) << too_long.err;
  const auto too_long_json = nlohmann::json::parse(too_long.out);
  EXPECT_NEAR(too_long_json.at("bias").at("value").get<double>(), 720.0, 1e-9);  // 1 / 5 * 3600
  // Its row stays, not measured (a plan's limit on it fails rather than judging another row).
  ASSERT_EQ(too_long_json.at("bias_stability").size(), 1u);
  EXPECT_TRUE(too_long_json.at("bias_stability").at(0).at("value").is_null());
  EXPECT_FALSE(too_long_json.at("bias_stability").at(0).at("measured").get<bool>());
  EXPECT_THAT(too_long_json.at("warnings").dump(), ::testing::HasSubstr("longer than the record"));
  const auto bad_rate = run_cli({"bias", file, "--rate", "0", "--scale-factor", "5", "--smoothing", "1"});
  EXPECT_EQ(bad_rate.exit_code, 2);
  EXPECT_THAT(bad_rate.err, ::testing::HasSubstr("--rate must be positive, got 0 Hz"));
  const auto no_k = run_cli({"bias", file, "--rate", "10", "--smoothing", "1"});
  EXPECT_EQ(no_k.exit_code, 2);
  EXPECT_THAT(no_k.err, ::testing::HasSubstr("scale factor"));
  const auto missing = run_cli({"bias", scratch.path() + "/none.txt", "--rate", "10", "--scale-factor", "5"});
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_THAT(missing.err, ::testing::HasSubstr("none.txt"));
  EXPECT_TRUE(missing.out.empty());
  // The Earth rate removed depends on the latitude: not given, it is asked for (0 was assumed).
  const auto no_latitude = run_cli({"bias", file, "--rate", "10", "--scale-factor", "5", "--remove-earth-rate"});
  EXPECT_EQ(no_latitude.exit_code, 2);
  EXPECT_THAT(no_latitude.err, ::testing::HasSubstr("--latitude is needed to remove the Earth rate"));
  EXPECT_TRUE(no_latitude.out.empty());
  // A latitude or heading without --remove-earth-rate is an error: it was ignored, and the bias
  // kept the Earth rate the engineer meant to remove.
  for (const char* option : {"--latitude", "--heading"}) {
    const auto alone = run_cli({"bias", file, "--rate", "10", "--scale-factor", "5", option, "45"});
    EXPECT_EQ(alone.exit_code, 2) << option;
    EXPECT_THAT(alone.err, ::testing::HasSubstr(std::string(option) + ") is used only with remove_earth_rate"));
    EXPECT_TRUE(alone.out.empty());
  }
}

// A pulse counter read each sample interval (--output-unit pulse) gives counts, not pulse/s: the
// readers make them rates, count x the sample rate, and the figures are those of the rates.
TEST(BiasCommandTest, PulseCountsPerSampleIntervalAreMadeRates) {
  ScratchDirectory scratch;
  std::vector<double> counts = square_wave_record();  // at 10 Hz: output/10 pulses an interval
  for (double& count : counts) count /= 10.0;
  const std::string rates = scratch.write("rates.txt", as_text(square_wave_record()));
  const std::string pulses = scratch.write("pulses.txt", as_text(counts));
  const std::vector<std::string> bias = {"bias", "--rate", "10", "--scale-factor", "5", "--smoothing", "1", "--json"};
  const auto run = [&](const std::string& file, const std::string& unit) {
    std::vector<std::string> arguments = bias;
    arguments.insert(arguments.begin() + 1, file);
    arguments.insert(arguments.end(), {"--output-unit", unit});
    const auto result = run_cli(arguments);
    EXPECT_EQ(result.exit_code, 0) << result.err;
    return nlohmann::json::parse(result.out);
  };
  const nlohmann::json of_rates = run(rates, "pulse/s");
  const nlohmann::json of_counts = run(pulses, "pulse");
  EXPECT_NEAR(of_counts.at("bias").at("value").get<double>(), 2.0 / 5.0 * 3600.0, 1e-9);
  EXPECT_NEAR(of_counts.at("bias_stability")[0].at("value").get<double>(),
              of_rates.at("bias_stability")[0].at("value").get<double>(), 1e-9);
  // The counts taken as pulse/s: 10 times too small.
  EXPECT_NEAR(run(pulses, "pulse/s").at("bias").at("value").get<double>(), 2.0 / 5.0 * 360.0, 1e-9);

  // A timed record: the rate from the time column (0.5 s an interval), and from --rate.
  const std::string power_on = scratch.write("on.csv", "t,out\n0.5,0.5\n1,0.25\n1.5,0.1\n2,0.025\n2.5,0.005\n");
  for (const std::vector<std::string>& timing : {std::vector<std::string>{"--run", "0:" + power_on},
                                                 std::vector<std::string>{"--run", "0:" + power_on, "--rate", "2",
                                                                          "--column", "out"}}) {
    std::vector<std::string> arguments = {"turn-on-time", "--scale-factor", "3600", "--rest-band", "0.1",
                                          "--output-unit", "pulse", "--json"};
    arguments.insert(arguments.end(), timing.begin(), timing.end());
    const auto on = run_cli(arguments);
    ASSERT_EQ(on.exit_code, 0) << on.err;
    // Rates 1, 0.5, 0.2, 0.05, 0.01 pulse/s: within 0.1 deg/h (0.1 pulse/s) from the 4th sample, at 2 s.
    EXPECT_DOUBLE_EQ(nlohmann::json::parse(on.out).at("turn_on_time").at("value").get<double>(), 2.0);
  }
}

TEST(BiasCommandTest, RepeatabilityAndTemperature) {
  ScratchDirectory scratch;
  std::vector<std::string> files;
  for (int i = 1; i <= 6; ++i) {
    files.push_back(scratch.write("run" + std::to_string(i) + ".txt", as_text(std::vector<double>(4, 0.1 * i))));
  }
  std::vector<std::string> arguments = {"bias-repeatability"};
  arguments.insert(arguments.end(), files.begin(), files.end());
  for (const char* a : {"--scale-factor", "3600", "--json"}) arguments.push_back(a);
  const auto repeat = run_cli(arguments);
  ASSERT_EQ(repeat.exit_code, 0) << repeat.err;
  // Biases 0.1 ... 0.6 deg/h: standard deviation 0.1·sqrt(3.5).
  EXPECT_NEAR(nlohmann::json::parse(repeat.out).at("bias_repeatability").at("value").get<double>(),
              0.1 * std::sqrt(3.5), 1e-12);
  const auto temperature = run_cli({"bias-temperature", "--run", "20:" + files[0], "--run", "60:" + files[4],
                                    "--run", "-40:" + files[2], "--scale-factor", "3600", "--json"});
  ASSERT_EQ(temperature.exit_code, 0) << temperature.err;
  // |0.5 - 0.1| / 40 = 0.01, |0.3 - 0.1| / 60.
  EXPECT_NEAR(nlohmann::json::parse(temperature.out).at("bias_temperature_sensitivity").at("value").get<double>(),
              0.01, 1e-12);
  const auto bad = run_cli({"bias-temperature", "--run", "hot:" + files[0], "--scale-factor", "1"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, ::testing::HasSubstr("NUMBER:FILE"));
  const auto one = run_cli({"bias-repeatability", files[0], "--scale-factor", "1"});
  EXPECT_EQ(one.exit_code, 2);
  EXPECT_THAT(one.err, ::testing::HasSubstr("at least 2"));
}

TEST(ProcedureCommandsTest, TurnOnTimePolarityThresholdResolution) {
  ScratchDirectory scratch;
  // Time column + output: error 1, 0.5, 0.2, 0.05, 0.01 deg/h (K = 3600) at t = 1..5 s; band 0.1.
  const std::string power_on = scratch.write("on.csv", "t,out\n1,1\n2,0.5\n3,0.2\n4,0.05\n5,0.01\n");
  const auto on = run_cli({"turn-on-time", "--run", "0:" + power_on, "--scale-factor", "3600", "--rest-band", "0.1",
                           "--json"});
  ASSERT_EQ(on.exit_code, 0) << on.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(on.out).at("turn_on_time").at("value").get<double>(), 4.0);
  const auto warm = run_cli({"warm-up-time", "--run", "0:" + power_on, "--scale-factor", "3600", "--rest-band",
                             "0.1", "--json"});
  ASSERT_EQ(warm.exit_code, 0) << warm.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(warm.out).at("warm_up_time").at("value").get<double>(), 4.0);
  // With --rate 2 the same column alone: sample i at (i + 1)/2 s -> the 4th sample at 2 s.
  const std::string column = scratch.write("on.txt", "1\n0.5\n0.2\n0.05\n0.01\n");
  const auto by_rate = run_cli({"turn-on-time", "--run", "0:" + column, "--rate", "2", "--scale-factor", "3600",
                                "--rest-band", "0.1", "--json"});
  ASSERT_EQ(by_rate.exit_code, 0) << by_rate.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(by_rate.out).at("turn_on_time").at("value").get<double>(), 2.0);

  const auto pol = run_cli({"polarity", "--positive-output", "-3", "--negative-output", "3", "--json"});
  ASSERT_EQ(pol.exit_code, 0) << pol.err;
  EXPECT_EQ(nlohmann::json::parse(pol.out).at("polarity"), "negative");

  const std::string points = scratch.write("th.csv", "rate,output\n0,10\n10,20\n2,11.5\n1,10.6\n-10,0\n-4,7\n-2,9.5\n");
  const auto th = run_cli({"threshold", points, "--method", "1", "--scale-factor", "3600", "--rate-unit", "deg/h",
                           "--json"});
  ASSERT_EQ(th.exit_code, 0) << th.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(th.out).at("threshold").at("value").get<double>(), 4.0);
  // 60 % of the expected output at 2 deg/h: passes the default criterion, fails eq. (15) as printed.
  const std::string sixty = scratch.write("th60.csv", "rate,output\n0,0\n4,4\n2,1.2\n1,0.45\n-4,-4\n-2,-2\n-1,-0.45\n");
  const std::vector<std::string> threshold_args = {"threshold", sixty,         "--method", "1",     "--scale-factor",
                                                   "3600",      "--rate-unit", "deg/h",    "--json"};
  const auto th_expected = run_cli(threshold_args);
  ASSERT_EQ(th_expected.exit_code, 0) << th_expected.err;
  EXPECT_EQ(nlohmann::json::parse(th_expected.out).at("criterion_denominator"), "expected");
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(th_expected.out).at("threshold").at("value").get<double>(), 2.0);
  auto measured_args = threshold_args;
  measured_args.insert(measured_args.end(), {"--criterion-denominator", "measured"});
  const auto th_measured = run_cli(measured_args);
  ASSERT_EQ(th_measured.exit_code, 0) << th_measured.err;
  EXPECT_EQ(nlohmann::json::parse(th_measured.out).at("criterion_denominator"), "measured");
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(th_measured.out).at("threshold").at("value").get<double>(), 4.0);
  measured_args.back() = "theoretical";
  EXPECT_NE(run_cli(measured_args).exit_code, 0);  // a usage error (CLI11)

  const std::string steps = scratch.write("res.csv",
                                          "base_rate,base_output,rate,output\n100,0,110,10\n100,0,102,1.2\n"
                                          "100,0,101,0.4\n-100,0,-110,-10\n-100,0,-104,-2.5\n-100,0,-103,-1\n");
  const auto res = run_cli({"resolution", steps, "--scale-factor", "3600", "--rate-unit", "deg/h", "--json"});
  ASSERT_EQ(res.exit_code, 0) << res.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(res.out).at("resolution").at("value").get<double>(), 4.0);
}

// A text record whose own stamps have a gap: bias's windows, counted in samples at the rate, would
// hold unequal times (an error naming both spans); a record read for its mean alone is not held to it.
TEST(BiasCommandTest, AGapInTheStampsIsAnErrorWhereTheRateTimesTheSamples) {
  ScratchDirectory dir;
  std::string text = "time_s,output\n";
  for (int i = 0; i < 3000; ++i) {
    if (i < 1000 || i >= 2000) text += fmt::format("{:.1f},{}\n", i / 10.0, 3600.0 + (i % 7));
  }
  const std::string gap = dir.write("gap.csv", text);
  const auto bias = run_cli({"bias", gap, "--rate", "10", "--scale-factor", "3600", "--column", "output"});
  EXPECT_EQ(bias.exit_code, 2);
  EXPECT_THAT(bias.err, ::testing::HasSubstr("gap.csv:1: the time column 'time_s' spans 299.9 s from the first sample to the last, "
                                  "but its 2000 samples at the interval of its first rows (0.1 s) span 199.9 s"));
  // Without --rate the time column gives it (10 Hz), and the same gap is found.
  const auto from_stamps = run_cli({"bias", gap, "--scale-factor", "3600", "--column", "output"});
  EXPECT_EQ(from_stamps.exit_code, 2);
  EXPECT_THAT(from_stamps.err, ::testing::HasSubstr("gap.csv:1: the time column 'time_s' spans 299.9 s"));
  std::string even = "time_s,output\n";
  for (int i = 0; i < 3000; ++i) even += fmt::format("{:.1f},{}\n", i / 10.0, 3600.0 + (i % 7));
  const std::string regular = dir.write("regular.csv", even);
  const auto given = run_cli({"bias", regular, "--rate", "10", "--scale-factor", "3600", "--column", "output", "--json"});
  const auto stamped = run_cli({"bias", regular, "--scale-factor", "3600", "--column", "output", "--json"});
  ASSERT_EQ(stamped.exit_code, 0) << stamped.err;
  EXPECT_EQ(nlohmann::json::parse(stamped.out), nlohmann::json::parse(given.out));
  const std::string minus = dir.write("minus.csv", "output\n-3600\n-3601\n");
  const auto polarity = run_cli({"polarity", "--positive-file", gap, "--negative-file", minus, "--column", "output"});
  EXPECT_EQ(polarity.exit_code, 0) << polarity.err;
}

}  // namespace
}  // namespace inertest
