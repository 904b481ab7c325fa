#include "inertest/core/calendar_date.h"

#include <gtest/gtest.h>

namespace inertest {
namespace {

TEST(CalendarDate, ExactlyADayOfTheCalendar) {
  const auto day = parse_calendar_date("2024-02-29");
  ASSERT_TRUE(day.has_value());
  EXPECT_EQ(*day, std::chrono::year_month_day(std::chrono::year{2024}, std::chrono::February, std::chrono::day{29}));
  for (const char* not_a_day : {"2023-02-29", "2026-13-45", "2026-04-04x", "2026-04-04T00:00:00Z", "2026-4-04",
                                "last tuesday", "+026-04-04", "2026-+4-04", "", "2026-04-0 "}) {
    EXPECT_FALSE(parse_calendar_date(not_a_day).has_value()) << not_a_day;
  }
}

}  // namespace
}  // namespace inertest
