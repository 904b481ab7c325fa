// Streaming reader of one channel of a rate record, for records too long to hold (the Allan
// engine reads 10^9 samples through it): text (CSV, TSV, semicolon or whitespace separated,
// optional header, '#' comments), raw binary (f64, f32, i32 or i16, little- or big-endian), or a record of named channels
// (MATLAB .mat, HDF5, NI TDMS; io/channel_record.h). The file is read in chunks, never held whole:
// a record of any length passes through a few MB of buffer. Text rows are checked exactly as
// read_text_table checks them (same messages, same file:line:column).
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "inertest/io/binary_record.h"
#include "inertest/io/channel_record.h"
#include "inertest/io/text_table.h"

namespace inertest {

// kAuto: a .mat, HDF5 or TDMS record by its magic bytes (detect_channel_record_format), else text.
// Raw binary has no magic bytes: its sample type is always named (RateRecordSource::binary).
enum class RateRecordFormat { kAuto, kCsv, kBinary, kMat, kHdf5, kTdms };

struct RateRecordSource {
  std::string path;
  RateRecordFormat format = RateRecordFormat::kAuto;
  // Text: the column, by header name or 1-based index; .mat, HDF5, TDMS: the channel, by name or
  // 1-based index (io/channel_record.h). Without it the record must have one column (channel).
  std::optional<ColumnSelector> column;
  BinaryFormat binary = {};  // kBinary: the sample type and byte order (one channel)
  // "auto", "csv", "mat", "hdf5", "tdms", or raw binary: "f64", "f32", "i32" or "i16", optionally
  // with "le" or "be" ("i32be"; BinaryFormat::parse); throws Error.
  void set_format(std::string_view text);
};

// source.format with kAuto replaced by what the file holds (kMat, kHdf5, kTdms or kCsv). Throws
// Error when the file cannot be opened.
RateRecordFormat resolve_rate_record_format(const RateRecordSource& source);

// The format of a record of named channels, or nullopt for text and raw binary (after kAuto is resolved).
std::optional<ChannelRecordFormat> channel_record_format_of(RateRecordFormat format);

// The sample rate the record stores for the channel (io/channel_record.h), nullopt when it stores
// none or is text or raw binary. Throws Error as read_rate_record, and as resolve_sample_rate for a
// stored rate that is no rate or a channel with a sample_rate_problem.
std::optional<double> stored_sample_rate(const RateRecordSource& source);

// The unit of the samples: resolve_unit (io/channel_record.h) for a record of named channels,
// `given` for text and raw binary. Throws Error as resolve_unit and read_rate_record.
std::optional<std::string> resolved_unit(const RateRecordSource& source, const std::optional<std::string>& given);

using SampleSink = std::function<void(std::span<const double> samples)>;

// Reads the record from the start and hands consecutive chunks of samples to `sink`; returns the
// number of samples. A binary record and a record of named channels stream in buffers; a text
// record is parsed once, whole (see read_text_rate_record), and handed over as one chunk. Throws
// Error with file:line:column for text that is not a number, a missing column or channel, a NaN or
// infinite sample, a binary size that is not a whole number of samples, or an unreadable file.
std::size_t read_rate_record(const RateRecordSource& source, const SampleSink& sink);

// Where a reader puts the samples: room() is where the next ones go (at least one slot), and
// filled(count) says that its first `count` slots now hold them, in order. A reader that writes
// them there spares the copy from a buffer of its own (the Allan engine's ring).
class SampleDestination {
 public:
  virtual ~SampleDestination() = default;
  virtual std::span<double> room() = 0;
  virtual void filled(std::size_t count) = 0;
};

// A raw binary record (source.format kBinary) read into `destination` in chunks of 256 KiB at
// most, little-endian f64 straight into its slots; returns the number of samples. Throws Error as
// read_rate_record (a size that is not a whole number of samples before anything is read).
std::size_t read_binary_rate_record(const RateRecordSource& source, SampleDestination& destination);

// The samples of a text record (source.format csv): the file mapped and parsed once, in parallel
// chunks at line boundaries (read_text_table), into memory: 8 bytes a sample, beside the mapped
// text. Without source.column the record must have one column.
std::vector<double> read_text_rate_record(const RateRecordSource& source);

}  // namespace inertest
