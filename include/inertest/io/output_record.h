// Reading one instrument-output record for the procedures that work on sampled output (bias,
// turn-on time, threshold method 3, polarity): a text record (one column chosen by name or
// 1-based position, optionally with a time column) or a raw binary record (f64, f32, ...).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace inertest {

struct OutputRecordSource {
  std::string path;
  // Empty: a text record. Otherwise a binary format as BinaryFormat::parse reads it ("f64", "f32be").
  std::string format;
  // Text records: the output column by header name or 1-based index ("2"); empty means the only
  // column, or the second when a time column is read. Ignored for binary records.
  std::string column;
};

// The output column as doubles. Throws Error naming the file (and line/column in a text record)
// when it is missing, malformed, or holds fewer than minimum_samples samples.
std::vector<double> read_output_record(const OutputRecordSource& source, std::size_t minimum_samples = 1);

// A record with the time of each sample in seconds since power-on (or since the record's start).
struct TimedRecord {
  std::vector<double> time_s;
  std::vector<double> output;
};

// With sample_rate_hz: the output column alone; sample i (0-based) gets the time (i + 1) / rate,
// the end of the interval over which the instrument accumulated it. Without: a text record with a
// time column (time_column by name or index; empty means the first column) and the output column
// (source.column; empty means the second column). Times must increase strictly; a violation is an
// Error naming the line.
TimedRecord read_timed_record(const OutputRecordSource& source, std::optional<double> sample_rate_hz,
                              const std::string& time_column = "", std::size_t minimum_samples = 1);

}  // namespace inertest
