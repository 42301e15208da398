#include <cmath>

#include "common/formats/nmea_writer.hpp"
#include "common/io/input_error.hpp"
#include "common/time/utc_text.hpp"
#include "toolbox/convert/track_formats.hpp"

namespace ldv::convert {
namespace {

int gga_quality(const TrackPoint& p) {
  if (p.aiding == Aiding::kInsOnly) return 6;
  if (!p.pos_std_ned_m.allFinite()) return p.aiding == Aiding::kGnss ? 2 : 1;
  const double horizontal_m = std::hypot(p.pos_std_ned_m.x(), p.pos_std_ned_m.y());
  return horizontal_m <= 0.05 ? 4 : horizontal_m <= 0.5 ? 5 : 2;
}

}  // namespace

void write_nmea(const SolutionTrack& track, std::ostream& out, const NmeaOptions& options) {
  if (!track.has_date)
    throw InputError(track.nav_path, 1, "NMEA needs calendar dates: the solution has no GPS week (give --week)");
  for (const TrackPoint& p : track.points) {
    // NMEA's centiseconds, rounded from GPS time (the millisecond UTC of the track would print 59.996 as 60.00).
    const CalendarTime utc = nmea::utc_from_gps(p.gps, gps_minus_utc_s(p.utc));
    nmea::GgaFields gga;
    gga.quality = gga_quality(p);
    gga.hdop = -1.0;  // an INS solution has none
    const char mode = p.aiding == Aiding::kInsOnly ? 'E' : p.aiding == Aiding::kGnss ? 'D' : 'A';
    out << nmea::gga(utc, p.pos, gga, options.talker);
    out << nmea::rmc(utc, p.pos, p.vel_n_mps.x(), p.vel_n_mps.y(), mode, options.talker);
    if (p.pos_std_ned_m.allFinite())
      out << nmea::gst(utc, p.pos_std_ned_m.x(), p.pos_std_ned_m.y(), p.pos_std_ned_m.z(), options.talker);
    out << nmea::vtg(p.vel_n_mps.x(), p.vel_n_mps.y(), mode, options.talker);
    out << nmea::hdt(p.rpy_rad.z(), options.talker);
  }
}

}  // namespace ldv::convert
