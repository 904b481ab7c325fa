#include "inertest/core/instrument_id.h"

#include <algorithm>

namespace inertest {

std::optional<std::string> instrument_id_problem(std::string_view id) {
  if (id.empty()) return "is empty";
  if (id.size() > 256) return "is longer than 256 bytes";
  if (std::any_of(id.begin(), id.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; })) {
    return "contains a control character";
  }
  // "." and ".." would name the directory of the history pages, not a page of their own.
  if (id.find_first_not_of('.') == std::string_view::npos) return "'" + std::string(id) + "' is only dots";
  return std::nullopt;
}

}  // namespace inertest
