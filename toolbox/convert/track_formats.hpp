#pragma once
// Writers of a solution track (solution_track.hpp) in the formats people's tools read: GPX 1.1 (GIS, mapping apps),
// KML with gx:Track (Google Earth: the track coloured by GNSS-aided / INS-only, a placemark per INS-only span), NMEA
// 0183 (GGA, RMC, GST, VTG, HDT: moving maps, survey software, any device) and CSV with a header naming each column
// and its unit (spreadsheets). Positions with 1e-9 deg (0.1 mm) and heights with 0.1 mm; times with 1 ms (NMEA: its
// centiseconds). Heights are ellipsoidal (WGS84), as the solution's: GPX's ele and KML's absolute altitude are meant
// above the geoid, so each file says so, and GGA states a geoid separation of 0 so that readers get it back.
#include <ostream>
#include <string>

#include "toolbox/convert/solution_track.hpp"

namespace ldv::convert {

// GPX, KML and NMEA carry calendar dates: they refuse a track without a GPS week (InputError on the .nav).
void write_gpx(const SolutionTrack& track, std::ostream& out);
void write_kml(const SolutionTrack& track, std::ostream& out);
void write_csv(const SolutionTrack& track, std::ostream& out);

struct NmeaOptions {
  std::string talker = "GN";
};
// The sentences of common/formats/nmea_solution.hpp per point (GGA quality 6 where the INS ran alone).
void write_nmea(const SolutionTrack& track, std::ostream& out, const NmeaOptions& options);

// "2024-08-27T17:30:01.123Z" (the track's UTC, to the millisecond).
std::string iso_utc(const CalendarTime& utc);

}  // namespace ldv::convert
