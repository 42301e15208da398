#include "estimator/update/vehicle_velocity.hpp"

namespace ldv::est {

VehicleVelocity vehicle_velocity(const NavState& nav, const LinearizationPoint& lp, const StateLayout& layout) {
  VehicleVelocity out;
  out.v_v_mps = lp.C_b_v * odometer_point_velocity_b(lp);
  out.H = Eigen::MatrixXd::Zero(3, layout.size());
  const Mat3 C_n_v = lp.C_b_v * lp.C_b_n.transpose();
  out.H.middleCols<3>(kVel) = C_n_v;
  out.H.middleCols<3>(kAtt) = -C_n_v * skew(nav.v_n_mps);
  return out;
}

}  // namespace ldv::est
