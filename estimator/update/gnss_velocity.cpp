#include "estimator/update/gnss_velocity.hpp"

#include "common/formats/gnss_solution_checks.hpp"
#include "estimator/update/gyro_coupling.hpp"

namespace ldv::est {

Vec3 antenna_velocity_n(const NavState& s, const LinearizationPoint& lp) {
  const Vec3 lever_n = lp.C_b_n * lp.lever_arm_b_m;
  return s.v_n_mps + lp.C_b_n * lp.omega_ib_b_rad_s.cross(lp.lever_arm_b_m) - lp.omega_in_n_rad_s.cross(lever_n);
}

Measurement gnss_velocity_measurement(const NavState& s, const LinearizationPoint& lp, const StateLayout& layout,
                                      const GnssFix& fix) {
  Measurement m(sensors::kGnssVelocity, 3, layout.size());
  m.gnss = true;
  m.step_block = kVel;
  m.y = antenna_velocity_n(s, lp) - fix.vel_n_mps;
  m.H.middleCols<3>(kVel).setIdentity();
  const Vec3 lever_n = lp.C_b_n * lp.lever_arm_b_m;
  const Vec3 rot_n = lp.C_b_n * lp.omega_ib_b_rad_s.cross(lp.lever_arm_b_m);
  m.H.middleCols<3>(kAtt) = skew(rot_n) - skew(lp.omega_in_n_rad_s) * skew(lever_n);
  add_gyro_error_columns(layout, lp, m);  // gyro errors move the antenna (gyro_coupling.hpp)
  add_effect_columns(layout, lp, m);
  m.R = Mat3(fix.vel_std_n_mps.cwiseAbs().cwiseMax(gnss::kMinCredibleGnssVelocityStd_mps).cwiseAbs2().asDiagonal());
  return m;
}

}  // namespace ldv::est
