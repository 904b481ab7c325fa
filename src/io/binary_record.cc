#include "inertest/io/binary_record.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "inertest/core/error.h"
#include "inertest/io/mapped_file.h"

namespace inertest {
namespace {

template <typename Unsigned>
Unsigned byte_swap(Unsigned value) {
  Unsigned swapped = 0;
  for (std::size_t i = 0; i < sizeof(Unsigned); ++i) {
    swapped = static_cast<Unsigned>((swapped << 8) | ((value >> (8 * i)) & 0xFF));
  }
  return swapped;
}

template <typename Sample, typename Unsigned>
void decode(std::string_view bytes, const BinaryFormat& format, std::span<double> out) {
  static_assert(sizeof(Sample) == sizeof(Unsigned));
  const bool swap = (format.endian == BinaryFormat::Endian::kBig) != (std::endian::native == std::endian::big);
  const std::size_t frame = format.frame_size();
  const std::size_t count = std::min(bytes.size() / frame, out.size());
  const char* base = bytes.data() + format.channel * sizeof(Sample);
  for (std::size_t i = 0; i < count; ++i) {
    Unsigned raw = 0;
    std::memcpy(&raw, base + i * frame, sizeof(raw));
    if (swap) raw = byte_swap(raw);
    out[i] = static_cast<double>(std::bit_cast<Sample>(raw));
  }
}

}  // namespace

BinaryFormat BinaryFormat::parse(std::string_view text) {
  BinaryFormat format;
  std::string_view type = text;
  if (text.size() > 2 && (text.ends_with("le") || text.ends_with("be"))) {
    format.endian = text.ends_with("be") ? Endian::kBig : Endian::kLittle;
    type = text.substr(0, text.size() - 2);
  }
  if (type == "f64") {
    format.type = SampleType::kFloat64;
  } else if (type == "f32") {
    format.type = SampleType::kFloat32;
  } else if (type == "i32") {
    format.type = SampleType::kInt32;
  } else if (type == "i16") {
    format.type = SampleType::kInt16;
  } else {
    throw Error("unknown binary format '" + std::string(text) + "' (expected f64, f32, i32 or i16, optionally with le or be)");
  }
  return format;
}

std::size_t BinaryFormat::sample_size() const {
  switch (type) {
    case SampleType::kFloat64: return 8;
    case SampleType::kFloat32: return 4;
    case SampleType::kInt32: return 4;
    case SampleType::kInt16: return 2;
  }
  return 8;
}

void decode_binary_frames(std::string_view bytes, const BinaryFormat& format, std::span<double> out) {
  switch (format.type) {
    case BinaryFormat::SampleType::kFloat64: decode<double, std::uint64_t>(bytes, format, out); break;
    case BinaryFormat::SampleType::kFloat32: decode<float, std::uint32_t>(bytes, format, out); break;
    case BinaryFormat::SampleType::kInt32: decode<std::int32_t, std::uint32_t>(bytes, format, out); break;
    case BinaryFormat::SampleType::kInt16: decode<std::int16_t, std::uint16_t>(bytes, format, out); break;
  }
}

std::vector<double> decode_binary_record(std::string_view bytes, const std::string& source, const BinaryFormat& format) {
  if (format.channels == 0 || format.channel >= format.channels) {
    throw Error(SourceLocation{source, 0, 0}, "channel " + std::to_string(format.channel + 1) + " of " +
                                                  std::to_string(format.channels) + " does not exist");
  }
  if (bytes.empty()) throw Error(SourceLocation{source, 0, 0}, "no data: the file is empty");
  const std::size_t frame = format.frame_size();
  if (bytes.size() % frame != 0) {
    throw Error(SourceLocation{source, 0, 0},
                "size " + std::to_string(bytes.size()) + " bytes is not a multiple of the " + std::to_string(frame) +
                    "-byte frame: " + std::to_string(bytes.size() % frame) + " trailing bytes (truncated record?)");
  }
  std::vector<double> values(bytes.size() / frame);
  decode_binary_frames(bytes, format, values);
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw Error(SourceLocation{source, 0, 0}, "sample " + std::to_string(i + 1) + " (byte offset " +
                                                    std::to_string(i * frame) + ") is NaN or Inf");
    }
  }
  return values;
}

std::vector<double> read_binary_record(const std::string& path, const BinaryFormat& format) {
  const MappedFile file(path);
  return decode_binary_record(file.bytes(), path, format);
}

}  // namespace inertest
