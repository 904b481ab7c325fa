// NI TDMS records, read as National Instruments' "TDMS File Format Internal Structure" describes
// them (no packaged library exists). A file is a sequence of segments, each a 28-byte lead-in
// ("TDSm", the ToC mask, the version, the offset of the next segment and of the raw data, both
// counted from the end of the lead-in), the metadata (the objects "/'group'/'channel'", each with
// its raw data index and properties) and the raw data: chunks in which each object of the segment's
// object list holds its values contiguously, or interleaved value by value (kTocInterleavedData).
// kTocNewObjList starts a new object list; otherwise the segment's objects update the previous
// list, and a raw data index of 0 repeats the object's previous index. kTocBigEndian makes the
// segment (after the ToC mask) big-endian. DAQmx raw data (index 0x1269, format changing scalers)
// holds raw integers in strided buffers, scaled by the channel's NI_Scale[n] properties (linear or
// polynomial). When "FILE.tdms_index" exists (lead-in "TDSh", metadata only), the metadata is read
// from it and each segment's lead-in in the data file is checked against it.
//
// Only the positions of the values are kept (one piece per run of consecutive values): a channel's
// samples are read at random from the file, so a record of any length is never held whole.
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <variant>

#include "inertest/core/error.h"
#include "io/channel_readers.h"

namespace inertest {
namespace {

constexpr std::uint32_t kTocMetaData = 1u << 1;
constexpr std::uint32_t kTocNewObjList = 1u << 2;
constexpr std::uint32_t kTocRawData = 1u << 3;
constexpr std::uint32_t kTocInterleavedData = 1u << 5;
constexpr std::uint32_t kTocBigEndian = 1u << 6;
constexpr std::uint64_t kLeadInBytes = 28;
constexpr std::uint64_t kIncompleteSegment = 0xFFFFFFFFFFFFFFFFull;
constexpr std::uint32_t kNoRawData = 0xFFFFFFFFu;
constexpr std::uint32_t kSameRawDataIndex = 0;
constexpr std::uint32_t kDaqmxFormatChangingScaler = 0x1269;
constexpr std::uint32_t kDaqmxDigitalLineScaler = 0x126A;
// Seconds from 1904-01-01 (the TDMS epoch) to 1970-01-01, both UTC.
constexpr double kTdmsEpochToUnixSeconds = 2082844800.0;

// tdsDataType
enum : std::uint32_t {
  kVoid = 0, kI8 = 1, kI16 = 2, kI32 = 3, kI64 = 4, kU8 = 5, kU16 = 6, kU32 = 7, kU64 = 8,
  kSingle = 9, kDouble = 10, kExtended = 11, kSingleWithUnit = 0x19, kDoubleWithUnit = 0x1A,
  kExtendedWithUnit = 0x1B, kString = 0x20, kBoolean = 0x21, kTimeStamp = 0x44, kComplexSingle = 0x08000C,
  kComplexDouble = 0x10000D
};

// Bytes of one value; 0 for strings (variable) and types not known.
std::uint32_t type_size(std::uint32_t type) {
  switch (type) {
    case kI8: case kU8: case kBoolean: return 1;
    case kI16: case kU16: return 2;
    case kI32: case kU32: case kSingle: case kSingleWithUnit: return 4;
    case kI64: case kU64: case kDouble: case kDoubleWithUnit: case kComplexSingle: return 8;
    case kExtended: case kExtendedWithUnit: case kTimeStamp: case kComplexDouble: return 16;
    default: return 0;
  }
}

// The stored type as ChannelInfo names it; numeric says whether it reads as samples.
std::string type_name(std::uint32_t type, bool& numeric) {
  numeric = true;
  switch (type) {
    case kI8: return "i8";
    case kI16: return "i16";
    case kI32: return "i32";
    case kI64: return "i64";
    case kU8: return "u8";
    case kU16: return "u16";
    case kU32: return "u32";
    case kU64: return "u64";
    case kSingle: case kSingleWithUnit: return "f32";
    case kDouble: case kDoubleWithUnit: return "f64";
    case kBoolean: return "bool";
    default: break;
  }
  numeric = false;
  switch (type) {
    case kString: return "string";
    case kTimeStamp: return "timestamp";
    case kComplexSingle: case kComplexDouble: return "complex";
    case kExtended: case kExtendedWithUnit: return "f128";
    default: return fmt::format("type 0x{:x}", type);
  }
}

// DAQmx raw data types (the format changing scaler's data type) as tdsDataType.
std::uint32_t daqmx_type(std::uint32_t type) {
  switch (type) {
    case 0: return kU8;
    case 1: return kI8;
    case 2: return kU16;
    case 3: return kI16;
    case 4: return kU32;
    case 5: return kI32;
    case 6: return kU64;
    case 7: return kI64;
    case 8: return kSingle;
    case 9: return kDouble;
    default: return kVoid;
  }
}

template <typename T>
T load(const unsigned char* bytes, bool big_endian) {
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  if (big_endian) {
    unsigned char reversed[sizeof(T)];
    for (std::size_t i = 0; i < sizeof(T); ++i) reversed[i] = bytes[sizeof(T) - 1 - i];
    std::memcpy(&value, reversed, sizeof(T));
  }
  return value;
}

double load_number(const unsigned char* bytes, std::uint32_t type, bool big_endian) {
  switch (type) {
    case kI8: return static_cast<double>(load<std::int8_t>(bytes, false));
    case kU8: case kBoolean: return static_cast<double>(load<std::uint8_t>(bytes, false));
    case kI16: return static_cast<double>(load<std::int16_t>(bytes, big_endian));
    case kU16: return static_cast<double>(load<std::uint16_t>(bytes, big_endian));
    case kI32: return static_cast<double>(load<std::int32_t>(bytes, big_endian));
    case kU32: return static_cast<double>(load<std::uint32_t>(bytes, big_endian));
    case kI64: return static_cast<double>(load<std::int64_t>(bytes, big_endian));
    case kU64: return static_cast<double>(load<std::uint64_t>(bytes, big_endian));
    case kSingle: case kSingleWithUnit: return static_cast<double>(load<float>(bytes, big_endian));
    default: return load<double>(bytes, big_endian);
  }
}

class File {
 public:
  explicit File(const std::string& path) : path_(path), fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC)) {
    if (fd_ < 0) throw Error(SourceLocation{path, 0, 0}, std::string("cannot open: ") + std::strerror(errno));
    struct stat status {};
    if (::fstat(fd_, &status) != 0 || !S_ISREG(status.st_mode)) {
      ::close(fd_);
      throw Error(SourceLocation{path, 0, 0}, "not a regular file");
    }
    size_ = static_cast<std::uint64_t>(status.st_size);
  }
  File(const File&) = delete;
  File& operator=(const File&) = delete;
  ~File() { ::close(fd_); }

  std::uint64_t size() const { return size_; }
  const std::string& path() const { return path_; }

  // Exactly bytes.size() bytes at offset; an Error naming the offset when the file ends before.
  void read(std::uint64_t offset, std::span<unsigned char> bytes) const {
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t got = ::pread(fd_, bytes.data() + done, bytes.size() - done, static_cast<off_t>(offset + done));
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) {
        throw Error(SourceLocation{path_, 0, 0},
                    fmt::format("byte offset {}: the file ends before the {} bytes expected there (truncated?)",
                                offset + done, bytes.size() - done));
      }
      done += static_cast<std::size_t>(got);
    }
  }

 private:
  std::string path_;
  int fd_;
  std::uint64_t size_ = 0;
};

// Reads the metadata of one segment, held in memory, with the segment's byte order. Every error
// names the file offset of the value that could not be read.
class MetadataReader {
 public:
  MetadataReader(const std::string& path, std::vector<unsigned char> bytes, std::uint64_t file_offset, bool big_endian)
      : path_(path), bytes_(std::move(bytes)), file_offset_(file_offset), big_endian_(big_endian) {}

  template <typename T>
  T number() {
    require(sizeof(T));
    const T value = load<T>(bytes_.data() + position_, big_endian_);
    position_ += sizeof(T);
    return value;
  }
  std::string text() {
    const std::uint32_t length = number<std::uint32_t>();
    require(length);
    std::string value(reinterpret_cast<const char*>(bytes_.data() + position_), length);
    position_ += length;
    return value;
  }
  void skip(std::uint64_t count) {
    require(count);
    position_ += static_cast<std::size_t>(count);
  }
  std::uint64_t offset() const { return file_offset_ + position_; }
  bool big_endian() const { return big_endian_; }
  const std::string& path() const { return path_; }
  [[noreturn]] void fail(const std::string& message) const {
    throw Error(SourceLocation{path_, 0, 0}, fmt::format("byte offset {}: {}", offset(), message));
  }

 private:
  void require(std::uint64_t count) const {
    if (count > bytes_.size() - position_) {
      fail(fmt::format("the segment's metadata ends before the {} bytes expected here (corrupt or truncated?)", count));
    }
  }

  const std::string& path_;
  std::vector<unsigned char> bytes_;
  std::uint64_t file_offset_;
  std::size_t position_ = 0;
  bool big_endian_;
};

using PropertyValue = std::variant<double, std::string>;

struct DaqmxScaler {
  std::uint32_t type = kVoid;  // tdsDataType of the raw value
  std::uint32_t buffer = 0;    // raw buffer index
  std::uint32_t byte_offset = 0;
  bool digital = false;
  std::uint32_t bit_offset = 0;
};

// An object's raw data index in a segment.
struct RawDataIndex {
  std::uint32_t type = kVoid;
  std::uint64_t count = 0;
  std::uint64_t bytes = 0;  // strings: the total size of the values
  bool daqmx = false;
  std::vector<DaqmxScaler> scalers;
  std::vector<std::uint32_t> widths;  // DAQmx raw buffer widths (bytes of one stride)
};

struct Object {
  std::string path;
  std::map<std::string, PropertyValue> properties;
  std::optional<RawDataIndex> index;  // the last index given; nullopt before any
};

// Consecutive values of a channel at a place in the file.
struct Piece {
  std::uint64_t first_sample = 0;  // of the channel
  std::uint64_t count = 0;
  std::uint64_t offset = 0;  // of the first value's first byte
  std::uint64_t stride = 0;  // from one value to the next
  std::uint32_t type = kVoid;
  bool big_endian = false;
};

struct ChannelData {
  std::vector<Piece> pieces;
  std::uint64_t length = 0;
  std::uint32_t type = kVoid;
  bool daqmx = false;
  bool digital = false;
  bool mixed_types = false;
  std::uint32_t bit_offset = 0;  // DAQmx digital lines: the line's bit in its byte
  std::optional<double> increment;  // the wf_increment of the first samples that had one
  std::string increment_change;     // the first other wf_increment, described; empty when none
  void add(Piece piece) {
    piece.first_sample = length;
    length += piece.count;
    if (!pieces.empty()) {
      Piece& last = pieces.back();
      // A run continuing where the last one ended (contiguous chunks) extends it.
      if (last.stride == piece.stride && last.type == piece.type && last.big_endian == piece.big_endian &&
          last.offset + last.count * last.stride == piece.offset) {
        last.count += piece.count;
        return;
      }
    }
    pieces.push_back(piece);
  }
};

// "/'group'/'channel'" -> {"group", "channel"} ('' inside a name is one quote).
std::vector<std::string> split_object_path(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t i = 0;
  while (i < path.size()) {
    if (path[i] != '/' || i + 1 >= path.size() || path[i + 1] != '\'') return {};
    std::string part;
    i += 2;
    while (true) {
      if (i >= path.size()) return {};
      if (path[i] == '\'') {
        if (i + 1 < path.size() && path[i + 1] == '\'') {
          part += '\'';
          i += 2;
          continue;
        }
        ++i;
        break;
      }
      part += path[i++];
    }
    parts.push_back(std::move(part));
  }
  return parts;
}

std::optional<double> number_property(const Object& object, const std::string& name) {
  const auto it = object.properties.find(name);
  if (it == object.properties.end() || !std::holds_alternative<double>(it->second)) return std::nullopt;
  return std::get<double>(it->second);
}

std::optional<std::string> text_property(const Object& object, const std::string& name) {
  const auto it = object.properties.find(name);
  if (it == object.properties.end() || !std::holds_alternative<std::string>(it->second)) return std::nullopt;
  return std::get<std::string>(it->second);
}

// A DAQmx scale: NI_Scale[n]_Scale_Type "Linear" (y = slope x + intercept) or "Polynomial"
// (y = sum c_i x^i), applied to the value NI_Scale[n]_..._Input_Source names. NI's convention (as
// npTDMS's scaling.py reads it, RAW_DATA_INPUT_SOURCE): 0xFFFFFFFF, or no such property, is the raw
// data; m < NI_Number_Of_Scales is the output of NI_Scale[m]. A scale m without a Scale_Type is the
// DAQmx scaler's own value, which is the raw value read here.
struct Scale {
  std::vector<double> coefficients;  // polynomial coefficients, lowest power first
  std::optional<std::size_t> input;  // scale applied before, nullopt: the raw value
};
constexpr double kRawDataInputSource = 4294967295.0;  // 0xFFFFFFFF, as a u32 property reads

class TdmsRecord final : public ChannelRecord {
 public:
  explicit TdmsRecord(const std::string& path) : ChannelRecord(path, ChannelRecordFormat::kTdms), file_(path) {
    if (file_.size() == 0) throw Error(SourceLocation{path, 0, 0}, "no data: the file is empty");
    const std::string index_path = path + "_index";
    std::error_code error;
    if (std::filesystem::is_regular_file(index_path, error)) {
      const File index(index_path);
      parse(index, "TDSh");
    } else {
      parse(file_, "TDSm");
    }
    list_channels();
  }

  void read(std::size_t channel, std::uint64_t first, std::span<double> out) override {
    const ChannelInfo& info = channels_.at(channel);
    const ChannelData& data = data_by_channel_[channel];
    if (first + out.size() > data.length) {
      throw Error(SourceLocation{path(), 0, 0},
                  channel_range_context(info, first, out.size()) + fmt::format(": beyond its {} samples", data.length));
    }
    auto piece = std::upper_bound(data.pieces.begin(), data.pieces.end(), first,
                                  [](std::uint64_t sample, const Piece& p) { return sample < p.first_sample; }) - 1;
    std::size_t done = 0;
    while (done < out.size()) {
      const std::uint64_t within = first + done - piece->first_sample;
      const auto count = static_cast<std::size_t>(std::min<std::uint64_t>(piece->count - within, out.size() - done));
      const std::uint32_t size = type_size(piece->type);
      buffer_.resize(static_cast<std::size_t>((count - 1) * piece->stride + size));
      file_.read(piece->offset + within * piece->stride, buffer_);
      for (std::size_t i = 0; i < count; ++i) {
        const unsigned char* bytes = buffer_.data() + i * piece->stride;
        double value = 0.0;
        if (data.digital) {
          value = static_cast<double>((bytes[0] >> (data.bit_offset % 8)) & 1u);
        } else {
          value = load_number(bytes, piece->type, piece->big_endian);
        }
        out[done + i] = value;
      }
      done += count;
      ++piece;
    }
    // The scales' output, where the channel has them (raw data: DAQmx, or NI_Scaling_Status "unscaled").
    if (const auto found = last_scale_.find(channel_objects_[channel]); found != last_scale_.end()) {
      const std::vector<std::optional<Scale>>& scales = scales_.at(found->first);
      for (double& value : out) value = apply(scales, found->second, value);
    }
  }

 private:
  void parse(const File& source, const char* tag) {
    std::vector<std::size_t> list;  // objects_ indices of the current object list, in order
    std::uint64_t position = 0;      // in `source`
    std::uint64_t data_position = 0; // of the same segment in the data file
    while (position < source.size()) {
      std::array<unsigned char, kLeadInBytes> lead_in{};
      if (source.size() - position < kLeadInBytes) {
        throw Error(SourceLocation{source.path(), 0, 0},
                    fmt::format("byte offset {}: {} bytes left, too few for a segment lead-in of 28 (truncated?)",
                                position, source.size() - position));
      }
      source.read(position, lead_in);
      if (std::memcmp(lead_in.data(), tag, 4) != 0) {
        throw Error(SourceLocation{source.path(), 0, 0},
                    fmt::format("byte offset {}: the segment lead-in starts with {:?}, not \"{}\" (not a TDMS segment: "
                                "a corrupt file?)",
                                position, std::string(reinterpret_cast<const char*>(lead_in.data()), 4), tag));
      }
      const std::uint32_t toc = load<std::uint32_t>(lead_in.data() + 4, false);
      const bool big_endian = (toc & kTocBigEndian) != 0;
      const std::uint32_t version = load<std::uint32_t>(lead_in.data() + 8, big_endian);
      std::uint64_t next_offset = load<std::uint64_t>(lead_in.data() + 12, big_endian);
      const std::uint64_t raw_offset = load<std::uint64_t>(lead_in.data() + 20, big_endian);
      if (version != 4712 && version != 4713) {
        throw Error(SourceLocation{source.path(), 0, 0},
                    fmt::format("byte offset {}: TDMS version {} is not 4712 or 4713", position + 8, version));
      }
      const bool is_index = source.path() != file_.path();
      if (is_index) check_data_lead_in(data_position, toc);
      const std::uint64_t data_end_available = file_.size() - std::min(file_.size(), data_position + kLeadInBytes);
      const bool complete = next_offset != kIncompleteSegment;
      if (!complete) {
        // A writer that stopped before finishing the segment: its raw data runs to the end of the file.
        next_offset = data_end_available;
      } else if (next_offset > data_end_available) {
        throw Error(SourceLocation{path(), 0, 0},
                    fmt::format("byte offset {}: the segment claims {} bytes after its lead-in, the file has {} "
                                "(truncated?)",
                                data_position, next_offset, data_end_available));
      }
      if (raw_offset > next_offset) {
        throw Error(SourceLocation{source.path(), 0, 0},
                    fmt::format("byte offset {}: the raw data offset {} lies beyond the segment's {} bytes",
                                position + 20, raw_offset, next_offset));
      }
      const std::uint64_t metadata_available = source.size() - position - kLeadInBytes;
      if ((toc & kTocMetaData) != 0) {
        if (raw_offset > metadata_available) {
          throw Error(SourceLocation{source.path(), 0, 0},
                      fmt::format("byte offset {}: the metadata of {} bytes runs past the end of the file (truncated?)",
                                  position + kLeadInBytes, raw_offset));
        }
        std::vector<unsigned char> bytes(static_cast<std::size_t>(raw_offset));
        source.read(position + kLeadInBytes, bytes);
        MetadataReader metadata(source.path(), std::move(bytes), position + kLeadInBytes, big_endian);
        read_metadata(metadata, (toc & kTocNewObjList) != 0, list);
      }
      if ((toc & kTocRawData) != 0) {
        add_raw_data(list, data_position + kLeadInBytes + raw_offset, next_offset - raw_offset, toc, data_position,
                     complete);
      }
      position += kLeadInBytes + (is_index ? raw_offset : next_offset);
      data_position += kLeadInBytes + next_offset;
    }
  }

  // With an index file: the data file's segment at `offset` must start as the index says.
  void check_data_lead_in(std::uint64_t offset, std::uint32_t toc) const {
    std::array<unsigned char, 8> lead_in{};
    if (file_.size() < offset + lead_in.size()) {
      throw Error(SourceLocation{path(), 0, 0},
                  fmt::format("byte offset {}: the index file lists a segment here, but the file ends (truncated?)", offset));
    }
    file_.read(offset, lead_in);
    if (std::memcmp(lead_in.data(), "TDSm", 4) != 0 || load<std::uint32_t>(lead_in.data() + 4, false) != toc) {
      throw Error(SourceLocation{path(), 0, 0},
                  fmt::format("byte offset {}: the segment lead-in differs from the one in the index file {} (a "
                              "corrupt file, or an index file of another one?)",
                              offset, path() + "_index"));
    }
  }

  void read_metadata(MetadataReader& metadata, bool new_list, std::vector<std::size_t>& list) {
    if (new_list) list.clear();
    const std::uint32_t count = metadata.number<std::uint32_t>();
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::uint64_t object_offset = metadata.offset();
      const std::string object_path = metadata.text();
      auto [found, inserted] = object_index_.try_emplace(object_path, objects_.size());
      if (inserted) objects_.push_back(Object{object_path, {}, std::nullopt});
      const std::size_t id = found->second;
      const std::uint32_t index_length = metadata.number<std::uint32_t>();
      bool has_data = true;
      if (index_length == kNoRawData) {
        has_data = false;
      } else if (index_length == kSameRawDataIndex) {
        if (!objects_[id].index) metadata.fail(fmt::format("object {} repeats a raw data index it never had", object_path));
      } else if (index_length == kDaqmxFormatChangingScaler || index_length == kDaqmxDigitalLineScaler) {
        objects_[id].index = read_daqmx_index(metadata, index_length == kDaqmxDigitalLineScaler);
      } else {
        RawDataIndex index;
        index.type = metadata.number<std::uint32_t>();
        if (metadata.number<std::uint32_t>() != 1) metadata.fail(fmt::format("object {}: array dimension is not 1", object_path));
        index.count = metadata.number<std::uint64_t>();
        if (index.type == kString) {
          index.bytes = metadata.number<std::uint64_t>();
        } else if (type_size(index.type) == 0) {
          throw Error(SourceLocation{path(), 0, 0},
                      fmt::format("byte offset {}: object {} has raw data of unknown type 0x{:x}", object_offset,
                                  object_path, index.type));
        } else if (__builtin_mul_overflow(index.count, type_size(index.type), &index.bytes)) {
          throw Error(SourceLocation{path(), 0, 0},
                      fmt::format("byte offset {}: object {} has {} values of {} bytes, more than 2^64 bytes (a corrupt "
                                  "raw data index)",
                                  object_offset, object_path, index.count, type_size(index.type)));
        }
        objects_[id].index = index;
      }
      const auto listed = std::find(list.begin(), list.end(), id);
      if (listed == list.end()) list.push_back(id);
      has_data_[id] = has_data;
      read_properties(metadata, objects_[id]);
    }
  }

  RawDataIndex read_daqmx_index(MetadataReader& metadata, bool digital) {
    RawDataIndex index;
    index.daqmx = true;
    index.type = metadata.number<std::uint32_t>();
    if (metadata.number<std::uint32_t>() != 1) metadata.fail("DAQmx raw data: array dimension is not 1");
    index.count = metadata.number<std::uint64_t>();
    const std::uint32_t scalers = metadata.number<std::uint32_t>();
    if (scalers > 4096) metadata.fail(fmt::format("{} DAQmx scalers: a corrupt raw data index", scalers));
    for (std::uint32_t i = 0; i < scalers; ++i) {
      DaqmxScaler scaler;
      scaler.digital = digital;
      scaler.type = daqmx_type(metadata.number<std::uint32_t>());
      scaler.buffer = metadata.number<std::uint32_t>();
      if (digital) {
        scaler.bit_offset = metadata.number<std::uint32_t>();
        metadata.skip(1);  // sample format bitmap
        scaler.byte_offset = scaler.bit_offset / 8;
        scaler.type = kU8;
      } else {
        scaler.byte_offset = metadata.number<std::uint32_t>();
        metadata.skip(4);  // sample format bitmap
      }
      metadata.skip(4);  // scale id
      index.scalers.push_back(scaler);
    }
    const std::uint32_t widths = metadata.number<std::uint32_t>();
    if (widths > 4096) metadata.fail(fmt::format("{} DAQmx raw buffers: a corrupt raw data index", widths));
    for (std::uint32_t i = 0; i < widths; ++i) index.widths.push_back(metadata.number<std::uint32_t>());
    return index;
  }

  static void read_properties(MetadataReader& metadata, Object& object) {
    const std::uint32_t count = metadata.number<std::uint32_t>();
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::string name = metadata.text();
      const std::uint64_t type_offset = metadata.offset();
      const std::uint32_t type = metadata.number<std::uint32_t>();
      if (type == kString) {
        object.properties[name] = metadata.text();
      } else if (type == kTimeStamp) {
        // Seconds since 1904-01-01 UTC and 2^-64 fractions: the fraction first when little-endian.
        std::uint64_t fraction = 0;
        std::int64_t seconds = 0;
        if (metadata.big_endian()) {
          seconds = metadata.number<std::int64_t>();
          fraction = metadata.number<std::uint64_t>();
        } else {
          fraction = metadata.number<std::uint64_t>();
          seconds = metadata.number<std::int64_t>();
        }
        object.properties[name] =
            static_cast<double>(seconds) - kTdmsEpochToUnixSeconds + static_cast<double>(fraction) * 0x1p-64;
      } else if (bool numeric = false; (type_name(type, numeric), numeric)) {
        std::array<unsigned char, 8> bytes{};
        const std::uint32_t size = type_size(type);
        for (std::uint32_t b = 0; b < size; ++b) bytes[b] = metadata.number<std::uint8_t>();
        object.properties[name] = load_number(bytes.data(), type, metadata.big_endian());
      } else if (type_size(type) != 0) {
        metadata.skip(type_size(type));
      } else {
        throw Error(SourceLocation{metadata.path(), 0, 0},
                    fmt::format("byte offset {}: property '{}' has unknown data type 0x{:x}", type_offset, name, type));
      }
    }
  }

  // The raw data of the segment at byte offset `segment`: `size` bytes from `start`, in chunks as the
  // objects' raw data indices lay out. A chunk that does not fit in 64 bits, or a complete segment
  // (its lead-in gives its length) shorter than one chunk, is an Error naming the segment: its indices
  // claim more values than it holds. The last chunk may be partial (a segment the writer could not
  // finish, or one cut short): it holds what fits.
  void add_raw_data(const std::vector<std::size_t>& list, std::uint64_t start, std::uint64_t size, std::uint32_t toc,
                    std::uint64_t segment, bool complete) {
    const bool big_endian = (toc & kTocBigEndian) != 0;
    std::vector<std::size_t> with_data;
    std::uint64_t chunk = 0;
    bool daqmx_counted = false;
    bool overflow = false;
    for (const std::size_t id : list) {
      if (!has_data_[id] || !objects_[id].index) continue;
      const RawDataIndex& index = *objects_[id].index;
      with_data.push_back(id);
      if (index.daqmx) {
        // The channels of a DAQmx segment share its raw buffers: counted once.
        if (!daqmx_counted) {
          for (const std::uint32_t width : index.widths) {
            std::uint64_t bytes = 0;
            overflow = overflow || __builtin_mul_overflow(index.count, width, &bytes) ||
                       __builtin_add_overflow(chunk, bytes, &chunk);
          }
        }
        daqmx_counted = true;
      } else {
        overflow = overflow || __builtin_add_overflow(chunk, index.bytes, &chunk);
      }
    }
    if (overflow) {
      throw Error(SourceLocation{path(), 0, 0},
                  fmt::format("byte offset {}: the raw data indices of the segment's objects add up to more than 2^64 "
                              "bytes a chunk (a corrupt raw data index)",
                              segment));
    }
    if (chunk == 0 || size == 0) return;
    for (const std::size_t id : with_data) note_increment(id, false);
    if (complete && chunk > size) {
      throw Error(SourceLocation{path(), 0, 0},
                  fmt::format("byte offset {}: the raw data indices of the segment's objects give {} bytes a chunk, "
                              "but the segment holds {} bytes of raw data (a corrupt raw data index)",
                              segment, chunk, size));
    }
    const bool interleaved = (toc & kTocInterleavedData) != 0 && !daqmx_counted;
    const std::uint64_t chunks = size / chunk;
    const std::uint64_t left_over = size % chunk;
    for (std::uint64_t c = 0; c <= chunks; ++c) {
      // The last, partial chunk of a segment the writer could not finish holds what fits.
      std::uint64_t available = c < chunks ? chunk : left_over;
      if (available == 0) break;
      const std::uint64_t chunk_start = start + c * chunk;
      if (interleaved) {
        add_interleaved(with_data, chunk_start, available, big_endian, segment);
        continue;
      }
      std::uint64_t offset = chunk_start;
      for (const std::size_t id : with_data) {
        const RawDataIndex& index = *objects_[id].index;
        if (index.daqmx) {
          add_daqmx(id, index, chunk_start, available, big_endian);
          continue;
        }
        const std::uint32_t size_of_value = type_size(index.type);
        const std::uint64_t bytes = std::min(index.bytes, available);
        if (size_of_value != 0 && index.type != kString) {
          data_[id].add(Piece{0, bytes / size_of_value, offset, size_of_value, index.type, big_endian});
          note_type(id, index.type, false, false);
        } else {
          note_type(id, index.type, false, false);
        }
        offset += bytes;
        available -= bytes;
      }
    }
  }

  // Interleaved data holds its values frame by frame, one value of each object a frame (NI, "TDMS
  // File Format Internal Structure", Raw Data): every object of the segment has the same count.
  void add_interleaved(const std::vector<std::size_t>& ids, std::uint64_t start, std::uint64_t available,
                       bool big_endian, std::uint64_t segment) {
    std::uint64_t frame = 0;
    const std::uint64_t count = objects_[ids.front()].index->count;
    for (const std::size_t id : ids) {
      const RawDataIndex& index = *objects_[id].index;
      if (type_size(index.type) == 0 || index.type == kString) {
        throw Error(SourceLocation{path(), 0, 0},
                    fmt::format("byte offset {}: interleaved raw data of object {} has no fixed size", segment,
                                objects_[id].path));
      }
      if (index.count != count) {
        throw Error(SourceLocation{path(), 0, 0},
                    fmt::format("byte offset {}: interleaved raw data with {} values of object {} but {} of object {}: "
                                "interleaved data holds the same number of values of every object",
                                segment, count, objects_[ids.front()].path, index.count, objects_[id].path));
      }
      frame += type_size(index.type);
    }
    const std::uint64_t frames = std::min(count, available / frame);
    std::uint64_t offset = start;
    for (const std::size_t id : ids) {
      const std::uint32_t type = objects_[id].index->type;
      data_[id].add(Piece{0, frames, offset, frame, type, big_endian});
      note_type(id, type, false, false);
      offset += type_size(type);
    }
  }

  void add_daqmx(std::size_t id, const RawDataIndex& index, std::uint64_t chunk_start, std::uint64_t available,
                 bool big_endian) {
    if (index.scalers.empty()) return;
    const DaqmxScaler& scaler = index.scalers.front();
    if (scaler.buffer >= index.widths.size() || scaler.type == kVoid ||
        scaler.byte_offset + type_size(scaler.type) > index.widths[scaler.buffer]) {
      throw Error(SourceLocation{path(), 0, 0},
                  fmt::format("byte offset {}: object {}: a DAQmx scaler outside its raw buffer", chunk_start,
                              objects_[id].path));
    }
    std::uint64_t buffer_start = chunk_start;
    for (std::uint32_t b = 0; b < scaler.buffer; ++b) buffer_start += index.count * index.widths[b];
    const std::uint64_t width = index.widths[scaler.buffer];
    const std::uint64_t fits = buffer_start - chunk_start < available ? (available - (buffer_start - chunk_start)) / width : 0;
    data_[id].add(Piece{0, std::min(index.count, fits), buffer_start + scaler.byte_offset, width, scaler.type, big_endian});
    note_type(id, scaler.type, true, scaler.digital);
    data_[id].bit_offset = scaler.bit_offset;
  }

  // The wf_increment in effect for the samples a segment adds is the object's property as the
  // metadata so far left it (a later segment's metadata overwrites it). Samples with another
  // increment than earlier ones are not evenly spaced: the first such change is noted, with the
  // number of samples before it; `after_last_sample`: the increment as the file ends.
  void note_increment(std::size_t id, bool after_last_sample) {
    const std::optional<double> increment = number_property(objects_[id], "wf_increment");
    ChannelData& data = data_[id];
    if (!increment || !data.increment_change.empty()) return;
    if (!data.increment) {
      if (!after_last_sample) data.increment = increment;
      return;
    }
    if (std::abs(*increment - *data.increment) <= 1e-9 * std::abs(*data.increment)) return;
    data.increment_change = fmt::format(
        "wf_increment is {} s for samples 1..{}, then {} s{}: the samples are not evenly spaced, so no one sample "
        "rate applies",
        *data.increment, data.length, *increment, after_last_sample ? " (set after the last sample)" : "");
  }

  void note_type(std::size_t id, std::uint32_t type, bool daqmx, bool digital) {
    ChannelData& data = data_[id];
    if (data.type != kVoid && data.type != type) data.mixed_types = true;
    data.type = type;
    data.daqmx = daqmx;
    data.digital = digital;
  }

  // The scales of a channel of raw data, from its NI_Scale[n] properties. An input source that is neither
  // the raw data nor one of the channel's scales, or input sources that form a cycle, are an Error
  // naming the channel.
  void read_scales(std::size_t id, const Object& object, const std::string& channel) {
    const std::optional<double> count = number_property(object, "NI_Number_Of_Scales");
    if (!count || *count < 1 || *count > 64) return;
    std::vector<std::optional<Scale>> scales(static_cast<std::size_t>(*count));
    for (std::size_t n = 0; n < scales.size(); ++n) {
      const std::string prefix = fmt::format("NI_Scale[{}]_", n);
      const std::optional<std::string> kind = text_property(object, prefix + "Scale_Type");
      if (!kind) continue;
      Scale scale;
      std::string source_key;
      if (*kind == "Linear") {
        scale.coefficients = {number_property(object, prefix + "Linear_Y_Intercept").value_or(0.0),
                              number_property(object, prefix + "Linear_Slope").value_or(1.0)};
        source_key = prefix + "Linear_Input_Source";
      } else if (*kind == "Polynomial") {
        const auto size = static_cast<std::size_t>(
            std::clamp(number_property(object, prefix + "Polynomial_Coefficients_Size").value_or(0.0), 0.0, 64.0));
        for (std::size_t i = 0; i < size; ++i) {
          scale.coefficients.push_back(
              number_property(object, fmt::format("{}Polynomial_Coefficients[{}]", prefix, i)).value_or(0.0));
        }
        source_key = prefix + "Polynomial_Input_Source";
      } else {
        unsupported_scale_[id] = *kind;
        continue;
      }
      const double source = number_property(object, source_key).value_or(kRawDataInputSource);
      if (source != kRawDataInputSource) {
        if (!(source >= 0.0 && source < static_cast<double>(scales.size()) && source == std::floor(source))) {
          throw Error(SourceLocation{path(), 0, 0},
                      fmt::format("channel '{}': {} is {}, neither 0xFFFFFFFF (the raw data) nor one of the "
                                  "channel's {} scales (NI_Number_Of_Scales)",
                                  channel, source_key, source, scales.size()));
        }
        scale.input = static_cast<std::size_t>(source);
      }
      scales[n] = scale;
    }
    // Each scale's chain of inputs must end at the raw data (or a DAQmx scaler's value).
    for (std::size_t n = 0; n < scales.size(); ++n) {
      std::vector<std::size_t> chain{n};
      for (std::size_t at = n; scales[at] && scales[at]->input && scales[*scales[at]->input];) {
        at = *scales[at]->input;
        const bool repeated = std::find(chain.begin(), chain.end(), at) != chain.end();
        chain.push_back(at);
        if (repeated) {
          throw Error(SourceLocation{path(), 0, 0},
                      fmt::format("channel '{}': the input sources of its scales form a cycle, NI_Scale[{}] (each "
                                  "takes the output of the next)",
                                  channel, fmt::join(chain, "] <- NI_Scale[")));
        }
      }
    }
    // The last scale defined gives the channel's values.
    for (std::size_t n = scales.size(); n-- > 0;) {
      if (scales[n]) {
        scales_[id] = scales;
        last_scale_[id] = n;
        return;
      }
    }
  }

  // Scale n of a chain read_scales has checked (no cycle, every input within the scales).
  static double apply(const std::vector<std::optional<Scale>>& scales, std::size_t n, double raw) {
    const Scale& scale = *scales[n];
    const double x = scale.input && scales[*scale.input] ? apply(scales, *scale.input, raw) : raw;
    double y = 0.0;
    for (std::size_t i = scale.coefficients.size(); i-- > 0;) y = y * x + scale.coefficients[i];
    return y;
  }

  void list_channels() {
    std::vector<ChannelData> by_channel;
    for (std::size_t id = 0; id < objects_.size(); ++id) {
      const Object& object = objects_[id];
      const std::vector<std::string> parts = split_object_path(object.path);
      if (parts.size() != 2) continue;
      ChannelData& data = data_[id];
      ChannelInfo info;
      info.name = parts[0] + "/" + parts[1];
      // DAQmx raw data are raw; plain data whose NI_Scaling_Status is "unscaled" are too, as npTDMS
      // reads them (its scaling.py): their values are the scales' output.
      if (data.daqmx || text_property(object, "NI_Scaling_Status") == "unscaled") read_scales(id, object, info.name);
      std::uint32_t type = data.type;
      if (type == kVoid && object.index) type = object.index->daqmx ? kVoid : object.index->type;
      info.type = type == kVoid ? "none" : type_name(type, info.numeric);
      if (data.daqmx) info.type = "daqmx " + info.type;
      if (data.digital) info.type = "daqmx digital";
      if (type == kVoid || data.digital || data.mixed_types || unsupported_scale_.contains(id)) info.numeric = false;
      if (data.mixed_types) info.type += " (types differ between segments)";
      if (const auto scale = unsupported_scale_.find(id); scale != unsupported_scale_.end()) {
        info.type += " (scale '" + scale->second + "' not supported)";
      }
      info.length = data.length;
      info.unit = text_property(object, "unit_string").value_or("");
      note_increment(id, true);
      if (!data.increment_change.empty()) {
        info.sample_rate_problem = data.increment_change;
      } else if (const auto increment = number_property(object, "wf_increment"); increment && *increment > 0.0) {
        info.sample_rate_hz = 1.0 / *increment;
      }
      info.start_time_s = number_property(object, "wf_start_time");
      channels_.push_back(std::move(info));
      channel_objects_.push_back(id);
      by_channel.push_back(data);
    }
    data_by_channel_ = std::move(by_channel);
  }

  File file_;
  std::vector<Object> objects_;
  std::map<std::string, std::size_t> object_index_;
  std::map<std::size_t, bool> has_data_;
  std::map<std::size_t, ChannelData> data_;
  std::vector<ChannelData> data_by_channel_;
  std::vector<std::size_t> channel_objects_;
  std::map<std::size_t, std::vector<std::optional<Scale>>> scales_;
  std::map<std::size_t, std::size_t> last_scale_;
  std::map<std::size_t, std::string> unsupported_scale_;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<ChannelRecord> open_tdms_record(const std::string& path) { return std::make_unique<TdmsRecord>(path); }

}  // namespace inertest
