// Test dates as the plans write them and the archive stores and compares them.
#pragma once

#include <chrono>
#include <optional>
#include <string_view>

namespace inertest {

// The day `text` names when it is exactly YYYY-MM-DD and a day of the Gregorian calendar, what
// sorts and compares as text; nullopt otherwise ("2026-02-30", "2026-13-45", "2026-04-04x", a time
// after the day, "last tuesday").
std::optional<std::chrono::year_month_day> parse_calendar_date(std::string_view text);

}  // namespace inertest
