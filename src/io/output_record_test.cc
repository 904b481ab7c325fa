// Tests for the record readers of a procedure's call (io/output_record.h).
#include "inertest/io/output_record.h"

#include <gtest/gtest.h>

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

// A counter's interval is the mean step between the gaps: stamps with a logger's jitter (+-3 ms at
// 25 Hz) average to it, and a 5 s gap does not lower it.
TEST(OutputRecord, MeanSampleRateLeavesOutTheGaps) {
  std::vector<double> time_s;
  for (int i = 0; i < 1000; ++i) time_s.push_back(0.04 * i + (i % 3 == 1 ? 0.003 : i % 3 == 2 ? -0.003 : 0.0));
  EXPECT_NEAR(mean_sample_rate_hz(time_s), 25.0, 1e-12);
  for (double& t : std::span(time_s).subspan(500)) t += 5.0;
  // The step across the gap, 5 s and a jittered 0.034 s, is left out; 5 s kept gave 22.2 Hz.
  EXPECT_NEAR(mean_sample_rate_hz(time_s), 998.0 / (0.04 * 999 - 0.034), 1e-9);
  EXPECT_NEAR(mean_sample_rate_hz(std::vector<double>{2.0, 2.5}), 2.0, 1e-15);
}

}  // namespace
}  // namespace inertest
