#pragma once
// Calendar date-times as loggers print them ("2024-08-27T17:30:01.123Z", "2024-08-27 17:30:01.123+02:00",
// "2024/08/27 17:30:01.123") and UTC to GPS time. GPS - UTC is the leap seconds since 1980 (IERS Bulletin C,
// 18 s since 2017-01-01); written here rather than read from tzdata's leap-seconds.list at run time (a service must not
// depend on a file the machine may not have); tests/common/test_utc_text.cpp checks it against that file.
#include <string_view>

#include "common/time/gps_time.hpp"

namespace ldv {

// A date and time of day, with the zone it states (seconds east of UTC; 0 for "Z"). false when the text is not
// one: date "YYYY-MM-DD" or "YYYY/MM/DD", then 'T' or one space, then "hh:mm:ss" with an optional fraction, then an
// optional "Z" or "+hh:mm" / "-hh:mm" / "+hhmm". has_zone says whether the text named its zone.
struct DateTimeText {
  CalendarTime calendar{};
  double zone_east_s = 0.0;
  bool has_zone = false;
};
bool parse_date_time(std::string_view text, DateTimeText& out);

// GPS - UTC [s] at a UTC calendar time (0 before 1981-07-01).
int gps_minus_utc_s(const CalendarTime& utc);

// The GPS time of a UTC calendar time.
GpsTime gps_from_utc(const CalendarTime& utc);

}  // namespace ldv
