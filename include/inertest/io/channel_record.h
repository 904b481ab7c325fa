// Records whose channels carry names, as labs save them (issue 21): MATLAB .mat (v5, v7 compressed,
// v7.3), HDF5 and National Instruments TDMS. The format is found by the file's magic bytes, never
// by its extension. A channel is selected as a text column is: by name or by 1-based position among
// the channels listed. Names: HDF5 "group/dataset" (a leading '/' may be given), MAT "variable" or
// "struct.field" (nested: "a.b.c"), TDMS "group/channel" (the group and channel names, unquoted).
// Channels are read in ranges, so a record of 10^9 samples streams through a few MB of buffer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "inertest/io/text_table.h"

namespace inertest {

enum class ChannelRecordFormat { kMat, kHdf5, kTdms };

// "mat", "hdf5", "tdms".
std::string_view channel_record_format_name(ChannelRecordFormat format);

// The format of a file by its magic bytes: "MATLAB 5.0 MAT-file" with a version and endian
// indicator at bytes 124..127 (v5, v7; v7.3 when the HDF5 signature follows at 512), the HDF5
// signature \x89HDF\r\n\x1a\n at byte 0, 512, 1024, 2048, ... (a user block), or the TDMS lead-in
// "TDSm" at byte 0. nullopt for anything else (text, raw binary). Throws Error when the file cannot
// be opened.
std::optional<ChannelRecordFormat> detect_channel_record_format(const std::string& path);

// One channel of a record. `type` names the stored sample type: "f64", "f32", "i8".."i64",
// "u8".."u64", "bool" for numbers; anything else ("string", "timestamp", "complex", "struct") is
// listed but cannot be read as samples (numeric is false).
struct ChannelInfo {
  std::string name;
  std::string type;
  bool numeric = true;
  std::uint64_t length = 0;
  std::string unit;                       // the file's `units` / `unit_string`; empty when absent
  // Why the file's unit cannot be used although it states one (an HDF5 `units` attribute that is
  // not one string); empty when there is no such problem. unit is then empty, and resolve_unit
  // refuses the channel.
  std::string unit_problem;
  std::optional<double> sample_rate_hz;   // stored: 1 / wf_increment, or a sample_rate_hz attribute
  // Why no stored rate applies although the file states one (a TDMS wf_increment that changes
  // between segments, an HDF5 rate attribute that is not one number); empty when there is no such
  // problem. sample_rate_hz is then nullopt, and
  // resolve_sample_rate refuses the channel: the samples are readable, their rate is not.
  std::string sample_rate_problem;
  std::optional<double> start_time_s;     // stored wf_start_time, in seconds since 1970-01-01 UTC
};

// An open record. Not safe to share between threads.
class ChannelRecord {
 public:
  virtual ~ChannelRecord() = default;
  ChannelRecord(const ChannelRecord&) = delete;
  ChannelRecord& operator=(const ChannelRecord&) = delete;

  const std::string& path() const { return path_; }
  ChannelRecordFormat format() const { return format_; }
  const std::vector<ChannelInfo>& channels() const { return channels_; }

  // The 0-based index of the channel chosen by name or 1-based position. Without a selector the
  // record must hold exactly one numeric channel. Throws Error naming the file and listing the
  // channels when there is no such channel, or it is not numeric.
  std::size_t find(const std::optional<ColumnSelector>& selector) const;

  // Samples [first, first + out.size()) of a numeric channel, converted to double. Throws Error
  // naming the file, the channel and the offset when the range lies beyond the channel or the
  // stored data cannot be read (truncated, corrupt).
  virtual void read(std::size_t channel, std::uint64_t first, std::span<double> out) = 0;

 protected:
  ChannelRecord(std::string path, ChannelRecordFormat format) : path_(std::move(path)), format_(format) {}
  std::vector<ChannelInfo> channels_;

 private:
  std::string path_;
  ChannelRecordFormat format_;
};

// Opens a record of the given format and lists its channels. Throws Error naming the file (and the
// byte offset or object) when it is not a readable record of that format.
std::unique_ptr<ChannelRecord> open_channel_record(const std::string& path, ChannelRecordFormat format);

// Reads a channel from the start, handing consecutive chunks of at most 1 Mi samples to `sink`;
// returns the number of samples. A NaN or infinite sample is an Error naming the channel and the
// 1-based sample number, raised before that sample's chunk is handed over.
std::size_t stream_channel(ChannelRecord& record, std::size_t channel,
                           const std::function<void(std::span<const double>)>& sink);

// The whole channel, as stream_channel checks it.
std::vector<double> read_channel(ChannelRecord& record, std::size_t channel);

// The sample rate to use: the stored one, or `given` when the record stores none. Throws Error
// naming the file, the channel and both values when they differ by more than 1e-7 relative, when
// neither is known, and naming the file, the channel and the problem when the channel has a
// sample_rate_problem (given or not).
double resolve_sample_rate(const ChannelRecord& record, std::size_t channel, std::optional<double> given);

// The unit of the samples to use: `given`, or the stored one (HDF5 `units`, TDMS `unit_string`)
// when none is given; nullopt when neither is known. Throws Error naming the file, the channel and
// both units when they differ (as units: "deg/s" and "°/s" agree), for a stored unit inertest
// does not know when none is given, and naming the problem when the channel has a unit_problem
// (given or not).
std::optional<std::string> resolve_unit(const ChannelRecord& record, std::size_t channel,
                                        const std::optional<std::string>& given);

// A unit a record states (`stated_where`: "stored for channel 'g'") against the one given: the
// stated one when none is given, the given one when they agree as units, else an Error at `where`
// naming both.
std::optional<std::string> resolve_stated_unit(const SourceLocation& where, const std::string& stated_where,
                                               const std::string& stated, const std::optional<std::string>& given);

// The unit a text column's header name states at its end, in brackets or parentheses ("gyro_x
// [deg/s]", "rate (deg/h)"): one inertest knows and not a bare ratio (1, ppm, %); nullopt for none
// or a note ("(raw)", "(inc/s)"); an Error at `where` for text that names an angle or a rate in a
// unit inertest does not read ("[deg s-1]", "(mdps)"), which resolve_text_unit lets a unit given
// override.
std::optional<std::string> unit_stated_in_name(std::string_view name, const SourceLocation& where);

// resolve_unit for a text record: the unit its header states for the column (by name, by 1-based
// index, or without one the only column), against `given`.
// A record without a header, or whose header states no unit for the column, gives `given`.
std::optional<std::string> resolve_text_unit(const std::string& path, const std::optional<ColumnSelector>& column,
                                             const std::optional<std::string>& given);

}  // namespace inertest
