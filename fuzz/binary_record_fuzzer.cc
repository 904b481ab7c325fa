// Fuzzes the binary reader: any bytes, with the sample type, byte order and channel layout taken
// from the first two bytes, must decode or give an inertest::Error; never a crash or other exception.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "inertest/core/error.h"
#include "inertest/io/binary_record.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  inertest::BinaryFormat format;
  format.type = static_cast<inertest::BinaryFormat::SampleType>(data[0] & 3);
  format.endian = (data[0] & 4) ? inertest::BinaryFormat::Endian::kBig : inertest::BinaryFormat::Endian::kLittle;
  format.channels = data[1] & 7;        // 0 is invalid on purpose: it must be an Error
  format.channel = (data[1] >> 3) & 7;  // may lie outside channels: an Error
  const std::string_view bytes(reinterpret_cast<const char*>(data + 2), size - 2);
  try {
    const auto values = inertest::decode_binary_record(bytes, "fuzz.bin", format);
    if (values.size() * format.frame_size() != bytes.size()) __builtin_trap();
  } catch (const inertest::Error&) {
  }
  return 0;
}
