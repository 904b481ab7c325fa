// An instrument's identifier keys its campaigns in the archive, names its history page and its URL:
// the rules a plan's [instrument] id and an archived results.json are both held to.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace inertest {

// Why `id` cannot identify an instrument ("is empty", "is longer than 256 bytes", "contains a
// control character", "'..' is only dots", "holds an invisible character", "has blanks around it":
// a space, a no-break or another Unicode space first or last), or nothing when it can. Each would
// be an instrument of its own that prints as another.
std::optional<std::string> instrument_id_problem(std::string_view id);

}  // namespace inertest
