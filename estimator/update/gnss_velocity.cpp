#include "estimator/update/gnss_velocity.hpp"

namespace ldv::est {

Vec3 antenna_velocity_n(const NavState& s, const LinearizationPoint& lp) {
  const Vec3 lever_n = lp.C_b_n * lp.lever_arm_b_m;
  return s.v_n_mps + lp.C_b_n * lp.omega_ib_b_rad_s.cross(lp.lever_arm_b_m) - lp.omega_in_n_rad_s.cross(lever_n);
}

Measurement gnss_velocity_measurement(const NavState& s, const LinearizationPoint& lp, const StateLayout& layout,
                                      const GnssFix& fix) {
  Measurement m;
  m.kind = MeasurementKind::kGnssVelocity;
  m.y = antenna_velocity_n(s, lp) - fix.vel_n_mps;
  m.H = Mat3X::Zero(3, layout.size());
  m.H.middleCols<3>(kVel).setIdentity();
  const Vec3 lever_n = lp.C_b_n * lp.lever_arm_b_m;
  const Vec3 rot_n = lp.C_b_n * lp.omega_ib_b_rad_s.cross(lp.lever_arm_b_m);
  m.H.middleCols<3>(kAtt) = skew(rot_n) - skew(lp.omega_in_n_rad_s) * skew(lever_n);
  // Gyro errors move the antenna: C (delta_w x l) = -C [l x] delta_w.
  const Mat3 dv_dw = -lp.C_b_n * skew(lp.lever_arm_b_m);
  Mat3X J_gyro, J_accel;
  for (const auto& b : layout.blocks()) {
    if (!b.effect->drives_gyro()) continue;
    J_gyro = Mat3X::Zero(3, b.dim);
    J_accel = Mat3X::Zero(3, b.dim);
    b.effect->imu_jacobians(lp, J_gyro, J_accel);
    m.H.middleCols(b.offset, b.dim) += dv_dw * J_gyro;
  }
  add_effect_columns(layout, lp, m);
  m.R = fix.vel_std_n_mps.cwiseAbs2().asDiagonal();
  return m;
}

}  // namespace ldv::est
