#pragma once
// The velocity of the odometer point (rear-axle centre; l = odometer lever arm, body axes) in vehicle axes,
// what the land-vehicle aids measure: v_v = C_b_v (C_n_b v_n + w_nb_b x l). The non-holonomic constraint
// says its lateral and vertical components are zero; an odometer measures its forward component.
//
// Jacobian w.r.t. the error state (delta = estimate - truth; C_b_n_hat = (I - [phi x]) C_b_n):
//   d v_v / d delta_v = C_b_v C_n_b,   d v_v / d phi = -C_b_v C_n_b [v_n x],
// Gyro errors (d v_v / dx = -C_b_v [l x] J_gyro) are added per measurement by add_gyro_error_columns
// (gyro_coupling.hpp), the mounting and lever-arm effects add their own columns (vehicle_mounting.cpp,
// odometer_lever_arm.cpp).
#include <Eigen/Core>

#include "estimator/ins/nav_state.hpp"
#include "estimator/update/measurement.hpp"

namespace ldv::est {

struct VehicleVelocity {
  Vec3 v_v_mps = Vec3::Zero();  // odometer point, vehicle axes (x forward, y right, z down)
  Eigen::MatrixXd H;            // 3 x n, navigation columns
};

VehicleVelocity vehicle_velocity(const NavState& nav, const LinearizationPoint& lp, const StateLayout& layout);

// The odometer point's velocity in body axes (lp's attitude, velocity, body rate and lever arm).
inline Vec3 odometer_point_velocity_b(const LinearizationPoint& lp) {
  return lp.C_b_n.transpose() * lp.v_n_mps + lp.omega_nb_b_rad_s.cross(lp.odometer_lever_arm_b_m);
}

}  // namespace ldv::est
