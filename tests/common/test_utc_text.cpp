// Date-time text as loggers print it, and UTC to GPS time: against published instants (GPS week 1930 began at
// 2017-01-01 00:00:00 UTC + 18 s, the day the 18th leap second took effect) and against tzdata's leap-seconds.list
// (IERS Bulletin C), an independent copy of the leap-second table.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/time/utc_text.hpp"

namespace ldv {
namespace {

TEST(UtcText, GivenTheDateTimesLoggersPrint_ThenEachIsReadWithItsZone) {
  struct Case {
    const char* text;
    int year, month, day, hour, minute;
    double second, zone_east_s;
    bool has_zone;
  };
  for (const Case& c : {Case{"2024-08-27T17:30:01.123Z", 2024, 8, 27, 17, 30, 1.123, 0.0, true},
                        Case{"2024-08-27 17:30:01.5", 2024, 8, 27, 17, 30, 1.5, 0.0, false},
                        Case{"2024/08/27 17:30:01", 2024, 8, 27, 17, 30, 1.0, 0.0, false},
                        Case{"2024-08-27T19:30:01,25+02:00", 2024, 8, 27, 19, 30, 1.25, 7200.0, true},
                        Case{"2024-08-27T12:00:00-0530", 2024, 8, 27, 12, 0, 0.0, -19800.0, true}}) {
    DateTimeText d;
    ASSERT_TRUE(parse_date_time(c.text, d)) << c.text;
    EXPECT_EQ(d.calendar.year, c.year) << c.text;
    EXPECT_EQ(d.calendar.month, c.month) << c.text;
    EXPECT_EQ(d.calendar.day, c.day) << c.text;
    EXPECT_EQ(d.calendar.hour, c.hour) << c.text;
    EXPECT_EQ(d.calendar.minute, c.minute) << c.text;
    EXPECT_NEAR(d.calendar.second, c.second, 1e-12) << c.text;
    EXPECT_EQ(d.zone_east_s, c.zone_east_s) << c.text;
    EXPECT_EQ(d.has_zone, c.has_zone) << c.text;
  }
  DateTimeText d;
  for (const char* bad : {"", "17:30:01", "2024-08-27", "2024-13-01T00:00:00", "2024-08-27T24:00:00",
                          "2024-08-27T17:30:01.", "2024-08-27T17:30:01Zulu", "2024-08-27 17:30", "1724779801.123",
                          "2024-08/27 17:30:01", "2024-08-27T17:30:01+25:00"})
    EXPECT_FALSE(parse_date_time(bad, d)) << bad;
}

TEST(UtcText, GivenTheInstantsAroundTheLastLeapSecond_ThenTheGpsTimeIsThePublishedOne) {
  // GPS week 1930 began at 2017-01-01 00:00:00 GPST; UTC was 18 s behind from that day on, 17 s the day before.
  const GpsTime new_year = gps_from_utc({2017, 1, 1, 0, 0, 0.0});
  EXPECT_EQ(new_year.week, 1930);
  EXPECT_NEAR(new_year.sow_s, 18.0, 1e-9);
  const GpsTime before = gps_from_utc({2016, 12, 31, 23, 59, 59.0});
  EXPECT_EQ(before.week, 1930);
  EXPECT_NEAR(before.sow_s, 16.0, 1e-9);
  EXPECT_EQ(gps_minus_utc_s({1980, 1, 6, 0, 0, 0.0}), 0);
  EXPECT_EQ(gps_minus_utc_s({2026, 12, 7, 0, 0, 0.0}), 18);
}

// tzdata's copy of IERS Bulletin C: "NTP seconds  TAI-UTC  # date"; GPS - UTC = TAI - UTC - 19 from 1980 on.
TEST(UtcText, GivenTzdatasLeapSecondList_ThenEveryStepSince1980Agrees) {
  const std::filesystem::path list = "/usr/share/zoneinfo/leap-seconds.list";
  if (!std::filesystem::exists(list)) GTEST_SKIP() << list << " not installed (Debian package tzdata)";
  std::ifstream in(list);
  int steps = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream row(line);
    double ntp_s = 0.0;
    int tai_minus_utc = 0;
    if (!(row >> ntp_s >> tai_minus_utc)) continue;
    constexpr double kNtpToUnix_s = 2208988800.0;  // 1900-01-01 to 1970-01-01
    const GpsTime step = GpsTime::from_total_seconds(ntp_s - kNtpToUnix_s - kGpsEpochInUnixSeconds);
    if (step.week < 0 || ntp_s - kNtpToUnix_s < kGpsEpochInUnixSeconds) continue;  // before GPS time began
    const CalendarTime at = calendar_from_gps(step);  // the step's UTC date (this scale counts no leap seconds)
    EXPECT_EQ(gps_minus_utc_s(at), tai_minus_utc - 19) << line;
    const CalendarTime second_before = calendar_from_gps(GpsTime::from_total_seconds(step.total_seconds() - 1.0));
    EXPECT_EQ(gps_minus_utc_s(second_before), tai_minus_utc - 20) << line;
    ++steps;
  }
  EXPECT_EQ(steps, 18);
}

}  // namespace
}  // namespace ldv
