#include "common/formats/nmea_solution.hpp"
#include "toolbox/convert/track_formats.hpp"

namespace ldv::convert {

void write_nmea(const SolutionTrack& track, std::ostream& out, const NmeaOptions& options) {
  require_dates(track, "NMEA");
  for (const TrackPoint& p : track.points) {
    nmea::SolutionEpoch e;
    e.gps = p.gps;
    e.pos = p.pos;
    e.vel_n_mps = p.vel_n_mps;
    e.heading_rad = p.rpy_rad.z();
    e.pos_std_ned_m = p.pos_std_ned_m;
    e.source = p.aiding == Aiding::kInsOnly ? nmea::SolutionEpoch::Source::kInsOnly
               : p.aiding == Aiding::kGnss  ? nmea::SolutionEpoch::Source::kGnssAided
                                            : nmea::SolutionEpoch::Source::kUnknown;
    out << nmea::solution_sentences(e, options.talker);
  }
}

}  // namespace ldv::convert
