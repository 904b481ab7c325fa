#include "inertest/core/filesystem_error.h"

#include <string>

namespace inertest {

Error error_of(const std::filesystem::filesystem_error& failure) {
  std::string reason = failure.code().message();
  if (!failure.path2().empty()) reason += " (with '" + failure.path2().string() + "')";
  if (failure.path1().empty()) return Error(reason);
  return Error(SourceLocation{failure.path1().string(), 0, 0}, reason);
}

}  // namespace inertest
