#include <cstdio>

#include "toolbox/convert/track_formats.hpp"

namespace ldv::convert {

std::string iso_utc(const CalendarTime& utc) {
  char b[40];
  std::snprintf(b, sizeof b, "%04d-%02d-%02dT%02d:%02d:%06.3fZ", utc.year, utc.month, utc.day, utc.hour, utc.minute,
                utc.second);
  return b;
}

void write_gpx(const SolutionTrack& track, std::ostream& out) {
  require_dates(track, "GPX");
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         "<gpx version=\"1.1\" creator=\"ldvnav ldv convert\" xmlns=\"http://www.topografix.com/GPX/1/1\" "
         "xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
         "xsi:schemaLocation=\"http://www.topografix.com/GPX/1/1 "
         "http://www.topografix.com/GPX/1/1/gpx.xsd\">\n";
  out << "  <metadata>\n    <desc>ldv nav solution " << track.nav_path
      << "; ele is the ellipsoidal height (WGS84) [m]; fix dgps where GNSS aided it, none where the INS ran alone"
         "</desc>\n";
  if (!track.points.empty()) out << "    <time>" << iso_utc(track.points.front().utc) << "</time>\n";
  out << "  </metadata>\n  <trk>\n    <name>" << track.nav_path << "</name>\n    <trkseg>\n";
  char b[256];
  for (const TrackPoint& p : track.points) {
    std::snprintf(b, sizeof b, "      <trkpt lat=\"%.9f\" lon=\"%.9f\"><ele>%.4f</ele><time>%s</time>",
                  p.pos.lat_rad * kRadToDeg, p.pos.lon_rad * kRadToDeg, p.pos.h_m, iso_utc(p.utc).c_str());
    out << b;
    if (p.aiding == Aiding::kGnss) out << "<fix>dgps</fix>";
    if (p.aiding == Aiding::kInsOnly) out << "<fix>none</fix>";
    out << "</trkpt>\n";
  }
  out << "    </trkseg>\n  </trk>\n</gpx>\n";
}

}  // namespace ldv::convert
