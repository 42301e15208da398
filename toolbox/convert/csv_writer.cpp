#include <cmath>
#include <cstdio>

#include "toolbox/convert/track_formats.hpp"

namespace ldv::convert {

void write_csv(const SolutionTrack& track, std::ostream& out) {
  out << "gps_week,gps_sow_s,utc,lat_deg,lon_deg,height_ellipsoid_m,vel_north_mps,vel_east_mps,vel_down_mps,"
         "roll_deg,pitch_deg,yaw_deg,std_north_m,std_east_m,std_down_m,aiding\n";
  char b[512];
  for (const TrackPoint& p : track.points) {
    const std::string utc = track.has_date ? iso_utc(p.utc) : std::string();
    // An unknown std is an empty field, not a zero.
    char stds[96] = ",,";
    if (p.pos_std_ned_m.allFinite())
      std::snprintf(stds, sizeof stds, "%.4f,%.4f,%.4f", p.pos_std_ned_m.x(), p.pos_std_ned_m.y(), p.pos_std_ned_m.z());
    std::snprintf(b, sizeof b, "%d,%.6f,%s,%.9f,%.9f,%.4f,%.4f,%.4f,%.4f,%.5f,%.5f,%.5f,%s,%s\n", p.gps.week,
                  p.gps.sow_s, utc.c_str(), p.pos.lat_rad * kRadToDeg, p.pos.lon_rad * kRadToDeg, p.pos.h_m,
                  p.vel_n_mps.x(), p.vel_n_mps.y(), p.vel_n_mps.z(), p.rpy_rad.x() * kRadToDeg,
                  p.rpy_rad.y() * kRadToDeg, p.rpy_rad.z() * kRadToDeg, stds, aiding_name(p.aiding));
    out << b;
  }
}

}  // namespace ldv::convert
