#include "toolbox/assess/nav_difference.hpp"

#include "common/geo/earth_model.hpp"

namespace ldv::assess {

NavDifference nav_difference(const NavSample& a, const NavSample& b) {
  NavDifference d;
  d.pos_ned_m = earth::ned_between(b.pos, a.pos);
  d.vel_ned_mps = a.vel_n_mps - b.vel_n_mps;
  const Vec3 rpy_a = euler_from_C_b_n(a.q_b_n.toRotationMatrix());
  const Vec3 rpy_b = euler_from_C_b_n(b.q_b_n.toRotationMatrix());
  for (int i = 0; i < 3; ++i) d.rpy_rad(i) = wrap_pi(rpy_a(i) - rpy_b(i));
  // C_a = (I - [phi x]) C_b  =>  C_b C_a^T = I + [phi x] to first order.
  d.att_phi_n_rad = rotvec_from_quat(b.q_b_n * a.q_b_n.conjugate());
  return d;
}

}  // namespace ldv::assess
