#pragma once
#include "common/geo/geodetic.hpp"
#include "common/math/rotation.hpp"

namespace ldv::sim {

// The true state at one instant. t_s is GPS seconds of week; rpy yaw wrapped to (-pi, pi];
// omega_ib_b and f_b are what a perfect IMU senses at that instant (body front-right-down).
struct TruthSample {
  double t_s = 0.0;
  Geodetic pos;
  Vec3 vel_n_mps = Vec3::Zero();
  Vec3 rpy_rad = Vec3::Zero();
  Vec3 omega_ib_b_rad_s = Vec3::Zero();
  Vec3 f_b_mps2 = Vec3::Zero();
};

}  // namespace ldv::sim
