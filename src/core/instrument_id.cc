#include "inertest/core/instrument_id.h"

#include <algorithm>
#include <fmt/format.h>

#include "inertest/core/utf8.h"

namespace inertest {

std::optional<std::string> instrument_id_problem(std::string_view id) {
  if (id.empty()) return "is empty";
  if (id.size() > 256) return "is longer than 256 bytes";
  if (std::any_of(id.begin(), id.end(), is_ascii_control)) {
    return "contains a control character";
  }
  // "." and ".." would name the directory of the history pages, not a page of their own.
  if (id.find_first_not_of('.') == std::string_view::npos) return fmt::format("'{}' is only dots", id);
  std::size_t size = 0;
  bool blank_first = false;
  bool blank_last = false;
  for (std::size_t at = 0; at < id.size(); at += size) {
    const char32_t c = code_point_at(id, at, size);
    if (is_invisible(c)) return fmt::format("'{}' holds an invisible character (a zero-width space or joiner)", id);
    // A blank around the id: another instrument that prints as the same ("FOG-001 ", "FOG-001" + U+00A0).
    if (at == 0) blank_first = is_unicode_blank(c);
    blank_last = is_unicode_blank(c);
  }
  if (blank_first || blank_last) return fmt::format("'{}' has blanks around it", id);
  return std::nullopt;
}

}  // namespace inertest
