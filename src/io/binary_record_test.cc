#include "inertest/io/binary_record.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

template <typename T>
std::string bytes_of(const std::vector<T>& values, bool big_endian) {
  std::string bytes(values.size() * sizeof(T), '\0');
  std::memcpy(bytes.data(), values.data(), bytes.size());
  if (big_endian) {
    for (std::size_t i = 0; i < values.size(); ++i) {
      std::reverse(bytes.begin() + static_cast<std::ptrdiff_t>(i * sizeof(T)),
                   bytes.begin() + static_cast<std::ptrdiff_t>((i + 1) * sizeof(T)));
    }
  }
  return bytes;
}

TEST(BinaryRecord, EveryTypeAndEndianness) {
  for (bool big : {false, true}) {
    const char* suffix = big ? "be" : "le";
    EXPECT_EQ(decode_binary_record(bytes_of<double>({1.5, -2.25}, big), "r", BinaryFormat::parse(std::string("f64") + suffix)),
              (std::vector<double>{1.5, -2.25}));
    EXPECT_EQ(decode_binary_record(bytes_of<float>({0.5F, 3.0F}, big), "r", BinaryFormat::parse(std::string("f32") + suffix)),
              (std::vector<double>{0.5, 3.0}));
    EXPECT_EQ(decode_binary_record(bytes_of<std::int32_t>({-7, 100000}, big), "r",
                                   BinaryFormat::parse(std::string("i32") + suffix)),
              (std::vector<double>{-7, 100000}));
    EXPECT_EQ(decode_binary_record(bytes_of<std::int16_t>({-32768, 12}, big), "r",
                                   BinaryFormat::parse(std::string("i16") + suffix)),
              (std::vector<double>{-32768, 12}));
  }
}

TEST(BinaryRecord, InterleavedChannel) {
  BinaryFormat format = BinaryFormat::parse("i16");
  format.channels = 3;
  format.channel = 1;
  EXPECT_EQ(decode_binary_record(bytes_of<std::int16_t>({1, 2, 3, 4, 5, 6}, false), "r", format),
            (std::vector<double>{2, 5}));
}

TEST(BinaryRecord, BadInputIsNamed) {
  using ::testing::HasSubstr;
  auto message = [](std::string_view bytes, const BinaryFormat& format) {
    try {
      decode_binary_record(bytes, "rec.bin", format);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message(std::string(12, '\0'), BinaryFormat::parse("f64")),
              HasSubstr("rec.bin: size 12 bytes is not a multiple of the 8-byte frame: 4 trailing bytes"));
  EXPECT_THAT(message("", BinaryFormat::parse("f32")), HasSubstr("rec.bin: no data"));
  EXPECT_THAT(message(bytes_of<double>({1.0, std::numeric_limits<double>::quiet_NaN()}, false), BinaryFormat::parse("f64")),
              HasSubstr("sample 2 (byte offset 8) is NaN or Inf"));
  EXPECT_THROW(BinaryFormat::parse("f16"), Error);
  BinaryFormat bad_channel;
  bad_channel.channels = 2;
  bad_channel.channel = 2;
  EXPECT_THAT(message(std::string(16, '\0'), bad_channel), HasSubstr("does not exist"));
}

TEST(BinaryRecord, ReadsThroughTheMemoryMap) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("r.f64", bytes_of<double>({1.0, 2.0, 4.0}, false));
  EXPECT_EQ(read_binary_record(path, BinaryFormat{}), (std::vector<double>{1.0, 2.0, 4.0}));
}

}  // namespace
}  // namespace inertest
