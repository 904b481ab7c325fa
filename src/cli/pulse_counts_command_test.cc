// An output unit of pulse is a pulse counter read once a sample interval (io/output_record.h
// read_pulse_counts_as_rates): every command that reads the instrument's raw records takes the
// counts times the sample rate, so a record of counts with --output-unit pulse (an IMU's --gyro-unit
// pulse) gives the figures of the same record in pulse/s; a table of mean outputs, which has no
// interval, is taken per second.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inertest/core/units.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;
using testing::run_cli;
using testing::ScratchDirectory;

// Writes a data set whose outputs (pulse/s) each pass through `output` (identity for rates, /fs for
// counts) into `directory`, returning the command's arguments.
using DataSet =
    std::function<std::vector<std::string>(ScratchDirectory& directory, const std::function<double(double)>& output)>;

// Numbers equal to 1e-9 relative (1e-9 absolute near zero: a fit's residual of an exact line is
// rounding), strings and keys alike.
void expect_same_figures(const nlohmann::json& counts, const nlohmann::json& rates, const std::string& where) {
  ASSERT_EQ(counts.type(), rates.type()) << where;
  if (counts.is_object()) {
    ASSERT_EQ(counts.size(), rates.size()) << where;
    for (const auto& [key, value] : rates.items()) {
      ASSERT_TRUE(counts.contains(key)) << where << "/" << key;
      expect_same_figures(counts.at(key), value, where + "/" + key);
    }
  } else if (counts.is_array()) {
    ASSERT_EQ(counts.size(), rates.size()) << where;
    for (std::size_t i = 0; i < rates.size(); ++i)
      expect_same_figures(counts[i], rates[i], where + "/" + std::to_string(i));
  } else if (counts.is_number()) {
    const double a = counts.get<double>();
    const double b = rates.get<double>();
    EXPECT_NEAR(a, b, 1e-9 * (1.0 + std::abs(b))) << where;
  } else {
    EXPECT_EQ(counts, rates) << where;
  }
}

struct PulseCase {
  const char* name;
  double sample_rate_hz;
  DataSet data;
  const char* unit_flag = "--output-unit";
};

// A record per test point at 100 Hz: K = 100 pulse/s per deg/s, static runs at both ends.
std::vector<std::string> scale_factor_records(ScratchDirectory& directory,
                                              const std::function<double(double)>& output) {
  std::string listing = "rate,file\n";
  const std::array<double, 7> rates = {0, 10, -10, 20, -20, 50, 0};
  for (std::size_t i = 0; i < rates.size(); ++i) {
    std::string record = "output\n";
    for (int k = 0; k < 200; ++k) {
      record += fmt::format("{:.17g}\n", output(100.0 * rates[i] * (1.0 + 1e-5 * rates[i]) + 0.3 + 0.01 * (k % 7)));
    }
    listing += fmt::format("{},{}\n", rates[i], directory.write(fmt::format("p{}.csv", i), record));
  }
  return {"scale-factor", "--records", directory.write("points.csv", listing), "--sample-rate", "100"};
}

// One long record at 100 Hz with a table-rate column, 10 s at each rate.
std::vector<std::string> scale_factor_record(ScratchDirectory& directory, const std::function<double(double)>& output) {
  std::string record = "rate,output\n";
  for (double rate : {0.0, 10.0, -10.0, 20.0, -20.0, 50.0, -50.0, 0.0}) {
    for (int k = 0; k < 1000; ++k) {
      record += fmt::format("{},{:.17g}\n", rate, output(100.0 * rate * (1.0 + 1e-5 * rate) + 0.3 + 0.01 * (k % 7)));
    }
  }
  return {"scale-factor", "--record", directory.write("long.csv", record), "--sample-rate", "100"};
}

// Threshold by slow rotation (GJB 2426A 5.10.4.3): 10 Hz for one revolution at 1 deg/s, K = 100.
std::vector<std::string> slow_rotation(ScratchDirectory& directory, const std::function<double(double)>& output) {
  std::string record = "time_s,output\n";
  const double horizontal = 15.041067 / 3600.0 * std::cos(40.0 * constants::kDegree);  // deg/s
  for (int k = 1; k <= 3600; ++k) {
    const double t = 0.1 * k;
    const double rate = horizontal * std::cos(t * constants::kDegree);
    record +=
        fmt::format("{:.17g},{:.17g}\n", t, output(std::abs(rate) < 0.5 / 3600.0 ? 0.0 : 100.0 * rate));  // a dead zone
  }
  return {"threshold",      directory.write("rotation.csv", record),
          "--method",       "3",
          "--scale-factor", "100",
          "--table-rate",   "1",
          "--latitude",     "40"};
}

// Angular-vibration records at 10 kHz (GJB 2426A 5.13), as BandwidthCommand's, K = 100.
std::vector<std::string> vibration(ScratchDirectory& directory, const std::function<double(double)>& output) {
  const double t = 1.0 / (2 * constants::kPi * 200.0);
  std::string listing = "freq_hz,file\n";
  for (int i = 0; i < 10; ++i) {
    const double f = 10.0 * std::pow(60.0, i / 9.0);
    const double w = 2 * constants::kPi * f;
    const double phase = -std::atan(w * t) - w * 1e-4;
    std::string record = "time_s,output,angle_deg\n";
    for (int k = 0; k < 2000; ++k) {
      const double time = k / 10000.0;
      record += fmt::format(
          "{:.17g},{:.17g},{:.17g}\n", time,
          output(100.0 / std::sqrt(1 + w * w * t * t) * 0.2 * w * std::sin(w * time + constants::kPi / 2 + phase)),
          0.2 * std::sin(w * time));
    }
    listing += fmt::format("{:.17g},{}\n", f, directory.write(fmt::format("vib_{}.csv", i), record));
  }
  return {"bandwidth", "--records", directory.write("runs.csv", listing)};
}

// The misalignment paper's five positions at +-20 deg/s, 50 Hz, one whole revolution, K = 100.
std::vector<std::string> misalignment_records(ScratchDirectory& directory,
                                              const std::function<double(double)>& output) {
  const double angles_arcsec[] = {-7.5, 2.4, -53.8, -162.0, 56.3};  // y0, x0, y1, y2, z2
  const std::array<std::array<double, 2>, 5> positions = {{{0, 0}, {0, 180}, {180, 180}, {90, 180}, {0, 90}}};
  std::string listing = "alpha_deg,beta_deg,rate_dps,file\n";
  int index = 0;
  for (const auto& [alpha_deg, beta_deg] : positions) {
    for (double rate : {20.0, -20.0}) {
      const double a = alpha_deg * constants::kDegree;
      const double b = beta_deg * constants::kDegree;
      const double angles = (-angles_arcsec[0] * std::cos(b) + angles_arcsec[1] * std::sin(b) - angles_arcsec[2] +
                             angles_arcsec[4] * std::sin(a) - angles_arcsec[3] * std::cos(a)) *
                            constants::kArcsecond;
      std::string record = "time_s,output\n";
      for (int s = 0; s < 1000; ++s) {
        record += fmt::format("{:.17g},{:.17g}\n", 0.02 * s, output(0.3 + 100.0 * rate * (1.0 + angles)));
      }
      listing += fmt::format("{},{},{},{}\n", alpha_deg, beta_deg, rate,
                             directory.write(fmt::format("r{}.csv", index++), record));
    }
  }
  return {"misalignment", "gyro", directory.write("listing.csv", listing), "--records", "--scale-factor", "100"};
}

// The example chamber ramp (0.1 Hz, pulse/s, K = 36000) with its output column passed through `output`.
std::string chamber_ramp(ScratchDirectory& directory, const std::function<double(double)>& output) {
  return testing::write_example_with(directory, "examples/temperature_model/ramp.csv", "ramp.csv", {1}, output);
}

// Bias temperature model (IEEE Std 952-1997 Annex B) of the chamber ramp.
std::vector<std::string> temperature_model(ScratchDirectory& directory, const std::function<double(double)>& output) {
  return {"temperature-model",    chamber_ramp(directory, output),
          "--temperature-column", "coil",
          "--scale-factor",       "36000",
          "--interval",           "60",
          "--stability-window",   "600",
          "--rate-window",        "600"};
}

// The example coefficients applied to the chamber ramp.
std::vector<std::string> temperature_apply(ScratchDirectory& directory, const std::function<double(double)>& output) {
  return {"temperature-apply",  chamber_ramp(directory, output),
          "--coefficients",     testing::source_path("examples/temperature_model/coefficients.json"),
          "--scale-factor",     "36000",
          "--interval",         "60",
          "--stability-window", "600"};
}

// The example IMU tumble (25 Hz) with its gyro columns passed through `output`: delta angles counted
// per sample interval (Tedaldi, Pretto and Menegatti, ICRA 2014).
std::string imu_tumble(ScratchDirectory& directory, const std::function<double(double)>& output) {
  return testing::write_example_with(directory, "examples/imu_calibration/tumble.csv", "tumble.csv", {4, 5, 6}, output);
}

std::vector<std::string> imu_calibration(ScratchDirectory& directory, const std::function<double(double)>& output) {
  return {"imu-calibration", imu_tumble(directory, output)};
}

// The calibration of the tumble in pulse/s, applied.
std::vector<std::string> imu_apply(ScratchDirectory& directory, const std::function<double(double)>& output) {
  ScratchDirectory rates;
  const std::string calibration = directory.path() + "/calibration.json";
  const auto made = run_cli({"imu-calibration", imu_tumble(rates, [](double rate) { return rate; }), "--gyro-unit",
                             "pulse/s", "--export", calibration});
  EXPECT_EQ(made.exit_code, 0) << made.err;
  return {"imu-apply", calibration, imu_tumble(directory, output)};
}

class PulseCountsCommand : public ::testing::TestWithParam<PulseCase> {};

TEST_P(PulseCountsCommand, CountsPerIntervalGiveTheFiguresOfTheRates) {
  const PulseCase& c = GetParam();
  // The figures, or null where the command refuses the data.
  const auto figures = [&](ScratchDirectory& directory, const std::function<double(double)>& output,
                           const std::string& unit) {
    std::vector<std::string> arguments = c.data(directory, output);
    arguments.insert(arguments.end(), {c.unit_flag, unit, "--json"});
    const auto run = run_cli(arguments);
    if (run.exit_code != 0) return nlohmann::json();
    std::string text = run.out;  // the files' places are not figures
    for (std::size_t at; (at = text.find(directory.path())) != std::string::npos;)
      text.replace(at, directory.path().size(), "DIR");
    return nlohmann::json::parse(text);
  };
  ScratchDirectory rates_directory;
  ScratchDirectory counts_directory;
  const double fs = c.sample_rate_hz;
  const nlohmann::json of_rates = figures(
      rates_directory, [](double rate) { return rate; }, "pulse/s");
  const nlohmann::json of_counts = figures(
      counts_directory, [fs](double rate) { return rate / fs; }, "pulse");
  ASSERT_TRUE(of_rates.is_object() && of_counts.is_object()) << c.name;
  expect_same_figures(of_counts, of_rates, c.name);
  // The counts taken as pulse/s are another instrument (or refused): the comparison above is not empty.
  EXPECT_NE(figures(
                counts_directory, [fs](double rate) { return rate / fs; }, "pulse/s")
                .dump(),
            of_rates.dump())
      << c.name;
}

INSTANTIATE_TEST_SUITE_P(RawRecords, PulseCountsCommand,
                         ::testing::Values(PulseCase{"scale_factor_records", 100.0, scale_factor_records},
                                           PulseCase{"scale_factor_record", 100.0, scale_factor_record},
                                           PulseCase{"threshold_slow_rotation", 10.0, slow_rotation},
                                           PulseCase{"bandwidth_records", 10000.0, vibration},
                                           PulseCase{"misalignment_records", 50.0, misalignment_records},
                                           PulseCase{"temperature_model", 0.1, temperature_model},
                                           PulseCase{"temperature_apply", 0.1, temperature_apply},
                                           PulseCase{"imu_calibration", 25.0, imu_calibration, "--gyro-unit"},
                                           PulseCase{"imu_apply", 25.0, imu_apply, "--gyro-unit"}),
                         [](const auto& test) { return std::string(test.param.name); });

// A table of mean outputs has no interval left to convert by: its means are taken per second, as a
// lab reports a counter's, and named pulse/s (output_unit_as_rate); the figures are those of pulse/s.
TEST(PulseCountsCommand, TablesOfMeanOutputsArePerSecond) {
  ScratchDirectory scratch;
  const std::string points =
      scratch.write("points.csv", "rate,output\n0,0.3\n10,1000.3\n-10,-999.7\n20,2000.4\n-20,-1999.7\n0,0.3\n");
  const std::string positions =
      scratch.write("positions.csv", "position,output_positive,output_negative\n1,2.1,-1.9\n2,2.3,-1.6\n");
  for (const std::vector<std::string>& arguments :
       {std::vector<std::string>{"scale-factor", points},
        std::vector<std::string>{"maximum-input-rate", points, "--nonlinearity-limit", "50"},
        std::vector<std::string>{"input-axis-misalignment", positions, "--scale-factor", "100", "--rate", "20"}}) {
    const auto run = [&](const std::string& unit) {
      std::vector<std::string> with_unit = arguments;
      with_unit.insert(with_unit.end(), {"--output-unit", unit, "--json"});
      const auto result = run_cli(with_unit);
      EXPECT_EQ(result.exit_code, 0) << result.err;
      return result.out;
    };
    const std::string per_second = run("pulse/s");
    EXPECT_EQ(run("pulse"), per_second) << arguments[0];
    if (arguments[0] != "input-axis-misalignment") {  // its figures are angles
      EXPECT_THAT(per_second, HasSubstr("pulse/s")) << arguments[0];
    }
  }
}

}  // namespace
}  // namespace inertest
