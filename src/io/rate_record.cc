#include "inertest/io/rate_record.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

#include "inertest/core/error.h"
#include "inertest/core/records_read.h"
#include "inertest/io/text_table.h"
#include "inertest/io/time_stamps.h"

namespace inertest {
namespace {

// A chunk in L2: the finite check and the engine's integration find the chunk there, in its ring
// (4 MiB chunks went to L3 and back: OADEV alone on 3e7 f64 samples, 9 runs alternated, wall time
// 0.253 -> 0.230 s at best, 0.271 -> 0.256 s median, when the engine still copied each chunk).
constexpr std::size_t kChunkBytes = 256u << 10;
static_assert(std::endian::native == std::endian::little, "a little-endian f64 record is read as it is stored");

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File open(const std::string& path) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) throw Error(SourceLocation{path, 0, 0}, std::string("cannot open: ") + std::strerror(errno));
  note_record_read(path);
  return file;
}

// Whether every value is finite (no NaN or Inf), vectorisable: the exponent bits of each are not all ones.
bool all_finite(const double* values, std::size_t count) {
  std::uint64_t infinite = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const auto bits = std::bit_cast<std::uint64_t>(values[i]);
    infinite |= static_cast<std::uint64_t>((bits & 0x7FF0000000000000ULL) == 0x7FF0000000000000ULL);
  }
  return infinite == 0;
}

// The first sample of values[0, count) that is not finite, as a 1-based sample number from `first`.
[[noreturn]] void throw_not_finite(const std::string& path, const double* values, std::size_t count, std::size_t first) {
  const std::size_t i = static_cast<std::size_t>(std::find_if(values, values + count, [](double v) { return !std::isfinite(v); }) - values);
  throw Error(SourceLocation{path, 0, 0}, "sample " + std::to_string(first + i + 1) + " is not a finite number");
}

// A destination of its own: a chunk of samples, handed to `sink` as each read fills it.
class SinkDestination final : public SampleDestination {
 public:
  SinkDestination(std::size_t samples, const SampleSink& sink) : samples_(samples), sink_(sink) {}
  std::span<double> room() override { return samples_; }
  void filled(std::size_t count) override { sink_(std::span<const double>(samples_.data(), count)); }

 private:
  std::vector<double> samples_;
  const SampleSink& sink_;
};

}  // namespace

std::size_t read_binary_rate_record(const RateRecordSource& source, SampleDestination& destination) {
  const std::size_t sample_size = source.binary.sample_size();
  // Little-endian f64 is read straight into the destination's slots; any other type into
  // `bytes`, then decoded there (widened, byte-swapped).
  const bool direct = source.binary.type == BinaryFormat::SampleType::kFloat64 &&
                      source.binary.endian == BinaryFormat::Endian::kLittle;
  File file = open(source.path);
  std::error_code size_error;
  const auto size = static_cast<std::size_t>(std::filesystem::file_size(source.path, size_error));
  if (size_error) throw Error(SourceLocation{source.path, 0, 0}, "cannot read its size: " + size_error.message());
  if (size % sample_size != 0) {
    throw Error(SourceLocation{source.path, 0, 0},
                "the size is not a whole number of " + std::to_string(sample_size) + "-byte samples (" +
                    std::to_string(size % sample_size) + " trailing bytes)");
  }
  const std::size_t count = size / sample_size;
  if (count == 0) throw Error(SourceLocation{source.path, 0, 0}, "no data: the file is empty");
  std::vector<char> bytes(direct ? 0 : kChunkBytes);
  for (std::size_t done = 0; done < count;) {
    const std::span<double> slots = destination.room();
    const std::size_t want = std::min({slots.size(), count - done, kChunkBytes / sample_size});
    char* const target = direct ? reinterpret_cast<char*>(slots.data()) : bytes.data();
    if (std::fread(target, sample_size, want, file.get()) != want) {
      throw Error(SourceLocation{source.path, 0, 0}, std::ferror(file.get()) ? "read error" : "the file changed while it was read");
    }
    if (!direct) decode_binary_frames(std::string_view(bytes.data(), want * sample_size), source.binary, slots.first(want));
    if (!all_finite(slots.data(), want)) throw_not_finite(source.path, slots.data(), want, done);
    destination.filled(want);
    done += want;
  }
  return count;
}

void RateRecordSource::set_format(std::string_view text) {
  if (text == "auto") {
    format = RateRecordFormat::kAuto;
  } else if (text == "csv") {
    format = RateRecordFormat::kCsv;
  } else if (text == "mat") {
    format = RateRecordFormat::kMat;
  } else if (text == "hdf5") {
    format = RateRecordFormat::kHdf5;
  } else if (text == "tdms") {
    format = RateRecordFormat::kTdms;
  } else {
    try {
      binary = BinaryFormat::parse(text);
    } catch (const Error&) {
      throw Error("unknown record format '" + std::string(text) +
                  "' (expected auto, csv, mat, hdf5, tdms, or f64, f32, i32 or i16, optionally with le or be)");
    }
    format = RateRecordFormat::kBinary;
  }
}

RateRecordFormat resolve_rate_record_format(const RateRecordSource& source) {
  if (source.format != RateRecordFormat::kAuto) return source.format;
  const std::optional<ChannelRecordFormat> detected = detect_channel_record_format(source.path);
  if (!detected) return RateRecordFormat::kCsv;
  switch (*detected) {
    case ChannelRecordFormat::kMat: return RateRecordFormat::kMat;
    case ChannelRecordFormat::kHdf5: return RateRecordFormat::kHdf5;
    case ChannelRecordFormat::kTdms: return RateRecordFormat::kTdms;
  }
  return RateRecordFormat::kCsv;
}

std::optional<ChannelRecordFormat> channel_record_format_of(RateRecordFormat format) {
  switch (format) {
    case RateRecordFormat::kMat: return ChannelRecordFormat::kMat;
    case RateRecordFormat::kHdf5: return ChannelRecordFormat::kHdf5;
    case RateRecordFormat::kTdms: return ChannelRecordFormat::kTdms;
    default: return std::nullopt;
  }
}

std::optional<double> stored_sample_rate(const RateRecordSource& source) {
  const std::optional<ChannelRecordFormat> format = channel_record_format_of(resolve_rate_record_format(source));
  if (!format) return std::nullopt;
  const std::unique_ptr<ChannelRecord> record = open_channel_record(source.path, *format);
  const std::size_t channel = record->find(source.column);
  const ChannelInfo& info = record->channels()[channel];
  if (!info.sample_rate_hz && info.sample_rate_problem.empty()) return std::nullopt;
  // A stored 0 or NaN, or a rate stated but not applicable, is an error naming it.
  return resolve_sample_rate(*record, channel, std::nullopt);
}

std::optional<std::string> resolved_unit(const RateRecordSource& source, const std::optional<std::string>& given) {
  const RateRecordFormat resolved = resolve_rate_record_format(source);
  if (resolved == RateRecordFormat::kCsv) return resolve_text_unit(source.path, source.column, given);
  const std::optional<ChannelRecordFormat> format = channel_record_format_of(resolved);
  if (!format) return given;
  const std::unique_ptr<ChannelRecord> record = open_channel_record(source.path, *format);
  return resolve_unit(*record, record->find(source.column), given);
}

std::vector<double> read_text_rate_record(const RateRecordSource& source) {
  TextTableOptions options;
  options.record_row_lines = false;
  if (source.column) options.columns = {*source.column};
  TextTable table = read_text_table(source.path, options);
  check_time_column_span(source.path, table.rows());  // a gap in its stamps, a rate that changes
  if (table.columns.size() != 1) {
    std::string names;
    for (const auto& name : table.names) names += (names.empty() ? "" : ", ") + name;
    const std::size_t first_line = table.header_line != 0 ? table.header_line : table.first_data_line;
    throw Error(SourceLocation{source.path, first_line, 1},
                "the record has " + std::to_string(table.columns.size()) + " columns" +
                    (table.header_line != 0 ? " (" + names + ")" : "") + ": choose one with --column (plan key `column`)");
  }
  return std::move(table.columns.front());
}

std::size_t read_rate_record(const RateRecordSource& source, const SampleSink& sink) {
  const RateRecordFormat format = resolve_rate_record_format(source);
  if (const std::optional<ChannelRecordFormat> channel_format = channel_record_format_of(format)) {
    const std::unique_ptr<ChannelRecord> record = open_channel_record(source.path, *channel_format);
    return stream_channel(*record, record->find(source.column), sink);
  }
  if (format == RateRecordFormat::kBinary) {
    SinkDestination chunk(kChunkBytes / source.binary.sample_size(), sink);
    return read_binary_rate_record(source, chunk);
  }
  const std::vector<double> samples = read_text_rate_record(source);
  sink(samples);
  return samples.size();
}

}  // namespace inertest
