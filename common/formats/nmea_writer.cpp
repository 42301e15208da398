#include "common/formats/nmea_writer.hpp"

#include <cmath>
#include <cstdio>

#include "common/math/rotation.hpp"

namespace ldv::nmea {
namespace {
std::string hhmmss(const CalendarTime& t) {
  char b[32];
  std::snprintf(b, sizeof b, "%02d%02d%05.2f", t.hour, t.minute, t.second);
  return b;
}
// ddmm.mmmmmmm / dddmm.mmmmmmm with hemisphere.
std::string ddmm_text(double rad, int deg_digits, char pos, char neg) {
  const double a = std::abs(rad) * kRadToDeg;
  int d = static_cast<int>(std::floor(a));
  double m = (a - d) * 60.0;
  if (m >= 59.99999995) {  // rounding to 7 decimals would print 60
    m = 0.0;
    ++d;
  }
  char b[48];
  std::snprintf(b, sizeof b, "%0*d%010.7f,%c", deg_digits, d, m, rad >= 0 ? pos : neg);
  return b;
}
}  // namespace

uint8_t checksum(std::string_view body) {
  uint8_t c = 0;
  for (char ch : body) c ^= static_cast<uint8_t>(ch);
  return c;
}

std::string sentence(std::string_view body) {
  char tail[8];
  std::snprintf(tail, sizeof tail, "*%02X\r\n", checksum(body));
  return "$" + std::string(body) + tail;
}

CalendarTime utc_from_gps(const GpsTime& t, int leap_seconds) {
  // Round to centiseconds first so 59.999 never prints as 60.00.
  GpsTime r = GpsTime::from_total_seconds(std::round((t.total_seconds() - leap_seconds) * 100.0) / 100.0);
  return calendar_from_gps(r);
}

std::string gga(const CalendarTime& utc, const Geodetic& pos, const GgaFields& f, std::string_view talker) {
  char tail[160];
  char hdop[16] = "";
  if (f.hdop >= 0) std::snprintf(hdop, sizeof hdop, "%.1f", f.hdop);
  char age[16] = "";
  if (f.age_s >= 0) std::snprintf(age, sizeof age, "%.1f", f.age_s);
  char station[8] = "";
  if (f.age_s >= 0) std::snprintf(station, sizeof station, "%04d", f.station_id);
  std::snprintf(tail, sizeof tail, ",%d,%02d,%s,%.4f,M,0.0,M,%s,%s", f.quality, f.num_sats, hdop, pos.h_m, age,
                station);
  return sentence(std::string(talker) + "GGA," + hhmmss(utc) + "," + ddmm_text(pos.lat_rad, 2, 'N', 'S') + "," +
                  ddmm_text(pos.lon_rad, 3, 'E', 'W') + tail);
}

std::string gst(const CalendarTime& utc, double lat_std, double lon_std, double alt_std, std::string_view talker) {
  const double rms = std::sqrt(lat_std * lat_std + lon_std * lon_std + alt_std * alt_std);
  const double major = std::max(lat_std, lon_std), minor = std::min(lat_std, lon_std);
  const double orient = lat_std >= lon_std ? 0.0 : 90.0;
  char b[160];
  std::snprintf(b, sizeof b, "GST,%s,%.3f,%.3f,%.3f,%.1f,%.3f,%.3f,%.3f", hhmmss(utc).c_str(), rms, major, minor, orient,
                lat_std, lon_std, alt_std);
  return sentence(std::string(talker) + b);
}

std::string zda(const CalendarTime& utc, std::string_view talker) {
  char b[64];
  std::snprintf(b, sizeof b, "ZDA,%s,%02d,%02d,%04d,00,00", hhmmss(utc).c_str(), utc.day, utc.month, utc.year);
  return sentence(std::string(talker) + b);
}

namespace {
double course_deg(double vn, double ve) {
  const double course = std::atan2(ve, vn) * kRadToDeg;
  if (course < 0) return course + 360.0 >= 359.995 ? 0.0 : course + 360.0;  // would print as 360.00
  return course;
}
}  // namespace

std::string vtg(double vn, double ve, char mode, std::string_view talker) {
  const double speed_mps = std::hypot(vn, ve);
  char b[96];
  std::snprintf(b, sizeof b, "VTG,%.2f,T,,M,%.3f,N,%.3f,K,%c", course_deg(vn, ve), speed_mps / 0.514444,
                speed_mps * 3.6, mode);
  return sentence(std::string(talker) + b);
}

std::string hdt(double heading_rad, std::string_view talker) {
  double deg = std::fmod(heading_rad * kRadToDeg, 360.0);
  if (deg < 0) deg += 360.0;
  if (deg >= 359.995) deg = 0.0;  // prints as 360.00 otherwise
  char b[48];
  std::snprintf(b, sizeof b, "HDT,%.2f,T", deg);
  return sentence(std::string(talker) + b);
}

std::string rmc(const CalendarTime& utc, const Geodetic& pos, double vn, double ve, char mode, std::string_view talker) {
  const double speed_kn = std::hypot(vn, ve) / 0.514444;
  char b[96];
  std::snprintf(b, sizeof b, ",%.3f,%.2f,%02d%02d%02d,,,%c", speed_kn, course_deg(vn, ve), utc.day, utc.month,
                utc.year % 100, mode);
  return sentence(std::string(talker) + "RMC," + hhmmss(utc) + ",A," + ddmm_text(pos.lat_rad, 2, 'N', 'S') + "," +
                  ddmm_text(pos.lon_rad, 3, 'E', 'W') + b);
}

}  // namespace ldv::nmea
