#include <gtest/gtest.h>

#include "common/time/gps_time.hpp"

using namespace ldv;

TEST(GpsTime, SecondWeekRolloverIsWeek2048) {
  // The second GPS week-number rollover happened at 2019-04-07 00:00:00 GPST (week 2048).
  const GpsTime t = gps_from_calendar({2019, 4, 7, 0, 0, 0.0});
  EXPECT_EQ(t.week, 2048);
  EXPECT_DOUBLE_EQ(t.sow_s, 0.0);
}

TEST(GpsTime, CalendarRoundTripAndRtklibFormat) {
  const CalendarTime c{2024, 6, 24, 8, 20, 0.25};
  const GpsTime t = gps_from_calendar(c);
  EXPECT_EQ(format_rtklib_time(t, 3), "2024/06/24 08:20:00.250");
  // 2024-06-24 is a Monday: one day plus 8h20m into the week.
  EXPECT_NEAR(t.sow_s, 86400.0 + 8 * 3600 + 20 * 60 + 0.25, 1e-9);
}
