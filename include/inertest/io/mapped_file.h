// A read-only memory map of a whole file: records of 10^9 samples are read without copies and
// without iostreams. An empty file maps to an empty view.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace inertest {

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
  std::size_t size() const { return size_; }

 private:
  std::string path_;
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace inertest
