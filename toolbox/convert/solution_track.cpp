#include "toolbox/convert/solution_track.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "common/formats/kfgins_files.hpp"
#include "common/io/input_error.hpp"
#include "common/time/utc_text.hpp"
#include "toolbox/assess/nav_side_files.hpp"

namespace ldv::convert {
namespace {

// Epochs further apart than this are a gap in the solution: no point is interpolated across it.
constexpr double kMaxInterpolationGap_s = 1.0;

double wrap_pi(double a) { return std::remainder(a, 2.0 * M_PI); }

// The UTC calendar time of a GPS time, rounded to the millisecond first (so 59.9996 s never prints as 60.000).
CalendarTime utc_of(const GpsTime& t) {
  const int leap = gps_minus_utc_s(calendar_from_gps(t));
  const double utc_total_s = std::round((t.total_seconds() - leap) * 1000.0) / 1000.0;
  return calendar_from_gps(GpsTime::from_total_seconds(utc_total_s));
}

// A point between solution epochs a and b at weight w in [0, 1] (continuous seconds t_s).
TrackPoint interpolate(const NavRecord& a, const NavRecord& b, double w) {
  TrackPoint p;
  p.pos.lat_rad = a.pos.lat_rad + w * (b.pos.lat_rad - a.pos.lat_rad);
  p.pos.lon_rad = a.pos.lon_rad + w * wrap_pi(b.pos.lon_rad - a.pos.lon_rad);
  p.pos.h_m = a.pos.h_m + w * (b.pos.h_m - a.pos.h_m);
  p.vel_n_mps = a.vel_n_mps + w * (b.vel_n_mps - a.vel_n_mps);
  for (int i = 0; i < 3; ++i) p.rpy_rad(i) = wrap_pi(a.rpy_rad(i) + w * wrap_pi(b.rpy_rad(i) - a.rpy_rad(i)));
  return p;
}

TrackPoint point_of(const NavRecord& r) { return interpolate(r, r, 0.0); }

}  // namespace

const char* aiding_name(Aiding a) {
  switch (a) {
    case Aiding::kGnss:
      return "gnss";
    case Aiding::kInsOnly:
      return "ins_only";
    default:
      return "unknown";
  }
}

void require_dates(const SolutionTrack& track, const char* format) {
  if (!track.has_date)
    throw InputError(track.nav_path, 1,
                     std::string(format) + " needs calendar dates: the solution has no GPS week (give --week)");
}

SolutionTrack load_solution_track(const std::string& nav_path, const TrackOptions& options) {
  SolutionTrack track;
  track.nav_path = nav_path;
  std::vector<NavRecord> nav = read_nav(nav_path);
  if (nav.empty()) throw InputError(nav_path, 0, "no solution epoch in the file");
  if (options.week >= 0)
    for (NavRecord& r : nav)
      if (r.week == 0) r.week = options.week;
  track.has_date = nav.front().week > 0;
  ContinuousGpsTime clock;
  std::vector<double> t_s(nav.size());
  for (size_t i = 0; i < nav.size(); ++i) t_s[i] = clock.seconds(nav[i].week, nav[i].sow_s);

  std::vector<assess::StdRow> stds;
  std::vector<double> gnss_accepted_s;
  std::error_code ec;
  if (const std::string p = assess::std_path_for(nav_path); p != nav_path && std::filesystem::is_regular_file(p, ec)) {
    stds = assess::read_std_file(p);
    track.std_path = p;
  }
  if (const std::string p = assess::innovations_path_for(nav_path);
      p != nav_path && std::filesystem::is_regular_file(p, ec)) {
    for (const assess::InnovationRow& r : assess::read_innovations_file(p))
      if (r.accepted && r.kind.rfind("gnss_", 0) == 0) gnss_accepted_s.push_back(r.t_s);
    std::sort(gnss_accepted_s.begin(), gnss_accepted_s.end());
    track.innovations_path = p;
  }

  const auto finish = [&](TrackPoint& p, double t) {
    p.gps = clock.week_time(t);
    if (track.has_date) p.utc = utc_of(p.gps);
    // The std row at or before t (the _std.txt may be written at a lower rate than the .nav).
    const auto s =
        std::upper_bound(stds.begin(), stds.end(), t, [](double x, const assess::StdRow& r) { return x < r.t_s; });
    if (s != stds.begin()) p.pos_std_ned_m = std::prev(s)->pos_ned_m;
    if (!track.innovations_path.empty()) {
      const auto g = std::upper_bound(gnss_accepted_s.begin(), gnss_accepted_s.end(), t + 1e-6);
      p.aiding = g != gnss_accepted_s.begin() && t - *std::prev(g) <= kAidedWithin_s ? Aiding::kGnss : Aiding::kInsOnly;
    }
    track.points.push_back(p);
  };
  if (!(options.rate_hz > 0.0)) {
    for (size_t i = 0; i < nav.size(); ++i) {
      TrackPoint p = point_of(nav[i]);
      finish(p, t_s[i]);
    }
    return track;
  }
  const double step_s = 1.0 / options.rate_hz;
  size_t i = 0;
  for (double k = std::ceil(t_s.front() / step_s - 1e-9);; k += 1.0) {
    const double t = k * step_s;
    if (t > t_s.back() + 1e-9) break;
    while (i + 1 < nav.size() && t_s[i + 1] <= t) ++i;
    if (i + 1 == nav.size()) {
      if (std::abs(t - t_s[i]) < 1e-6) {
        TrackPoint p = point_of(nav[i]);
        finish(p, t);
      }
      break;
    }
    const double span = t_s[i + 1] - t_s[i];
    if (!(span > 0.0) || span > kMaxInterpolationGap_s) continue;
    TrackPoint p = interpolate(nav[i], nav[i + 1], (t - t_s[i]) / span);
    finish(p, t);
  }
  return track;
}

std::vector<InsOnlySpan> ins_only_spans(const SolutionTrack& track) {
  std::vector<InsOnlySpan> spans;
  for (size_t i = 0; i < track.points.size(); ++i) {
    if (track.points[i].aiding != Aiding::kInsOnly) continue;
    if (!spans.empty() && spans.back().last + 1 == i)
      spans.back().last = i;
    else
      spans.push_back({i, i});
  }
  return spans;
}

}  // namespace ldv::convert
