#pragma once
// GPS time (GPST, no leap seconds) as week + seconds of week, and conversions to the calendar
// labels RTKLIB prints (GPST) and to the Unix-style seconds count used by RTKLIB tag files.
#include <string>

namespace ldv {

constexpr double kSecondsPerWeek = 604800.0;
// Seconds from the Unix epoch (1970-01-01) to the GPS epoch (1980-01-06), both counted without leap seconds.
constexpr double kGpsEpochInUnixSeconds = 315964800.0;

struct GpsTime {
  int week = 0;
  double sow_s = 0.0;  // seconds of week [0, 604800)

  double total_seconds() const { return week * kSecondsPerWeek + sow_s; }
  static GpsTime from_total_seconds(double s);
};

// Calendar date/time in the GPST scale (as RTKLIB .pos files print with "GPST").
struct CalendarTime {
  int year, month, day, hour, minute;
  double second;
};

GpsTime gps_from_calendar(const CalendarTime& c);
CalendarTime calendar_from_gps(const GpsTime& t);
// "2024/06/24 08:20:00.000" (RTKLIB layout).
std::string format_rtklib_time(const GpsTime& t, int decimals = 3);

}  // namespace ldv
