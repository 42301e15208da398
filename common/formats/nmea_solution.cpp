#include "common/formats/nmea_solution.hpp"

#include <cmath>

#include "common/formats/nmea_writer.hpp"
#include "common/time/utc_text.hpp"

namespace ldv::nmea {

int gga_quality(const SolutionEpoch& e) {
  using Source = SolutionEpoch::Source;
  if (e.source == Source::kInvalid) return 0;
  if (e.source == Source::kInsOnly) return 6;
  if (!e.pos_std_ned_m.allFinite()) return e.source == Source::kGnssAided ? 2 : 1;
  const double horizontal_m = std::hypot(e.pos_std_ned_m.x(), e.pos_std_ned_m.y());
  return horizontal_m <= 0.05 ? 4 : horizontal_m <= 0.5 ? 5 : 2;
}

std::string solution_sentences(const SolutionEpoch& e, std::string_view talker) {
  using Source = SolutionEpoch::Source;
  // NMEA's centiseconds, rounded from GPS time; GPS - UTC at that time
  const CalendarTime utc = utc_from_gps(e.gps, gps_minus_utc_s(calendar_from_gps(e.gps)));
  GgaFields fields;
  fields.quality = gga_quality(e);
  fields.hdop = -1.0;  // an INS solution has none
  // RMC/VTG mode: E estimated (dead reckoning), D differential (GNSS-aided), N not valid, A otherwise
  const char mode = e.source == Source::kInsOnly     ? 'E'
                    : e.source == Source::kGnssAided ? 'D'
                    : e.source == Source::kInvalid   ? 'N'
                                                     : 'A';
  std::string out = gga(utc, e.pos, fields, talker);
  out += rmc(utc, e.pos, e.vel_n_mps.x(), e.vel_n_mps.y(), mode, talker);
  if (e.pos_std_ned_m.allFinite())
    out += gst(utc, e.pos_std_ned_m.x(), e.pos_std_ned_m.y(), e.pos_std_ned_m.z(), talker);
  out += vtg(e.vel_n_mps.x(), e.vel_n_mps.y(), mode, talker);
  out += hdt(e.heading_rad, talker);
  return out;
}

}  // namespace ldv::nmea
