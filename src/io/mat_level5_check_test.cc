// The MAT level-5 header check against layouts built here byte by byte (MATLAB's "MAT-File Format",
// chapter 1): the legitimate ones pass and the records' channels open; counts a variable cannot hold
// are refused before matio allocates for them.
#include "io/mat_level5_check.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "inertest/core/error.h"
#include "inertest/io/channel_record.h"
#include "inertest/io/text_table.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using Bytes = std::string;

Bytes u32(std::uint32_t a, std::uint32_t b) {
  Bytes out(8, '\0');
  std::memcpy(out.data(), &a, 4);
  std::memcpy(out.data() + 4, &b, 4);
  return out;
}

// A data element: its tag, its data, padded to 8 bytes.
Bytes element(std::uint32_t type, const Bytes& data) {
  return u32(type, static_cast<std::uint32_t>(data.size())) + data + Bytes((8 - data.size() % 8) % 8, '\0');
}

constexpr std::uint32_t kMiInt8 = 1, kMiInt32 = 5, kMiUint32 = 6, kMiDouble = 9, kMiMatrix = 14, kMiInt16 = 3;

Bytes matrix(std::uint32_t array_class, std::uint32_t rows, std::uint32_t columns, const std::string& name,
             const Bytes& rest) {
  return element(kMiMatrix, element(kMiUint32, u32(array_class, 0)) + element(kMiInt32, u32(rows, columns)) +
                                element(kMiInt8, name) + rest);
}

Bytes doubles(const std::string& name, std::uint32_t count) {
  Bytes values(count * 8, '\0');
  for (std::uint32_t i = 0; i < count; ++i) {
    const double v = i;
    std::memcpy(values.data() + 8 * i, &v, 8);
  }
  return matrix(6, count, 1, name, element(kMiDouble, values));
}

// A v5 file: the 128-byte header, the variable under test, then a 64-sample channel "rate".
std::string write_mat(testing::ScratchDirectory& dir, const Bytes& variable) {
  Bytes header = "MATLAB 5.0 MAT-file, inertest test";
  header.resize(124, ' ');
  header += Bytes("\x00\x01IM", 4);
  return dir.write("v.mat", header + variable + doubles("rate", 64));
}

Bytes field_names(std::uint32_t length, const Bytes& names) {
  return element(kMiInt32, Bytes(reinterpret_cast<const char*>(&length), 4)) + element(kMiInt8, names);
}

struct Layout {
  const char* name;
  Bytes variable;
};

class LegitimateLayout : public ::testing::TestWithParam<Layout> {};

TEST_P(LegitimateLayout, PassesAndItsRecordOpens) {
  testing::ScratchDirectory dir;
  const std::string path = write_mat(dir, GetParam().variable);
  EXPECT_NO_THROW(check_mat_level5_headers(path));
  const auto record = open_channel_record(path, ChannelRecordFormat::kMat);
  EXPECT_NO_THROW(record->find(ColumnSelector{"rate"}));
}

const Bytes kEmptyDouble = matrix(6, 0, 0, "", element(kMiDouble, ""));

INSTANTIATE_TEST_SUITE_P(
    MatLevel5Check, LegitimateLayout,
    ::testing::Values(
        // A miMATRIX of no bytes is an empty element (matio and scipy read it as []).
        Layout{"cell_of_empty_elements", matrix(1, 1, 2, "c", element(kMiMatrix, "") + element(kMiMatrix, ""))},
        Layout{"cell_of_empty_doubles", matrix(1, 1, 2, "c", kEmptyDouble + kEmptyDouble)},
        Layout{"struct_array_without_fields", matrix(2, 1000, 1, "s", field_names(1, ""))},
        Layout{"struct_with_an_empty_field", matrix(2, 1, 1, "s", field_names(8, Bytes("note\0\0\0\0", 8)) + element(kMiMatrix, ""))},
        // An object: a struct after its class name.
        Layout{"object", matrix(3, 1, 1, "o", element(kMiInt8, "myclass") + field_names(8, Bytes("x\0\0\0\0\0\0\0", 8)) + kEmptyDouble)}),
    testing::NameOfParam());

// More elements than the bytes left can hold (each is at least an 8-byte tag): refused with the
// offset, before matio allocates a pointer for each.
TEST(MatLevel5Check, ACellOfMoreElementsThanItsBytesIsRefused) {
  testing::ScratchDirectory dir;
  const std::string path = write_mat(dir, matrix(1, 65536, 65536, "c", element(kMiMatrix, "")));
  try {
    check_mat_level5_headers(path);
    FAIL() << "no error";
  } catch (const Error& e) {
    // 184: the 128-byte header, the variable's tag, its flags, dimensions and name (16 bytes each).
    EXPECT_THAT(e.what(), ::testing::HasSubstr("byte offset 184: 4294967296 fields and cells in the 8 bytes left"));
  }
}

// A numeric array of more elements than the bytes left (each is a byte at the least): a fuzzer's
// int16 array of 4160749569 x 3 elements in a 400-byte file, which matio allocated first.
TEST(MatLevel5Check, ANumericArrayOfMoreElementsThanItsBytesIsRefused) {
  testing::ScratchDirectory dir;
  const std::string path = write_mat(dir, matrix(10, 0xF8000001u, 3, "x", element(kMiInt16, "")));
  try {
    check_mat_level5_headers(path);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("byte offset 184: an array of 12482248707 elements in the 8 bytes left"));
  }
  EXPECT_NO_THROW(check_mat_level5_headers(write_mat(dir, doubles("y", 3))));
}

// Function handles: matio allocates a pointer per element before it reads them (2^31 in a 400-byte
// file asked for 17 GB).
TEST(MatLevel5Check, FunctionHandlesOfMoreElementsThanTheirBytesAreRefused) {
  testing::ScratchDirectory dir;
  const std::string path = write_mat(dir, matrix(16, 65536, 32768, "f", element(kMiMatrix, "")));
  try {
    check_mat_level5_headers(path);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("byte offset 184: 2147483648 function handles in the 8 bytes left"));
  }
}

}  // namespace
}  // namespace inertest
