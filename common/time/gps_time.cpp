#include "common/time/gps_time.hpp"

#include <cmath>
#include <cstdio>

namespace ldv {
namespace {
// Days from 1970-01-01 to year/month/day in the proleptic Gregorian calendar (H. Hinnant's algorithm).
long days_from_civil(long y, unsigned m, unsigned d) {
  y -= m <= 2;
  const long era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<long>(doe) - 719468;
}
void civil_from_days(long z, int& y, int& m, int& d) {
  z += 719468;
  const long era = (z >= 0 ? z : z - 146096) / 146097;
  const unsigned doe = static_cast<unsigned>(z - era * 146097);
  const unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const long yy = static_cast<long>(yoe) + era * 400;
  const unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const unsigned mp = (5 * doy + 2) / 153;
  d = static_cast<int>(doy - (153 * mp + 2) / 5 + 1);
  m = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
  y = static_cast<int>(yy + (m <= 2));
}
}  // namespace

GpsTime GpsTime::from_total_seconds(double s) {
  GpsTime t;
  t.week = static_cast<int>(std::floor(s / kSecondsPerWeek));
  t.sow_s = s - t.week * kSecondsPerWeek;
  return t;
}

GpsTime gps_from_calendar(const CalendarTime& c) {
  const double unix_s = days_from_civil(c.year, c.month, c.day) * 86400.0 + c.hour * 3600.0 + c.minute * 60.0 +
                        c.second;
  return GpsTime::from_total_seconds(unix_s - kGpsEpochInUnixSeconds);
}

CalendarTime calendar_from_gps(const GpsTime& t) {
  const double unix_s = t.total_seconds() + kGpsEpochInUnixSeconds;
  const double days = std::floor(unix_s / 86400.0);
  double sod = unix_s - days * 86400.0;
  CalendarTime c{};
  civil_from_days(static_cast<long>(days), c.year, c.month, c.day);
  c.hour = static_cast<int>(sod / 3600.0);
  sod -= c.hour * 3600.0;
  c.minute = static_cast<int>(sod / 60.0);
  c.second = sod - c.minute * 60.0;
  return c;
}

std::string format_rtklib_time(const GpsTime& t, int decimals) {
  // Round first so 59.9999 never prints as 60.000.
  const double scale = std::pow(10.0, decimals);
  GpsTime r = t;
  r.sow_s = std::round(t.sow_s * scale) / scale;
  const CalendarTime c = calendar_from_gps(r);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%04d/%02d/%02d %02d:%02d:%0*.*f", c.year, c.month, c.day, c.hour, c.minute,
                decimals + 3, decimals, c.second);
  return buf;
}

}  // namespace ldv
