#include "io/mat_level5_check.h"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "inertest/core/error.h"

namespace inertest {
namespace {

// MAT-File Format, Table 1-1 (data types) and 1-3 (array classes).
constexpr std::uint32_t kMiInt8 = 1;
constexpr std::uint32_t kMiInt32 = 5;
constexpr std::uint32_t kMiUint32 = 6;
constexpr std::uint32_t kMiMatrix = 14;
constexpr std::uint32_t kMiCompressed = 15;
constexpr std::uint32_t kMxCell = 1;
constexpr std::uint32_t kMxStruct = 2;
constexpr std::uint32_t kMxObject = 3;
constexpr std::uint32_t kMxChar = 4;
constexpr std::uint32_t kMxDouble = 6;  // mxDOUBLE_CLASS .. mxUINT64_CLASS are 6 .. 15
constexpr std::uint32_t kMxUint64 = 15;
constexpr std::uint32_t kMxFunction = 16;  // matio allocates a pointer per element, as for a cell
constexpr std::size_t kPrefixBytes = 1u << 20;
constexpr std::uint64_t kMaximumInflation = 1032;
constexpr std::uint32_t kMaximumRank = 64;
constexpr std::uint32_t kMaximumName = 4096;
constexpr std::uint64_t kMaximumFields = 65536;
constexpr int kMaximumDepth = 32;

// The bytes of one element's content (or a prefix of it) and where they lie, for messages.
class Walker {
 public:
  // bytes: the element's content, or its first bytes; base: the file offset of bytes[0] (of an
  // inflated variable: the offset within its inflated bytes), after `where` in messages.
  Walker(const std::string& path, std::span<const unsigned char> bytes, bool big_endian, std::uint64_t base,
         std::string where)
      : path_(path), bytes_(bytes), big_endian_(big_endian), base_(base), where_(std::move(where)) {}

  // Checks the matrix whose content is bytes_[begin, end); `end` may lie beyond the bytes held (a
  // prefix). False when the bytes held ran out before the check was done.
  bool matrix(std::size_t begin, std::size_t end, int depth) {
    if (depth > kMaximumDepth) fail(begin, fmt::format("structs or cells nested more than {} deep", kMaximumDepth));
    std::size_t at = begin;
    Tag flags;
    if (!tag(at, end, flags)) return false;
    if (flags.type != kMiUint32 || flags.size != 8) fail(at, "the array flags are not 8 bytes of miUINT32");
    if (flags.data + 4 > bytes_.size()) return false;
    const std::uint32_t array_class = value(flags.data) & 0xFF;
    at = flags.next;
    Tag dims;
    if (!tag(at, end, dims)) return false;
    if (dims.type != kMiInt32 || dims.size % 4 != 0 || dims.size / 4 < 2 || dims.size / 4 > kMaximumRank) {
      fail(at, fmt::format("the dimensions take {} bytes: not a rank of 2 to {}", dims.size, kMaximumRank));
    }
    std::uint64_t elements = 1;
    for (std::uint64_t i = 0; i < dims.size / 4; ++i) {
      if (dims.data + 4 * i + 4 > bytes_.size()) return false;
      const std::uint64_t dimension = value(dims.data + 4 * i);
      elements = dimension != 0 && elements > (1ull << 40) / dimension ? 1ull << 40 : elements * dimension;
    }
    at = dims.next;
    Tag name;
    if (!tag(at, end, name)) return false;
    if (name.type != kMiInt8 || name.size > kMaximumName) fail(at, fmt::format("an array name of {} bytes", name.size));
    at = name.next;
    const auto left = [&] { return at < end ? end - at : std::size_t{0}; };
    // Each field or cell is a miMATRIX of at least a tag: matio allocates a pointer for each before
    // it reads them (2^31 function handles in a 400-byte file asked for 17 GB). A function handle's
    // elements are only counted, not walked: how MATLAB lays them out is not in the format's text.
    if (array_class == kMxFunction) {
      if (elements > left() / 8) fail(at, fmt::format("{} function handles in the {} bytes left", elements, left()));
      return true;
    }
    // A numeric or character array holds every element in its data, a byte each at the least
    // (miUINT8, the smallest storage type): matio allocates what the dimensions claim first, and
    // 1.2e10 int16 elements in a 400-byte file asked for gigabytes (under ASan their shadow made the
    // fuzzer's resident size 2.3 GB). A sparse array's dimensions count no stored element.
    if ((array_class == kMxChar || (array_class >= kMxDouble && array_class <= kMxUint64)) && elements > left()) {
      fail(at, fmt::format("an array of {} elements in the {} bytes left", elements, left()));
    }
    const bool cell = array_class == kMxCell;
    if (!cell && array_class != kMxStruct && array_class != kMxObject) return true;
    if (array_class == kMxObject) {  // a struct after its class name (MAT-File Format, "Object MAT-File Data Element")
      Tag class_name;
      if (!tag(at, end, class_name)) return false;
      if (class_name.type != kMiInt8 || class_name.size > kMaximumName) {
        fail(at, fmt::format("an object class name of {} bytes", class_name.size));
      }
      at = class_name.next;
    }
    std::uint64_t fields = 1;
    if (!cell) {
      Tag length;
      if (!tag(at, end, length)) return false;
      if (length.type != kMiInt32 || length.size != 4) fail(at, "the field name length is not one miINT32");
      if (length.data + 4 > bytes_.size()) return false;
      const std::uint32_t name_length = value(length.data);
      if (name_length == 0 || name_length > kMaximumName) fail(at, fmt::format("a field name length of {}", name_length));
      at = length.next;
      Tag names;
      if (!tag(at, end, names)) return false;
      fields = names.size / name_length;
      if (names.type != kMiInt8 || names.size % name_length != 0 || fields > kMaximumFields) {
        fail(at, fmt::format("field names of {} bytes for names of {} bytes", names.size, name_length));
      }
      at = names.next;
    }
    if (elements * fields > left() / 8) {
      fail(at, fmt::format("{} fields and cells in the {} bytes left", elements * fields, left()));
    }
    for (std::uint64_t i = 0; i < elements * fields; ++i) {
      Tag element;
      if (!tag(at, end, element)) return false;
      if (element.type != kMiMatrix) fail(at, "a struct field or cell is not a miMATRIX");
      // A miMATRIX of no bytes is an empty element (MATLAB writes an unset field so; matio and
      // scipy read it as []).
      if (element.size != 0 && !matrix(element.data, element.data + element.size, depth + 1)) return false;
      at = element.next;
    }
    return true;
  }

  struct Tag {
    std::uint32_t type = 0;
    std::uint64_t size = 0;
    std::size_t data = 0;  // where the data begins
    std::size_t next = 0;  // where the next element begins (8-byte aligned)
  };

  // The tag at `at`, within `end`; false when the bytes held end before it.
  bool tag(std::size_t at, std::size_t end, Tag& out) const {
    if (at + 8 > end) fail(at, "an element's tag runs past the end of the element that holds it");
    if (at + 8 > bytes_.size()) return false;
    const std::uint32_t first = value(at);
    if ((first >> 16) != 0) {
      // Small data element: the size in the upper 16 bits, the data in the 4 bytes after.
      out = {first & 0xFFFF, first >> 16, at + 4, at + 8};
      if (out.size > 4) fail(at, "a small data element of more than 4 bytes");
      return true;
    }
    out.type = first;
    out.size = value(at + 4);
    out.data = at + 8;
    if (out.size > end - out.data) fail(at, fmt::format("an element of {} bytes in the {} left", out.size, end - out.data));
    out.next = out.data + static_cast<std::size_t>((out.size + 7) / 8 * 8);
    return true;
  }

  std::uint32_t value(std::size_t at) const {
    std::uint32_t v = 0;
    std::memcpy(&v, bytes_.data() + at, 4);
    return big_endian_ ? __builtin_bswap32(v) : v;
  }

  [[noreturn]] void fail(std::size_t at, const std::string& message) const {
    throw Error(SourceLocation{path_, 0, 0}, fmt::format("{} {}: {} (a corrupt MAT-file?)", where_, base_ + at, message));
  }

 private:
  const std::string& path_;
  std::span<const unsigned char> bytes_;
  bool big_endian_;
  std::uint64_t base_;
  std::string where_;
};

struct Inflated {
  std::vector<unsigned char> bytes;
  std::string error;  // zlib's message when the stream broke off before the prefix was full
};

// The first kPrefixBytes (or fewer) of the inflated content of a compressed element.
Inflated inflate_prefix(const std::vector<unsigned char>& compressed) {
  Inflated out{std::vector<unsigned char>(kPrefixBytes), ""};
  z_stream stream{};
  if (inflateInit(&stream) != Z_OK) return {{}, "cannot start zlib"};
  stream.next_in = const_cast<unsigned char*>(compressed.data());
  stream.avail_in = static_cast<uInt>(compressed.size());
  stream.next_out = out.bytes.data();
  stream.avail_out = static_cast<uInt>(out.bytes.size());
  const int status = inflate(&stream, Z_SYNC_FLUSH);
  if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR) {
    out.error = stream.msg != nullptr ? stream.msg : fmt::format("zlib status {}", status);
  }
  out.bytes.resize(stream.total_out);
  inflateEnd(&stream);
  return out;
}

}  // namespace

void check_mat_level5_headers(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(SourceLocation{path, 0, 0}, std::string("cannot open: ") + std::strerror(errno));
  std::array<char, 128> header{};
  if (!file.read(header.data(), header.size())) return;
  if (header[124] != 0 || header[125] != 1) {
    if (header[124] != 1 || header[125] != 0) return;  // the version: 0x0100 is level 5 (0x0200: v7.3)
  }
  const bool big_endian = header[126] == 'M' && header[127] == 'I';
  file.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(file.tellg());
  std::uint64_t offset = 128;
  while (offset + 8 <= size) {
    std::array<unsigned char, 8> tag{};
    file.seekg(static_cast<std::streamoff>(offset));
    file.read(reinterpret_cast<char*>(tag.data()), tag.size());
    const Walker top(path, tag, big_endian, offset, "byte offset");
    const std::uint32_t type = top.value(0);
    const std::uint64_t bytes = top.value(4);
    if (bytes > size - offset - 8) {
      throw Error(SourceLocation{path, 0, 0},
                  fmt::format("byte offset {}: a variable of {} bytes, but the file holds {} after its tag (truncated?)",
                              offset, bytes, size - offset - 8));
    }
    if (type == kMiMatrix || type == kMiCompressed) {
      std::vector<unsigned char> content(static_cast<std::size_t>(std::min<std::uint64_t>(bytes, kPrefixBytes)));
      file.read(reinterpret_cast<char*>(content.data()), static_cast<std::streamsize>(content.size()));
      if (type == kMiMatrix) {
        Walker(path, content, big_endian, offset + 8, "byte offset").matrix(0, static_cast<std::size_t>(bytes), 0);
      } else {
        const Inflated inflated = inflate_prefix(content);
        Walker walker(path, inflated.bytes, big_endian, 0,
                      fmt::format("the compressed variable at byte offset {}, inflated byte", offset));
        // Deflate expands at most 1032 times (a 258-byte match in a bit or two; zlib's technical
        // details): a variable that says it inflates to more, which the prefix alone cannot show,
        // is held to that, so that its counts are checked against what the stream can hold.
        const std::uint64_t most = kMaximumInflation * bytes;
        Walker::Tag matrix;
        const bool checked = walker.tag(0, static_cast<std::size_t>(most), matrix) &&
                             (matrix.type != kMiMatrix || walker.matrix(matrix.data, matrix.data + matrix.size, 0));
        // A stream that breaks off before the headers end leaves matio to read sizes from garbage.
        if (!checked && !inflated.error.empty()) {
          throw Error(SourceLocation{path, 0, 0},
                      fmt::format("the compressed variable at byte offset {}: zlib stops after {} bytes, inside its "
                                  "headers: {} (a corrupt MAT-file?)",
                                  offset, inflated.bytes.size(), inflated.error));
        }
      }
    }
    offset += 8 + (type == kMiCompressed ? bytes : (bytes + 7) / 8 * 8);
  }
}

}  // namespace inertest
