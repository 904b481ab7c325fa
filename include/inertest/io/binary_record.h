// Raw binary lab records: interleaved channels of f64, f32, i32 or i16 samples, little or big
// endian. Read through a memory map; a size that is not a whole number of frames is an Error.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace inertest {

struct BinaryFormat {
  enum class SampleType { kFloat64, kFloat32, kInt32, kInt16 };
  enum class Endian { kLittle, kBig };
  SampleType type = SampleType::kFloat64;
  Endian endian = Endian::kLittle;
  std::size_t channels = 1;  // interleaved channels per frame
  std::size_t channel = 0;   // 0-based channel to read

  // "f64", "f32", "i32", "i16", optionally followed by "le" or "be" ("f32be"); throws Error.
  static BinaryFormat parse(std::string_view text);
  std::size_t sample_size() const;
  std::size_t frame_size() const { return sample_size() * channels; }
};

// Decodes the whole frames of bytes, format.channel of each, into out (as many as both hold); no
// other check.
void decode_binary_frames(std::string_view bytes, const BinaryFormat& format, std::span<double> out);

// Reads one channel of a binary record as doubles. Throws Error for an empty file, a size that is
// not a multiple of the frame size (naming the trailing byte count), or a NaN/Inf sample (naming
// the sample index).
std::vector<double> read_binary_record(const std::string& path, const BinaryFormat& format);

// Same, on bytes already in memory; `source` names them in messages.
std::vector<double> decode_binary_record(std::string_view bytes, const std::string& source, const BinaryFormat& format);

}  // namespace inertest
