#include "inertest/io/channel_record.h"

#include <cctype>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

#include "inertest/core/error.h"
#include "inertest/core/records_read.h"
#include "inertest/core/units.h"
#include "inertest/io/text_table.h"
#include "inertest/io/time_stamps.h"
#include "io/channel_readers.h"

namespace inertest {
namespace {

constexpr std::size_t kChunkSamples = 1u << 20;
constexpr std::array<unsigned char, 8> kHdf5Signature = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};

bool has_hdf5_signature_at(std::ifstream& file, std::uint64_t offset) {
  std::array<char, 8> bytes{};
  file.clear();
  file.seekg(static_cast<std::streamoff>(offset));
  if (!file.read(bytes.data(), bytes.size())) return false;
  return std::memcmp(bytes.data(), kHdf5Signature.data(), bytes.size()) == 0;
}

std::string channel_list(const ChannelRecord& record, bool numeric_only = false) {
  std::string names;
  for (const auto& channel : record.channels()) {
    if (!numeric_only || channel.numeric) names += (names.empty() ? "" : ", ") + channel.name;
  }
  return names.empty() ? "none" : names;
}

// "/a/b" and "a/b" name the same HDF5 dataset or TDMS channel.
std::string_view without_leading_slash(std::string_view name) {
  return !name.empty() && name.front() == '/' ? name.substr(1) : name;
}

}  // namespace

std::string_view channel_record_format_name(ChannelRecordFormat format) {
  switch (format) {
    case ChannelRecordFormat::kMat: return "mat";
    case ChannelRecordFormat::kHdf5: return "hdf5";
    case ChannelRecordFormat::kTdms: return "tdms";
  }
  return "unknown";
}

std::optional<ChannelRecordFormat> detect_channel_record_format(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(SourceLocation{path, 0, 0}, std::string("cannot open: ") + std::strerror(errno));
  std::array<char, 128> head{};
  file.read(head.data(), head.size());
  const auto got = static_cast<std::size_t>(file.gcount());
  const std::string_view start(head.data(), got);
  if (start.starts_with("TDSm")) return ChannelRecordFormat::kTdms;
  // MAT-file level 5 header (MATLAB "MAT-File Format", 1-6): 116 bytes of text, 8 of subsystem
  // offset, a 2-byte version and the endian indicator "IM" (or "MI" when written big-endian).
  if (got == head.size() && start.starts_with("MATLAB ") &&
      (start.substr(126, 2) == "IM" || start.substr(126, 2) == "MI")) {
    return ChannelRecordFormat::kMat;
  }
  // HDF5 (File Format Specification 3.0, II.A): the superblock signature at 0 or at 512, 1024,
  // 2048, ... after a user block.
  file.clear();
  file.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(file.tellg());
  for (std::uint64_t offset = 0; offset + kHdf5Signature.size() <= size; offset = offset == 0 ? 512 : offset * 2) {
    if (has_hdf5_signature_at(file, offset)) return ChannelRecordFormat::kHdf5;
  }
  return std::nullopt;
}

std::size_t ChannelRecord::find(const std::optional<ColumnSelector>& selector) const {
  const SourceLocation where{path_, 0, 0};
  std::size_t index = channels_.size();
  if (!selector) {
    std::size_t numeric = 0;
    for (std::size_t i = 0; i < channels_.size(); ++i) {
      if (channels_[i].numeric) {
        ++numeric;
        index = i;
      }
    }
    if (numeric != 1) {
      throw Error(where, fmt::format("the record has {} numeric channels ({}): choose one with --column (plan key "
                                     "`column`)",
                                     numeric, channel_list(*this, true)));
    }
    return index;
  }
  if (selector->index > 0) {
    if (selector->index > channels_.size()) {
      throw Error(where, fmt::format("channel {} asked for, but the record has {} channels ({})", selector->index,
                                     channels_.size(), channel_list(*this)));
    }
    index = selector->index - 1;
  } else {
    const std::string_view wanted = without_leading_slash(selector->name);
    const auto it = std::find_if(channels_.begin(), channels_.end(),
                                 [&](const ChannelInfo& c) { return without_leading_slash(c.name) == wanted; });
    if (it == channels_.end()) {
      throw Error(where, fmt::format("no channel '{}' in the record (channels: {})", selector->name, channel_list(*this)));
    }
    index = static_cast<std::size_t>(it - channels_.begin());
  }
  if (!channels_[index].numeric) {
    throw Error(where, fmt::format("channel '{}' holds {} values, not numbers", channels_[index].name,
                                   channels_[index].type));
  }
  return index;
}

std::unique_ptr<ChannelRecord> open_channel_record(const std::string& path, ChannelRecordFormat format) {
  note_record_read(path);
  switch (format) {
    case ChannelRecordFormat::kMat: return open_mat_record(path);
    case ChannelRecordFormat::kHdf5: return open_hdf5_record(path);
    case ChannelRecordFormat::kTdms: return open_tdms_record(path);
  }
  throw Error(SourceLocation{path, 0, 0}, "unknown record format");
}

std::size_t stream_channel(ChannelRecord& record, std::size_t channel,
                           const std::function<void(std::span<const double>)>& sink) {
  const ChannelInfo& info = record.channels().at(channel);
  if (info.length == 0) throw Error(SourceLocation{record.path(), 0, 0}, fmt::format("channel '{}' holds no samples", info.name));
  std::vector<double> buffer(static_cast<std::size_t>(std::min<std::uint64_t>(info.length, kChunkSamples)));
  for (std::uint64_t first = 0; first < info.length; first += buffer.size()) {
    const std::span<double> chunk(buffer.data(),
                                  static_cast<std::size_t>(std::min<std::uint64_t>(buffer.size(), info.length - first)));
    record.read(channel, first, chunk);
    for (std::size_t i = 0; i < chunk.size(); ++i) {
      if (!std::isfinite(chunk[i])) {
        throw Error(SourceLocation{record.path(), 0, 0},
                    fmt::format("channel '{}': sample {} is not a finite number", info.name, first + i + 1));
      }
    }
    sink(chunk);
  }
  return static_cast<std::size_t>(info.length);
}

std::vector<double> read_channel(ChannelRecord& record, std::size_t channel) {
  std::vector<double> samples;
  // A corrupt file may claim any length: reserve at most what one chunk proves readable.
  samples.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(record.channels().at(channel).length, kChunkSamples)));
  stream_channel(record, channel, [&](std::span<const double> chunk) { samples.insert(samples.end(), chunk.begin(), chunk.end()); });
  return samples;
}

double resolve_sample_rate(const ChannelRecord& record, std::size_t channel, std::optional<double> given) {
  const ChannelInfo& info = record.channels().at(channel);
  const SourceLocation where{record.path(), 0, 0};
  if (!info.sample_rate_problem.empty()) {
    throw Error(where, fmt::format("channel '{}': {}", info.name, info.sample_rate_problem));
  }
  if (info.sample_rate_hz && !(*info.sample_rate_hz > 0.0 && std::isfinite(*info.sample_rate_hz))) {
    if (given) return *given;  // a stored rate of 0 or NaN is no rate: the given one stands
    throw Error(where, fmt::format("channel '{}' stores the sample rate {} Hz, which is no rate: give it (--rate / "
                                   "sample_rate_hz)",
                                   info.name, *info.sample_rate_hz));
  }
  if (!info.sample_rate_hz) {
    if (!given) throw Error(where, fmt::format("channel '{}' stores no sample rate: give it (--rate / sample_rate_hz)", info.name));
    return *given;
  }
  // Within a single float's precision: a wf_increment of 0.01 s stored as f32 is 100.0000022 Hz
  // (the contradictions this finds are factors, 10 Hz taken as 100).
  if (given && std::abs(*given - *info.sample_rate_hz) > 1e-7 * std::abs(*info.sample_rate_hz)) {
    throw Error(where, fmt::format("the sample rate given, {} Hz, contradicts the {} Hz stored for channel '{}'", *given,
                                   *info.sample_rate_hz, info.name));
  }
  return *info.sample_rate_hz;
}

std::optional<std::string> resolve_unit(const ChannelRecord& record, std::size_t channel,
                                        const std::optional<std::string>& given) {
  const ChannelInfo& info = record.channels().at(channel);
  const SourceLocation where{record.path(), 0, 0};
  if (!info.unit_problem.empty()) throw Error(where, fmt::format("channel '{}': {}", info.name, info.unit_problem));
  if (info.unit.empty()) return given;
  try {
    Unit::parse(info.unit);
  } catch (const Error&) {
    if (given) return given;  // the stored unit is no unit inertest knows: the given one is taken as is
    throw Error(where, fmt::format("channel '{}' stores the unit '{}', which inertest does not know: correct the "
                                   "file's, or give the unit of the samples where the command takes one (--input-unit "
                                   "/ input_unit)",
                                   info.name, info.unit));
  }
  return resolve_stated_unit(where, fmt::format("stored for channel '{}'", info.name), info.unit, given);
}

std::optional<std::string> resolve_stated_unit(const SourceLocation& where, const std::string& stated_where,
                                               const std::string& stated, const std::optional<std::string>& given) {
  if (!given) return stated;
  if (!same_unit(*given, stated)) {
    throw Error(where, fmt::format("the unit given, {}, contradicts the unit {} {}", *given, stated, stated_where));
  }
  return given;
}

namespace {

// Bracketed text that names an angle or an angular rate in any case ("Deg s-1", "°/sec", "mdps",
// "度/秒"): a unit inertest does not read, not a note ("raw", "inc/s"), which read as none took the
// samples in deg/h.
bool names_an_angle(std::string_view text) {
  std::string lowered(text);
  for (char& c : lowered) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* mark : {"deg", "rad", "dps", "dph", "rpm", "\u00b0", "\u00ba", "\u5ea6"}) {  // °, º, 度
    if (lowered.find(mark) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

std::optional<std::string> unit_stated_in_name(std::string_view name, const SourceLocation& where) {
  while (!name.empty() && name.back() == ' ') name.remove_suffix(1);
  if (name.size() < 3 || (name.back() != ']' && name.back() != ')')) return std::nullopt;
  const std::size_t open = name.find_last_of(name.back() == ']' ? '[' : '(');
  if (open == std::string_view::npos || open == 0) return std::nullopt;  // the quantity's name comes first
  std::string_view inside = name.substr(open + 1, name.size() - open - 2);
  while (!inside.empty() && inside.front() == ' ') inside.remove_prefix(1);
  while (!inside.empty() && inside.back() == ' ') inside.remove_suffix(1);
  try {
    if (Unit::parse(inside).dimension() == Dimension{}) return std::nullopt;  // "[1]", "(%)": no quantity's unit
  } catch (const Error&) {
    // "(raw)", "[x]": a note, not a unit; "[deg s-1]" is a unit inertest does not read, and read as
    // none the samples were taken in deg/h, 3600 times off.
    if (!names_an_angle(inside)) return std::nullopt;
    throw Error(where, fmt::format("column '{}': '{}' reads as a unit inertest does not know; write it as deg/s, "
                                   "deg/h, rad/s...",
                                   name, inside));
  }
  return std::string(inside);
}

std::optional<std::string> resolve_text_unit(const std::string& path, const std::optional<ColumnSelector>& column,
                                             const std::optional<std::string>& given) {
  const std::optional<RecordHead> head = read_record_head(path);
  if (!head) return given;  // a pipe, or text the record's reader refuses with its own message
  const TextTableHeader& header = head->header;
  const std::vector<std::string>& names = header.names;
  std::string name;
  if (column && column->index == 0) {
    name = column->name;
  } else if (column && column->index <= names.size()) {
    name = names[column->index - 1];
  } else if (!column && names.size() == 1) {
    name = names[0];
  }
  std::optional<std::string> stated;
  try {
    stated = unit_stated_in_name(name, SourceLocation{path, header.line, 0});
  } catch (const Error&) {
    if (given) return given;  // the unit given says what the header's does not
    throw;
  }
  if (!stated) return given;
  return resolve_stated_unit(SourceLocation{path, header.line, 0}, fmt::format("the header states for column '{}'", name),
                             *stated, given);
}

std::string channel_range_context(const ChannelInfo& channel, std::uint64_t first, std::size_t count) {
  return fmt::format("channel '{}', samples {}..{}", channel.name, first + 1, first + count);
}

}  // namespace inertest
