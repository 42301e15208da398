#pragma once
// Continuous-time dynamics of the 9 navigation error states (phi-angle form, delta = estimate - truth,
// C_b_n_hat = (I - [phi x]) C_b_n):
//   d(delta_r)/dt = F_rr delta_r + delta_v
//   d(delta_v)/dt = F_vr delta_r + F_vv delta_v + [f_n x] phi + C_b_n delta_f_b + delta_g_n
//   d(phi)/dt     = F_pr delta_r + F_pv delta_v - [w_in x] phi - C_b_n delta_w_ib_b
// Checked against numerical derivatives of the nonlinear model in tests/estimator/test_jacobians.cpp.
#include <Eigen/Core>

#include "estimator/ins/nav_state.hpp"

namespace ldv::est {

using Mat9 = Eigen::Matrix<double, 9, 9>;

// dg_dlat [m/s^2/rad] and dg_dh [m/s^2/m]: normal gravity gradients (GravityCache).
Mat9 nav_error_F(const NavState& s, const Vec3& f_n_mps2, const Vec3& dg_dlat, const Vec3& dg_dh);

}  // namespace ldv::est
