#pragma once
// NMEA 0183 sentence writers (GGA, GST, ZDA, RMC, VTG, HDT) with correct checksums and CR LF endings, as a
// GNSS receiver or an RTK engine prints them. Times are UTC (GPS time minus the leap seconds).
#include <string>
#include <string_view>

#include "common/geo/geodetic.hpp"
#include "common/time/gps_time.hpp"

namespace ldv::nmea {

// XOR of the characters between '$' and '*'.
uint8_t checksum(std::string_view body);
// "$" + body + "*HH\r\n".
std::string sentence(std::string_view body);

// UTC calendar time of a GPS time.
CalendarTime utc_from_gps(const GpsTime& t, int leap_seconds);

struct GgaFields {
  int quality = 4;  // 0 invalid, 1 GPS, 2 DGPS, 4 RTK fixed, 5 RTK float
  int num_sats = 0;
  double hdop = 0.8;    // < 0: empty field (a solution that has none, e.g. an INS's)
  double age_s = -1.0;  // < 0: empty field
  int station_id = 0;
};
// Altitude field = ellipsoidal height, geoid separation written as 0.0 (so altitude + separation =
// ellipsoidal height, which is what the readers compute).
std::string gga(const CalendarTime& utc, const Geodetic& pos, const GgaFields& f, std::string_view talker = "GN");
// Error statistics: position std north/east/down [m]; the error ellipse is taken axis aligned.
std::string gst(const CalendarTime& utc, double lat_std_m, double lon_std_m, double alt_std_m,
                std::string_view talker = "GN");
std::string zda(const CalendarTime& utc, std::string_view talker = "GN");
// RMC with mode indicator: speed over ground and course from the NED velocity.
std::string rmc(const CalendarTime& utc, const Geodetic& pos, double v_north_mps, double v_east_mps, char mode,
                std::string_view talker = "GN");

// Track made good and ground speed from the NED velocity, with the mode indicator (A, D, E, N).
std::string vtg(double v_north_mps, double v_east_mps, char mode, std::string_view talker = "GN");
// True heading [rad] (an INS's yaw or a dual antenna's baseline).
std::string hdt(double heading_rad, std::string_view talker = "GN");

}  // namespace ldv::nmea
