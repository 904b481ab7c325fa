// Tests for the record readers of a procedure's call (io/output_record.h).
#include "inertest/io/output_record.h"

#include <gtest/gtest.h>

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
    read_pulse_counts_as_rates(call, rate);
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

}  // namespace
}  // namespace inertest
