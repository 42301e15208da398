#pragma once
// Strapdown mechanisation in the local-level NED frame on WGS84, from IMU increments
// (Savage's two-sample coning and sculling; Earth and transport rate and gravity evaluated at the
// extrapolated mid-interval position and velocity, as in Shin 2005 / KF-GINS).
#include "common/formats/nav_types.hpp"
#include "estimator/ins/gravity_cache.hpp"
#include "estimator/ins/nav_state.hpp"

namespace ldv::est {

// What one step produced, for the error-state transition matrix.
struct MechanizationStep {
  double dt_s = 0.0;
  Vec3 dv_sf_n_mps = Vec3::Zero();     // specific-force velocity increment resolved in n
  Vec3 omega_ib_b_rad_s = Vec3::Zero();  // mean angular rate over the step
  Vec3 f_b_mps2 = Vec3::Zero();          // mean specific force over the step
  Vec3 a_n_mps2 = Vec3::Zero();          // mean acceleration (dv_n/dt) over the step
  // The step went over a pole: the state is now on the far meridian (longitude + 180 deg) and its n frame is the
  // old one turned 180 deg about down (north and east negated), so an error state in n must turn with it.
  bool crossed_pole = false;
};

class Mechanization {
 public:
  // Starts a new integration at `s` (forgets the previous increment and velocity change).
  void reset(const NavState& s);
  // Advances `s` over one increment ending at inc.t_s; increments must follow each other.
  const MechanizationStep& step(NavState& s, const ImuIncrement& inc);
  // Estimated gravity anomaly (true minus normal gravity, NED [m/s^2]) added to normal gravity.
  void set_gravity_anomaly_n(const Vec3& dg_n) { gravity_anomaly_n_ = dg_n; }
  GravityCache& gravity() { return gravity_; }
  const MechanizationStep& last() const { return last_; }

 private:
  bool have_prev_ = false;
  ImuIncrement prev_;
  Vec3 dv_n_prev_ = Vec3::Zero();  // v(k-1) - v(k-2), for the mid-interval extrapolation
  double dt_prev_ = 0.0;
  Vec3 gravity_anomaly_n_ = Vec3::Zero();
  GravityCache gravity_;
  MechanizationStep last_;
};

}  // namespace ldv::est
