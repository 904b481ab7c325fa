// Tests for the record readers of a procedure's call (io/output_record.h).
#include "inertest/io/output_record.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <span>
#include <vector>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using testing::ScratchDirectory;

// Pulse counts per sample interval become pulse/s at the rate given or stored; a record with
// neither is an error naming it, not counts taken as a rate.
TEST(OutputRecord, PulseCountsNeedASampleRate) {
  ScratchDirectory scratch;
  const std::string bare = scratch.write("counts.txt", "3\n5\n4\n");
  const std::string timed = scratch.write("counts.csv", "time_s,output\n0.01,3\n0.02,5\n0.03,4\n");
  const auto reading = [](const std::string& file, std::optional<double> rate, const std::string& unit) {
    ProcedureCall call;
    call.parameters["output_unit"] = unit;
    OutputRecordSource source;
    source.path = file;
    set_record_readers(call, source, 1, std::nullopt, "");
    ProcedureSpec spec;
    spec.inputs = {InputSpec("record", "output record").read_from_file("FILE", "file").output_records()};
    read_pulse_counts_as_rates(
        call, spec, [](const InputSpec&) { return true; }, rate);
    return call;
  };
  EXPECT_EQ(reading(bare, 100.0, "pulse").read_record(bare), (std::vector<double>{300.0, 500.0, 400.0}));
  EXPECT_EQ(reading(bare, 100.0, "Pulses").parameters.at("output_unit"), "pulse/s");
  EXPECT_EQ(reading(timed, std::nullopt, "pulse").read_record(timed), (std::vector<double>{300.0, 500.0, 400.0}));
  EXPECT_EQ(reading(bare, 100.0, "pulse/s").read_record(bare), (std::vector<double>{3.0, 5.0, 4.0}));
  EXPECT_EQ(reading(bare, 100.0, "count").read_record(bare), (std::vector<double>{3.0, 5.0, 4.0}));  // levels
  EXPECT_EQ(reading(bare, 100.0, "LSB").read_record(bare), (std::vector<double>{3.0, 5.0, 4.0}));
  const std::string one_stamp = scratch.write("one.csv", "time_s,output\n0.01,3\n");
  try {
    reading(one_stamp, std::nullopt, "pulse").read_timed_record(one_stamp);
    ADD_FAILURE() << "one count without an interval was read";
  } catch (const Error& e) {
    EXPECT_NE(e.message().find("stores no sample rate"), std::string::npos) << e.message();
  }
  try {
    reading(bare, std::nullopt, "pulse").read_record(bare);
    ADD_FAILURE() << "counts without a rate were read";
  } catch (const Error& e) {
    EXPECT_EQ(e.location().value().file, bare);
    EXPECT_NE(e.message().find("stores no sample rate"), std::string::npos) << e.message();
  }
}

// Pulse counts: a table of mean outputs is named per second, unconverted; raw samples a procedure
// reads itself are its to convert (call.pulse_counts); values alone (polarity's signs) are left as
// they are.
TEST(OutputRecord, PulseCountsOfTablesAndOfOwnReaders) {
  const auto call_with = [](const InputSpec& input, const std::string& unit) {
    ProcedureCall call;
    call.parameters["output_unit"] = unit;
    ProcedureSpec spec;
    spec.inputs = {input};
    read_pulse_counts_as_rates(
        call, spec, [](const InputSpec&) { return true; }, std::nullopt);
    return call;
  };
  const ProcedureCall table =
      call_with(InputSpec("points", "CSV of test points").read_from_file("POINTS", "file"), "pulse");
  EXPECT_FALSE(table.pulse_counts);
  EXPECT_EQ(table.parameters.at("output_unit"), "pulse/s");
  const ProcedureCall own =
      call_with(InputSpec("record", "long record").read_from_file("--record", "record").holds_raw_samples(), "pulses");
  EXPECT_TRUE(own.pulse_counts);
  EXPECT_EQ(own.parameters.at("output_unit"), "pulse/s");
  EXPECT_FALSE(own.read_record);  // no output records: the procedure reads and converts them
  const ProcedureCall values = call_with(InputSpec("positive", "the output at the positive rate"), "pulse");
  EXPECT_FALSE(values.pulse_counts);
  EXPECT_EQ(values.parameters.at("output_unit"), "pulse");
  EXPECT_EQ(output_unit_as_rate("V"), "V");
}

// A counter's interval is the mean step between a logger's gaps (5 s lost at 25 Hz does not lower
// the rate, also with +-3 ms of jitter), and the steps over the span where the long steps are no
// dropped samples: stamps rounded to 1 ms at 800 Hz (steps of 1 and 2 ms, a quarter of them over 1.5
// median steps), +-12 ms of jitter at 25 Hz, packets of 4 stamps 1 ms apart at 25 Hz, and three
// stamps of which one step is twice the other (each read too high when their long steps were left out).
TEST(OutputRecord, MeanSampleRateLeavesOutTheGapsOfALogger) {
  const auto stamps = [](double rate, std::size_t n, const std::function<double(std::size_t)>& offset) {
    std::vector<double> time_s;
    for (std::size_t i = 0; i < n; ++i) time_s.push_back(static_cast<double>(i) / rate + offset(i));
    return time_s;
  };
  const auto none = [](std::size_t) { return 0.0; };
  testing::UniformSequence uniform(7);
  for (const double jitter_s : {0.0, 0.006}) {
    std::vector<double> time_s = stamps(25.0, 2000, [&](std::size_t) { return jitter_s * uniform.next(); });
    for (double& t : std::span(time_s).subspan(1000)) t += 5.0;
    // 5 s kept in the span gave 23.5 Hz; the jitter of the four stamps that bound the runs, 12 ms at most over
    // 80 s, moves the rate by up to 0.004 Hz.
    EXPECT_NEAR(mean_sample_rate_hz(time_s), 25.0, jitter_s == 0.0 ? 1e-9 : 0.004) << jitter_s;
  }
  std::vector<double> rounded = stamps(800.0, 8000, none);
  for (double& t : rounded) t = std::round(t * 1000.0) / 1000.0;
  EXPECT_NEAR(mean_sample_rate_hz(rounded), 800.0, 0.1);
  // Coarse stamps and a logger's gap together (0.8 Hz in whole seconds, 10 % lost in one outage): the
  // outage is left out, to the rounding of its two stamps (it read 0.72 Hz, every figure 10 % low).
  std::vector<double> seconds;
  for (const double t : stamps(0.8, 16800, none)) {
    if (t < 10000.0 || t >= 10000.0 + 1680 / 0.8) seconds.push_back(std::floor(t));
  }
  EXPECT_NEAR(mean_sample_rate_hz(seconds), 0.8, 0.8 * 2.0 / 15120.0);
  EXPECT_NEAR(mean_sample_rate_hz(stamps(25.0, 2000, [&](std::size_t) { return 0.024 * uniform.next(); })), 25.0, 0.01);
  EXPECT_NEAR(mean_sample_rate_hz(stamps(25.0, 2001, [](std::size_t i) { return (i % 4) * (0.001 - 0.04); })), 25.0,
              0.01);
  EXPECT_NEAR(mean_sample_rate_hz(std::vector<double>{0.0, 0.01, 0.03}), 2.0 / 0.03, 1e-12);
}

}  // namespace
}  // namespace inertest
