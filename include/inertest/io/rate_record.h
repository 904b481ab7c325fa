// Streaming reader of one channel of a rate record, for records too long to hold (the Allan
// engine reads 10^9 samples through it): text (CSV, TSV, semicolon or whitespace separated,
// optional header, '#' comments) or raw little-endian f64/f32. The file is read in chunks, never
// held whole: a record of any length passes through a few MB of buffer. Text rows are checked
// exactly as read_text_table checks them (same messages, same file:line:column).
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "inertest/io/text_table.h"

namespace inertest {

enum class RateRecordFormat { kCsv, kFloat64, kFloat32 };

// "csv", "f64", "f32"; throws Error.
RateRecordFormat parse_rate_record_format(std::string_view text);

struct RateRecordSource {
  std::string path;
  RateRecordFormat format = RateRecordFormat::kCsv;
  // Text only: the column, by header name or 1-based index. Without it the record must have one column.
  std::optional<ColumnSelector> column;
};

using SampleSink = std::function<void(std::span<const double> samples)>;

// Reads the record from the start and hands consecutive chunks of samples to `sink`; returns the
// number of samples. A binary record streams in buffers; a text record is parsed once, whole (see
// read_text_rate_record), and handed over as one chunk. Throws Error with file:line:column for text
// that is not a number, a missing column, a NaN or infinite sample, a binary size that is not a
// whole number of samples, or an unreadable file.
std::size_t read_rate_record(const RateRecordSource& source, const SampleSink& sink);

// The samples of a text record (source.format csv): the file mapped and parsed once, in parallel
// chunks at line boundaries (read_text_table), into memory: 8 bytes a sample, beside the mapped
// text. Without source.column the record must have one column.
std::vector<double> read_text_rate_record(const RateRecordSource& source);

}  // namespace inertest
