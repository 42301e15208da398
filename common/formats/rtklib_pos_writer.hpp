#pragma once
// RTKLIB solution file (.pos) writer in the layout rtkpost/rtkrcv print: '%' header lines, GPST
// calendar time "2024/06/24 08:20:00.000", lat lon [deg] height [m, ellipsoidal], Q, ns,
// sdn sde sdu sdne sdeu sdun [m], age [s], ratio, and optionally vn ve vu [m/s] with their sigmas.
#include <string>
#include <vector>

#include "common/formats/nav_types.hpp"

namespace ldv {

struct RtklibPosOptions {
  int gps_week = 0;                      // GnssFix::t_s is seconds of this week
  std::string program = "ldvnav";
  std::vector<std::string> comments;     // extra "% ..." header lines
  bool with_velocity = false;
};

void write_rtklib_pos(const std::string& path, const std::vector<GnssFix>& fixes, const RtklibPosOptions& opt);

}  // namespace ldv
