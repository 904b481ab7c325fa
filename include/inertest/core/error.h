// The one error type of inertest. The library throws it; the CLI prints what() and exits with
// status 2; the Python module raises ValueError with the same text.
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>

namespace inertest {

// Where in an input the problem is. line and column are 1-based; 0 means "not known".
struct SourceLocation {
  std::string file;
  std::size_t line = 0;
  std::size_t column = 0;

  // "file:line:column", "file:line" or "file", as far as known.
  std::string to_string() const;
};

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message);
  Error(SourceLocation location, const std::string& message);

  // The message without the location prefix.
  const std::string& message() const { return message_; }
  const std::optional<SourceLocation>& location() const { return location_; }

 private:
  std::string message_;
  std::optional<SourceLocation> location_;
};

}  // namespace inertest
