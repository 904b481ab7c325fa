#include "inertest/io/atomic_write.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <string>
#include <unistd.h>
#include <vector>

#include "inertest/core/error.h"

namespace inertest {

void write_file_atomically(const std::string& path, std::string_view content) {
  std::string pattern = path + ".tmp-XXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) throw Error(SourceLocation{path, 0, 0}, std::string("cannot create: ") + std::strerror(errno));
  const std::string temporary(name.data());
  auto fail = [&](const char* what) {
    const int saved = errno;
    ::close(fd);
    ::unlink(temporary.c_str());
    throw Error(SourceLocation{path, 0, 0}, std::string(what) + ": " + std::strerror(saved));
  };
  std::size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("cannot write");
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fchmod(fd, 0644) != 0) fail("cannot set permissions");
  if (::fsync(fd) != 0) fail("cannot flush");
  if (::close(fd) != 0) {
    ::unlink(temporary.c_str());
    throw Error(SourceLocation{path, 0, 0}, std::string("cannot close: ") + std::strerror(errno));
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int saved = errno;
    ::unlink(temporary.c_str());
    throw Error(SourceLocation{path, 0, 0}, std::string("cannot rename into place: ") + std::strerror(saved));
  }
}

void move_staged_files(const std::filesystem::path& staging, const std::filesystem::path& out,
                       const std::vector<std::filesystem::path>& names) {
  for (const auto& name : names) {
    if (std::filesystem::is_directory(out / name)) {
      throw Error(SourceLocation{(out / name).string(), 0, 0}, "a directory is where a file is to be written");
    }
    // A file where a directory of the path is to be ("coefficients" for "coefficients/model.json"):
    // found before the first file moves, not after results.json had replaced the earlier run's.
    for (std::filesystem::path above = name.parent_path(); !above.empty(); above = above.parent_path()) {
      if (std::filesystem::exists(out / above) && !std::filesystem::is_directory(out / above)) {
        throw Error(SourceLocation{(out / above).string(), 0, 0},
                    "a file is where the directory of '" + name.string() + "' is to be made");
      }
    }
  }
  for (const auto& name : names) {
    std::filesystem::create_directories((out / name).parent_path());
    std::filesystem::rename(staging / name, out / name);
  }
}

void require_output_directory(const std::filesystem::path& out) {
  if (std::filesystem::exists(out) && !std::filesystem::is_directory(out)) {
    throw Error(SourceLocation{out.string(), 0, 0}, "the output directory is a file");
  }
}

}  // namespace inertest
