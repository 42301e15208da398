#pragma once
// Field-level decoding of the NMEA 0183 sentences a GNSS receiver link needs: GGA (fix), GST
// (error statistics), RMC (minimum data, date), VTG (course and speed), ZDA (date and time).
// Input is the checksum-verified text between '$' and '*' as NmeaFramer delivers it. Angles come
// out in radians, speeds in m/s, heights in metres; times are UTC as the receiver prints them.
#include <optional>
#include <string_view>

namespace ldv::gnss {

// "GPGGA,..." -> talker "GP", type "GGA". Proprietary sentences ("PUBX,...") have talker "P".
struct NmeaAddress {
  std::string_view talker;
  std::string_view type;
};
std::optional<NmeaAddress> nmea_address(std::string_view sentence);

struct UtcDate {
  int year = 0, month = 0, day = 0;
};

struct NmeaGga {
  double utc_seconds_of_day = 0.0;
  bool has_position = false;  // false while the receiver has no fix (empty fields)
  double lat_rad = 0.0, lon_rad = 0.0;
  double altitude_msl_m = 0.0;      // above mean sea level (geoid)
  double geoid_separation_m = 0.0;  // geoid above ellipsoid
  int quality_code = 0;             // 0 invalid, 1 GPS, 2 DGPS, 4 RTK fixed, 5 RTK float, 6 estimated ...
  int num_sats = 0;
  double hdop = 0.0;
  std::optional<double> correction_age_s;
  double ellipsoid_height_m() const { return altitude_msl_m + geoid_separation_m; }
};

struct NmeaGst {
  double utc_seconds_of_day = 0.0;
  double range_rms_m = 0.0;
  double semi_major_std_m = 0.0, semi_minor_std_m = 0.0;
  double semi_major_orientation_rad = 0.0;  // from true north, clockwise
  double lat_std_m = 0.0, lon_std_m = 0.0, alt_std_m = 0.0;
};

struct NmeaRmc {
  double utc_seconds_of_day = 0.0;
  bool valid = false;  // status 'A'
  bool has_position = false;
  double lat_rad = 0.0, lon_rad = 0.0;
  double speed_mps = 0.0;
  std::optional<double> course_true_rad;
  UtcDate date;
  char mode = 'N';  // NMEA 2.3 mode indicator: A autonomous, D differential, R RTK fixed, F float, E estimated, N none
};

struct NmeaVtg {
  std::optional<double> course_true_rad;
  double speed_mps = 0.0;
  char mode = 'N';
};

struct NmeaZda {
  double utc_seconds_of_day = 0.0;
  UtcDate date;
};

// Each returns nullopt when the sentence is not of that type or a field is malformed.
std::optional<NmeaGga> parse_gga(std::string_view sentence);
std::optional<NmeaGst> parse_gst(std::string_view sentence);
std::optional<NmeaRmc> parse_rmc(std::string_view sentence);
std::optional<NmeaVtg> parse_vtg(std::string_view sentence);
std::optional<NmeaZda> parse_zda(std::string_view sentence);

}  // namespace ldv::gnss
