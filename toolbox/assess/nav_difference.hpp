#pragma once
// One solution minus another at the same instant, in the units of the paper's tables.
#include "toolbox/assess/nav_series.hpp"

namespace ldv::assess {

struct NavDifference {
  Vec3 pos_ned_m = Vec3::Zero();     // position of a relative to b, NED [m]
  Vec3 vel_ned_mps = Vec3::Zero();   // NED [m/s]
  Vec3 rpy_rad = Vec3::Zero();       // roll, pitch, yaw differences, each wrapped to (-pi, pi]
  Vec3 att_phi_n_rad = Vec3::Zero(); // attitude error as a small NED rotation vector (the filter's phi):
                                     // C_b_n(a) = (I - [phi x]) C_b_n(b); compared with the filter's std
};

NavDifference nav_difference(const NavSample& a, const NavSample& b);

}  // namespace ldv::assess
