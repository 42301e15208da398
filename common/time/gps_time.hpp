#pragma once
// GPS time (GPST, no leap seconds) as week + seconds of week, and conversions to the calendar
// labels RTKLIB prints (GPST) and to the Unix-style seconds count used by RTKLIB tag files.
#include <cmath>
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

// GPS time as one continuous count of seconds from the start of a reference week (the first week a stream
// showed): seconds of week that go on past 604800 after a rollover, as the offline readers and the filter
// use them (the filter's epochs are seconds, not week + seconds). The reference is fixed by the first call.
class ContinuousGpsTime {
 public:
  double seconds(int week, double sow_s) {
    if (!has_reference_) {
      reference_week_ = week;
      has_reference_ = true;
    }
    return (week - reference_week_) * kSecondsPerWeek + sow_s;
  }
  // Back to week + seconds of week in [0, 604800).
  GpsTime week_time(double continuous_s) const {
    const double weeks = std::floor(continuous_s / kSecondsPerWeek);
    GpsTime t{reference_week_ + static_cast<int>(weeks), continuous_s - weeks * kSecondsPerWeek};
    if (t.sow_s >= kSecondsPerWeek) t = {t.week + 1, 0.0};  // rounding of a time just below a week's end
    return t;
  }
  bool has_reference() const { return has_reference_; }
  int reference_week() const { return reference_week_; }

 private:
  bool has_reference_ = false;
  int reference_week_ = 0;
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
