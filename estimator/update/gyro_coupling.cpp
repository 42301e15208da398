#include "estimator/update/gyro_coupling.hpp"

#include "common/math/rotation.hpp"

namespace ldv::est {

Eigen::MatrixXd gyro_error_coupling(SensorName sensor, const LinearizationPoint& lp) {
  if (sensor == sensors::kGnssVelocity) return -lp.C_b_n * skew(lp.lever_arm_b_m);
  if (sensor == sensors::kZeroAngularRate) return Mat3::Identity();
  const Mat3 G_v = -lp.C_b_v * skew(lp.odometer_lever_arm_b_m);
  if (sensor == sensors::kNonHolonomic) return G_v.bottomRows<2>();
  if (sensor == sensors::kOdometer) return (1.0 + lp.odometer_scale) * G_v.topRows<1>();
  return Eigen::MatrixXd(0, 3);
}

void add_gyro_error_columns(const StateLayout& layout, const LinearizationPoint& lp, Measurement& m) {
  const Eigen::MatrixXd G = gyro_error_coupling(m.sensor, lp);
  if (G.rows() == 0) return;
  for (const auto& b : layout.blocks()) {
    if (!b.effect->drives_gyro()) continue;
    Mat3X J_gyro = Mat3X::Zero(3, b.dim), J_accel = Mat3X::Zero(3, b.dim);
    b.effect->imu_jacobians(lp, J_gyro, J_accel);
    m.H.middleCols(b.offset, b.dim) += G * J_gyro;
  }
}

}  // namespace ldv::est
