#include "common/time/utc_text.hpp"

#include <array>
#include <cctype>
#include <charconv>
#include <string>

namespace ldv {
namespace {

// UTC dates from which GPS - UTC took the next value (1 s at 1981-07-01 ... 18 s at 2017-01-01).
struct LeapStep {
  int year, month;  // the step is at 00:00 UTC on the 1st of this month
};
constexpr std::array<LeapStep, 18> kLeapSteps{{{1981, 7},
                                               {1982, 7},
                                               {1983, 7},
                                               {1985, 7},
                                               {1988, 1},
                                               {1990, 1},
                                               {1991, 1},
                                               {1992, 7},
                                               {1993, 7},
                                               {1994, 7},
                                               {1996, 1},
                                               {1997, 7},
                                               {1999, 1},
                                               {2006, 1},
                                               {2009, 1},
                                               {2012, 7},
                                               {2015, 7},
                                               {2017, 1}}};

// Reads exactly `digits` decimal digits at text[at]; advances at.
bool digits_at(std::string_view text, size_t& at, int digits, int& value) {
  if (at + static_cast<size_t>(digits) > text.size()) return false;
  value = 0;
  for (int k = 0; k < digits; ++k) {
    const char c = text[at + static_cast<size_t>(k)];
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    value = value * 10 + (c - '0');
  }
  at += static_cast<size_t>(digits);
  return true;
}

bool char_at(std::string_view text, size_t& at, char c) {
  if (at >= text.size() || text[at] != c) return false;
  ++at;
  return true;
}

}  // namespace

bool parse_date_time(std::string_view text, DateTimeText& out) {
  size_t at = 0;
  CalendarTime c{};
  if (!digits_at(text, at, 4, c.year)) return false;
  const char date_sep = at < text.size() ? text[at] : '\0';
  if (date_sep != '-' && date_sep != '/') return false;
  int second = 0;
  if (!char_at(text, at, date_sep) || !digits_at(text, at, 2, c.month) || !char_at(text, at, date_sep) ||
      !digits_at(text, at, 2, c.day))
    return false;
  if (!(char_at(text, at, 'T') || char_at(text, at, ' '))) return false;
  if (!digits_at(text, at, 2, c.hour) || !char_at(text, at, ':') || !digits_at(text, at, 2, c.minute) ||
      !char_at(text, at, ':') || !digits_at(text, at, 2, second))
    return false;
  c.second = second;
  if (at < text.size() && (text[at] == '.' || text[at] == ',')) {
    const size_t start = at++;
    while (at < text.size() && std::isdigit(static_cast<unsigned char>(text[at]))) ++at;
    if (at == start + 1) return false;
    double fraction = 0.0;
    std::string digits = "0.";
    digits.append(text.substr(start + 1, at - start - 1));
    const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), fraction);
    if (r.ec != std::errc()) return false;
    c.second += fraction;
  }
  DateTimeText d;
  if (char_at(text, at, 'Z')) {
    d.has_zone = true;
  } else if (at < text.size() && (text[at] == '+' || text[at] == '-')) {
    const double sign = text[at++] == '-' ? -1.0 : 1.0;
    int hh = 0, mm = 0;
    if (!digits_at(text, at, 2, hh)) return false;
    char_at(text, at, ':');
    if (!digits_at(text, at, 2, mm) || hh > 23 || mm > 59) return false;
    d.zone_east_s = sign * (hh * 3600.0 + mm * 60.0);
    d.has_zone = true;
  }
  if (at != text.size()) return false;
  if (c.month < 1 || c.month > 12 || c.day < 1 || c.day > 31 || c.hour > 23 || c.minute > 59 || c.second >= 61.0)
    return false;
  d.calendar = c;
  out = d;
  return true;
}

int gps_minus_utc_s(const CalendarTime& utc) {
  int leap = 0;
  for (const LeapStep& s : kLeapSteps)
    if (utc.year > s.year || (utc.year == s.year && utc.month >= s.month)) ++leap;
  return leap;
}

GpsTime gps_from_utc(const CalendarTime& utc) {
  return GpsTime::from_total_seconds(gps_from_calendar(utc).total_seconds() + gps_minus_utc_s(utc));
}

}  // namespace ldv
