// A read-only memory map of a whole file: records of 10^9 samples are read without copies and
// without iostreams. An empty file maps to an empty view.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace inertest {

// text without a leading UTF-8 byte order mark (EF BB BF).
inline std::string_view without_byte_order_mark(std::string_view text) {
  constexpr std::string_view kMark = "\xEF\xBB\xBF";
  return text.starts_with(kMark) ? text.substr(kMark.size()) : text;
}

class MappedFile {
 public:
  // Throws Error naming the file when it cannot be opened or mapped.
  explicit MappedFile(const std::string& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  MappedFile(MappedFile&& other) noexcept;
  MappedFile& operator=(MappedFile&& other) noexcept;

  const std::string& path() const { return path_; }
  std::string_view bytes() const { return {data_, size_}; }
  // The file as text: its bytes after the UTF-8 byte order mark that Excel's "CSV UTF-8" (and
  // Notepad) write first, if there is one (read as text, it made the first header name "\xEF\xBB\xBFsupply").
  std::string_view text() const { return without_byte_order_mark(bytes()); }
  std::size_t size() const { return size_; }

 private:
  std::string path_;
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace inertest
