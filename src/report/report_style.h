// The report's stylesheet, inlined into the page: screen layout, and print rules (A4, each
// procedure on a new page, no figure or table row split across pages, verdict colours kept).
#pragma once

#include <string_view>

namespace inertest::report {

std::string_view report_css();

}  // namespace inertest::report
