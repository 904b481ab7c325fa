#include "inertest/core/error.h"

#include <fmt/format.h>
#include <utility>

namespace inertest {

std::string SourceLocation::to_string() const {
  if (line == 0) return file.empty() ? "<input>" : file;
  if (column == 0) return fmt::format("{}:{}", file.empty() ? "<input>" : file, line);
  return fmt::format("{}:{}:{}", file.empty() ? "<input>" : file, line, column);
}

Error::Error(const std::string& message) : std::runtime_error(message), message_(message) {}

Error::Error(SourceLocation location, const std::string& message)
    : std::runtime_error(location.to_string() + ": " + message),
      message_(message),
      location_(std::move(location)) {}

}  // namespace inertest
