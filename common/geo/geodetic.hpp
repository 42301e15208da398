#pragma once
#include <Eigen/Core>

namespace ldv {

// A WGS84 geodetic position. Angles in radians, height above the ellipsoid in metres.
struct Geodetic {
  double lat_rad = 0.0;
  double lon_rad = 0.0;
  double h_m = 0.0;
};

}  // namespace ldv
