#pragma once
// An `ldv nav` solution as a track for other people's tools (`ldv convert`): per point its GPS and UTC time,
// position, velocity, attitude, the position 1-sigma where the run's FILE_std.txt gives it, and whether GNSS aided
// the solution or the INS ran alone (from FILE_innovations.txt: a GNSS measurement accepted within the last
// kAidedWithin_s, the filter's own outage rule). Optionally resampled on a regular grid of GPS time (multiples of
// 1/rate), each point interpolated between the two solution epochs around it: NMEA's centiseconds and a
// receiver-like rate need grid times, and a 200 Hz solution moves less than a millimetre from a straight line
// between samples.
#include <string>
#include <vector>

#include "common/formats/nav_types.hpp"
#include "common/time/gps_time.hpp"

namespace ldv::convert {

enum class Aiding { kUnknown, kGnss, kInsOnly };
const char* aiding_name(Aiding a);  // "unknown", "gnss", "ins_only"

inline constexpr double kAidedWithin_s = 2.0;

struct TrackPoint {
  GpsTime gps;
  CalendarTime utc{};  // valid when SolutionTrack::has_date
  Geodetic pos;
  Vec3 vel_n_mps = Vec3::Zero();
  Vec3 rpy_rad = Vec3::Zero();
  Vec3 pos_std_ned_m = Vec3::Constant(NAN);  // NaN: no _std.txt
  Aiding aiding = Aiding::kUnknown;
};

struct SolutionTrack {
  std::vector<TrackPoint> points;
  std::string nav_path, std_path, innovations_path;  // the files read ("" where none was beside the .nav)
  bool has_date = false;  // the .nav's rows carry a GPS week (KF-GINS files may hold seconds of week only)
};

struct TrackOptions {
  double rate_hz = 0.0;  // 0: every solution epoch
  int week = -1;         // >= 0: the GPS week of a .nav that has none (week 0 rows)
};

// A format that carries calendar dates (GPX, KML, NMEA) refuses a track without a GPS week: InputError on the .nav.
void require_dates(const SolutionTrack& track, const char* format);

// Reads NAV and, beside it, NAV's _std.txt and _innovations.txt when present; InputError names the file and line.
SolutionTrack load_solution_track(const std::string& nav_path, const TrackOptions& options);

// The spans where the INS ran alone: [first, last] point indices.
struct InsOnlySpan {
  size_t first = 0, last = 0;
};
std::vector<InsOnlySpan> ins_only_spans(const SolutionTrack& track);

}  // namespace ldv::convert
