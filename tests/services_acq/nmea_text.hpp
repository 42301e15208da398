#pragma once
// NMEA 0183 text for tests: one epoch of GGA + RMC (+ ZDA) as a receiver prints it.
#include <cmath>
#include <cstdio>
#include <string>

#include "common/formats/nmea_framer.hpp"

namespace ldv::test {

// "$<body>*hh\r\n"
inline std::string nmea_line(const std::string& body) {
  char cs[8];
  std::snprintf(cs, sizeof cs, "*%02X\r\n", gnss::nmea_checksum(body));
  return "$" + body + cs;
}

inline std::string nmea_angle(double deg, int degree_digits) {
  const double a = std::abs(deg);
  const int d = static_cast<int>(a);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%0*d%010.7f", degree_digits, d, (a - d) * 60.0);
  return buf;
}

struct NmeaEpoch {
  double utc_seconds_of_day = 0;
  int year = 2024, month = 6, day = 24;
  double lat_deg = 45.0, lon_deg = 7.0, height_m = 300.0;
  int gga_quality = 4;  // RTK fixed
  int sats = 14;
  bool with_zda = true;
};

inline std::string nmea_epoch_text(const NmeaEpoch& e) {
  const int hh = static_cast<int>(e.utc_seconds_of_day / 3600);
  const int mm = static_cast<int>(std::fmod(e.utc_seconds_of_day, 3600.0) / 60);
  const double ss = std::fmod(e.utc_seconds_of_day, 60.0);
  char time[16], date[16], body[256];
  std::snprintf(time, sizeof time, "%02d%02d%05.2f", hh, mm, ss);
  std::snprintf(date, sizeof date, "%02d%02d%02d", e.day, e.month, e.year % 100);
  const std::string lat = nmea_angle(e.lat_deg, 2), lon = nmea_angle(e.lon_deg, 3);
  const char ns = e.lat_deg >= 0 ? 'N' : 'S', ew = e.lon_deg >= 0 ? 'E' : 'W';
  std::string out;
  std::snprintf(body, sizeof body, "GPGGA,%s,%s,%c,%s,%c,%d,%02d,0.8,%.3f,M,0.000,M,1.0,0000", time, lat.c_str(), ns,
                lon.c_str(), ew, e.gga_quality, e.sats, e.height_m);
  out += nmea_line(body);
  std::snprintf(body, sizeof body, "GPRMC,%s,A,%s,%c,%s,%c,0.00,,%s,,,R", time, lat.c_str(), ns, lon.c_str(), ew, date);
  out += nmea_line(body);
  if (e.with_zda) {
    std::snprintf(body, sizeof body, "GPZDA,%s,%02d,%02d,%04d,00,00", time, e.day, e.month, e.year);
    out += nmea_line(body);
  }
  return out;
}

}  // namespace ldv::test
