// MATLAB MAT-files through matio: level 5 (v5, v7 compressed) and v7.3 (HDF5-based). Every numeric
// real vector is a channel named by its variable, and every such field of a 1x1 struct by
// "struct.field" (nested structs: "a.b.c"). A variable is read whole by matio (a level-5 variable
// cannot be read in parts once compressed) and kept while its channel is read, one at a time.
#include <fmt/format.h>
#include <matio.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <utility>

#include "inertest/core/error.h"
#include "io/channel_readers.h"
#include "io/mat_level5_check.h"

namespace inertest {
namespace {

// matio reports problems through its log; the last message goes into the Error raised.
thread_local std::string last_matio_message;

void install_matio_log() {
  static const bool installed = [] {
    Mat_LogInitFunc("inertest", [](int, char* message) { last_matio_message = message != nullptr ? message : ""; });
    return true;
  }();
  (void)installed;
}

// ": MESSAGE" of matio's last log message since the last call, or nothing.
std::string matio_detail() {
  std::string text = std::exchange(last_matio_message, "");
  return text.empty() ? "" : ": " + text;
}

struct VariableDeleter {
  void operator()(matvar_t* variable) const { Mat_VarFree(variable); }
};
using Variable = std::unique_ptr<matvar_t, VariableDeleter>;

struct FileCloser {
  void operator()(mat_t* file) const { Mat_Close(file); }
};

const char* class_type_name(matio_classes class_type) {
  switch (class_type) {
    case MAT_C_DOUBLE: return "f64";
    case MAT_C_SINGLE: return "f32";
    case MAT_C_INT8: return "i8";
    case MAT_C_UINT8: return "u8";
    case MAT_C_INT16: return "i16";
    case MAT_C_UINT16: return "u16";
    case MAT_C_INT32: return "i32";
    case MAT_C_UINT32: return "u32";
    case MAT_C_INT64: return "i64";
    case MAT_C_UINT64: return "u64";
    case MAT_C_CELL: return "cell";
    case MAT_C_STRUCT: return "struct";
    case MAT_C_CHAR: return "char";
    case MAT_C_SPARSE: return "sparse";
    case MAT_C_EMPTY: return "empty";
    default: return "object";
  }
}

template <typename T>
void convert(const void* data, std::size_t count, std::vector<double>& out) {
  const T* values = static_cast<const T*>(data);
  out.resize(count);
  for (std::size_t i = 0; i < count; ++i) out[i] = static_cast<double>(values[i]);
}

// The samples of a numeric variable read with its data; false for a class not read as numbers.
bool convert_variable(const matvar_t& variable, std::size_t count, std::vector<double>& out) {
  switch (variable.class_type) {
    case MAT_C_DOUBLE: convert<double>(variable.data, count, out); return true;
    case MAT_C_SINGLE: convert<float>(variable.data, count, out); return true;
    case MAT_C_INT8: convert<std::int8_t>(variable.data, count, out); return true;
    case MAT_C_UINT8: convert<std::uint8_t>(variable.data, count, out); return true;
    case MAT_C_INT16: convert<std::int16_t>(variable.data, count, out); return true;
    case MAT_C_UINT16: convert<std::uint16_t>(variable.data, count, out); return true;
    case MAT_C_INT32: convert<std::int32_t>(variable.data, count, out); return true;
    case MAT_C_UINT32: convert<std::uint32_t>(variable.data, count, out); return true;
    case MAT_C_INT64: convert<std::int64_t>(variable.data, count, out); return true;
    case MAT_C_UINT64: convert<std::uint64_t>(variable.data, count, out); return true;
    default: return false;
  }
}

std::uint64_t element_count(const matvar_t& variable) {
  std::uint64_t count = 1;
  for (int i = 0; i < variable.rank; ++i) count *= variable.dims[i];
  return variable.rank > 0 ? count : 0;
}

std::string shape_of(const matvar_t& variable) {
  std::string shape;
  for (int i = 0; i < variable.rank; ++i) {
    if (i > 0) shape += 'x';
    shape += std::to_string(variable.dims[i]);
  }
  return shape;
}

bool is_vector(const matvar_t& variable) {
  int longer_than_one = 0;
  for (int i = 0; i < variable.rank; ++i) longer_than_one += variable.dims[i] > 1 ? 1 : 0;
  return longer_than_one <= 1;
}

// "a.b.c" -> {"a", "b", "c"}
std::vector<std::string> split_path(const std::string& name) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = name.find('.', start);
    parts.push_back(name.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) return parts;
    start = dot + 1;
  }
}

class MatRecord final : public ChannelRecord {
 public:
  explicit MatRecord(const std::string& path) : ChannelRecord(path, ChannelRecordFormat::kMat) {
    install_matio_log();
    // matio falls back to reading any other bytes as a MAT v4 file, which has no header to check.
    if (detect_channel_record_format(path) != ChannelRecordFormat::kMat) {
      throw Error(SourceLocation{path, 0, 0},
                  "not a MAT-file: no MAT-file header (\"MATLAB 5.0 MAT-file\" or 7.3, the version and the endian "
                  "indicator at bytes 124..127)");
    }
    check_mat_level5_headers(path);
    file_size_ = std::filesystem::file_size(path);
    file_.reset(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
    if (!file_) throw Error(SourceLocation{path, 0, 0}, "not a readable MAT-file" + matio_detail());
    while (true) {
      Variable variable(Mat_VarReadNextInfo(file_.get()));
      if (!variable) break;
      if (variable->name != nullptr) add(*variable, variable->name);
    }
    const std::string detail = matio_detail();
    if (channels_.empty()) {
      throw Error(SourceLocation{path, 0, 0}, "the MAT-file holds no variable that can be read" + detail);
    }
  }

  void read(std::size_t channel, std::uint64_t first, std::span<double> out) override {
    const ChannelInfo& info = channels_.at(channel);
    const SourceLocation where{path(), 0, 0};
    if (first + out.size() > info.length) {
      throw Error(where, channel_range_context(info, first, out.size()) + fmt::format(": beyond its {} samples", info.length));
    }
    if (loaded_channel_ != channel) load(channel);
    std::copy_n(loaded_.begin() + static_cast<std::ptrdiff_t>(first), out.size(), out.begin());
  }

 private:
  void add(const matvar_t& variable, const std::string& name) {
    if (variable.class_type == MAT_C_STRUCT && element_count(variable) == 1) {
      const unsigned fields = Mat_VarGetNumberOfFields(const_cast<matvar_t*>(&variable));
      char* const* names = Mat_VarGetStructFieldnames(&variable);
      for (unsigned i = 0; i < fields && names != nullptr; ++i) {
        matvar_t* field = Mat_VarGetStructFieldByIndex(const_cast<matvar_t*>(&variable), i, 0);
        if (field != nullptr && names[i] != nullptr) add(*field, name + "." + names[i]);
      }
      return;
    }
    ChannelInfo info;
    info.name = name;
    info.type = class_type_name(variable.class_type);
    if (variable.isLogical != 0) info.type = "bool";
    info.length = element_count(variable);
    const bool numeric_class = variable.class_type >= MAT_C_DOUBLE && variable.class_type <= MAT_C_UINT64;
    info.numeric = numeric_class && variable.isComplex == 0 && is_vector(variable);
    if (variable.isComplex != 0) info.type.insert(0, "complex ");
    if (numeric_class && !is_vector(variable)) {
      info.type += ' ';
      info.type += shape_of(variable);
    }
    channels_.push_back(std::move(info));
    class_of_.push_back(variable.class_type);
  }

  void load(std::size_t channel) {
    const ChannelInfo& info = channels_[channel];
    const SourceLocation where{path(), 0, 0};
    const std::vector<std::string> parts = split_path(info.name);
    loaded_channel_ = static_cast<std::size_t>(-1);
    loaded_.clear();
    // zlib inflates at most 1032 bytes from one: a variable that claims more than that is corrupt,
    // and matio would first allocate all it claims.
    const std::uint64_t stored_bytes = info.length * Mat_SizeOfClass(class_of_[channel]);
    if (stored_bytes / 1032 > file_size_) {
      throw Error(where, fmt::format("channel '{}' claims {} samples, more than the file's {} bytes can hold (a corrupt "
                                     "variable?)",
                                     info.name, info.length, file_size_));
    }
    last_matio_message.clear();
    Variable variable(Mat_VarRead(file_.get(), parts.front().c_str()));
    // matio may log a failed inflate of a compressed variable and still return what it got.
    const std::string detail = matio_detail();
    if (!variable || !detail.empty()) {
      throw Error(where, fmt::format("channel '{}': cannot read the variable{} (a corrupt or truncated variable?)",
                                     info.name, detail));
    }
    const matvar_t* field = variable.get();
    for (std::size_t i = 1; i < parts.size() && field != nullptr; ++i) {
      field = Mat_VarGetStructFieldByName(const_cast<matvar_t*>(field), parts[i].c_str(), 0);
    }
    // matio reads a name's first variable: in a file holding two of one name, that may be another
    // than the channel listed (a complex one, whose data is two pointers, read as samples overran).
    if (field != nullptr && (field->isComplex != 0 || field->class_type != class_of_[channel])) {
      throw Error(where, fmt::format("channel '{}': the file holds another variable of this name before it, which is "
                                     "the one that can be read (rename one of them)",
                                     info.name));
    }
    if (field == nullptr || field->data == nullptr || element_count(*field) != info.length ||
        field->nbytes < info.length * Mat_SizeOfClass(field->class_type) ||
        !convert_variable(*field, static_cast<std::size_t>(info.length), loaded_)) {
      throw Error(where, fmt::format("channel '{}': its data cannot be read (a corrupt or truncated variable?)", info.name));
    }
    loaded_channel_ = channel;
  }

  std::unique_ptr<mat_t, FileCloser> file_;
  std::uint64_t file_size_ = 0;
  std::vector<int> class_of_;  // matio_classes of each channel
  std::size_t loaded_channel_ = static_cast<std::size_t>(-1);
  std::vector<double> loaded_;
};

}  // namespace

std::unique_ptr<ChannelRecord> open_mat_record(const std::string& path) { return std::make_unique<MatRecord>(path); }

}  // namespace inertest
