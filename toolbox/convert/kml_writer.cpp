#include <cmath>
#include <cstdio>

#include "toolbox/convert/track_formats.hpp"

namespace ldv::convert {
namespace {

const char* label_of(Aiding a) {
  switch (a) {
    case Aiding::kGnss:
      return "GNSS aided";
    case Aiding::kInsOnly:
      return "INS only";
    default:
      return "solution";
  }
}

void coord(std::ostream& out, const TrackPoint& p) {
  char b[160];
  std::snprintf(b, sizeof b, "%.9f %.9f %.4f", p.pos.lon_rad * kRadToDeg, p.pos.lat_rad * kRadToDeg, p.pos.h_m);
  out << b;
}

}  // namespace

void write_kml(const SolutionTrack& track, std::ostream& out) {
  require_dates(track, "KML");
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         "<kml xmlns=\"http://www.opengis.net/kml/2.2\" xmlns:gx=\"http://www.google.com/kml/ext/2.2\">\n"
         "<Document>\n  <name>"
      << track.nav_path
      << "</name>\n  <description>ldv nav solution; altitudes are ellipsoidal heights (WGS84) [m]; green where GNSS "
         "aided it, red where the INS ran alone</description>\n";
  // KML colours are aabbggrr.
  for (const auto& [id, colour] :
       {std::pair{"gnss", "ff00c000"}, std::pair{"ins_only", "ff0000ff"}, std::pair{"unknown", "ffff8000"}})
    out << "  <Style id=\"" << id << "\"><LineStyle><color>" << colour
        << "</color><width>3</width></LineStyle><IconStyle><color>" << colour << "</color></IconStyle></Style>\n";
  out << "  <Folder>\n    <name>Track</name>\n";
  // One gx:Track per run of one aiding; each after the first starts at the point before it, so the line is unbroken.
  const auto& pts = track.points;
  for (size_t begin = 0; begin < pts.size();) {
    size_t end = begin + 1;
    while (end < pts.size() && pts[end].aiding == pts[begin].aiding) ++end;
    const size_t from = begin > 0 ? begin - 1 : begin;
    out << "    <Placemark>\n      <name>" << label_of(pts[begin].aiding) << " " << iso_utc(pts[begin].utc)
        << "</name>\n"
        << "      <styleUrl>#" << aiding_name(pts[begin].aiding) << "</styleUrl>\n      <gx:Track>\n"
        << "        <altitudeMode>absolute</altitudeMode>\n";
    for (size_t i = from; i < end; ++i) out << "        <when>" << iso_utc(pts[i].utc) << "</when>\n";
    for (size_t i = from; i < end; ++i) {
      out << "        <gx:coord>";
      coord(out, pts[i]);
      out << "</gx:coord>\n";
    }
    out << "      </gx:Track>\n    </Placemark>\n";
    begin = end;
  }
  out << "  </Folder>\n";
  const std::vector<InsOnlySpan> spans = ins_only_spans(track);
  if (!spans.empty()) {
    out << "  <Folder>\n    <name>INS-only spans</name>\n";
    for (const InsOnlySpan& s : spans) {
      const TrackPoint &a = pts[s.first], &b = pts[s.last];
      char name[96];
      std::snprintf(name, sizeof name, "INS only %.1f s", b.gps.total_seconds() - a.gps.total_seconds());
      out << "    <Placemark>\n      <name>" << name << "</name>\n      <description>from " << iso_utc(a.utc) << " to "
          << iso_utc(b.utc);
      if (b.pos_std_ned_m.allFinite()) {
        char d[96];
        std::snprintf(d, sizeof d, "; horizontal 1-sigma at its end %.3f m",
                      std::hypot(b.pos_std_ned_m.x(), b.pos_std_ned_m.y()));
        out << d;
      }
      out << "</description>\n      <styleUrl>#ins_only</styleUrl>\n      <TimeSpan><begin>" << iso_utc(a.utc)
          << "</begin><end>" << iso_utc(b.utc)
          << "</end></TimeSpan>\n      <Point><altitudeMode>absolute</altitudeMode>"
          << "<coordinates>";
      char c[160];
      std::snprintf(c, sizeof c, "%.9f,%.9f,%.4f", a.pos.lon_rad * kRadToDeg, a.pos.lat_rad * kRadToDeg, a.pos.h_m);
      out << c << "</coordinates></Point>\n    </Placemark>\n";
    }
    out << "  </Folder>\n";
  }
  out << "</Document>\n</kml>\n";
}

}  // namespace ldv::convert
