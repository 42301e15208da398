#pragma once
// The navigation (nominal) state the strapdown INS integrates: position on WGS84, NED velocity,
// body-to-NED attitude. Time is the IMU time scale (GPS seconds of week).
#include "common/geo/geodetic.hpp"
#include "common/math/rotation.hpp"

namespace ldv::est {

struct NavState {
  double t_s = 0.0;
  Geodetic pos;
  Vec3 v_n_mps = Vec3::Zero();
  Quat q_b_n = Quat::Identity();  // rotates body vectors into NED: v_n = q_b_n * v_b

  Mat3 C_b_n() const { return q_b_n.toRotationMatrix(); }
  Vec3 rpy_rad() const { return euler_from_C_b_n(C_b_n()); }
};

// 1-sigma uncertainty of an initial state (NED position [m], velocity [m/s], attitude roll pitch yaw [rad]).
struct NavStd {
  Vec3 pos_ned_m = Vec3::Constant(1.0);
  Vec3 vel_n_mps = Vec3::Constant(0.1);
  Vec3 att_rad = Vec3::Constant(kDegToRad);
};

}  // namespace ldv::est
