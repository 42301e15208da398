#pragma once
// The current estimate of every sensor and GNSS effect, assembled from the effect blocks' nominal
// states (docs/effects.md definitions), and the correction of raw IMU increments it implies:
//   w_meas = M_g w + b_g + diag(k_g) f,   f_meas = M_a f + b_a
//   => w = M_g^-1 (w_meas - b_g - diag(k_g) f),   f = M_a^-1 (f_meas - b_a)
#include "common/formats/nav_types.hpp"

namespace ldv::est {

struct ImuErrorModel {
  Vec3 gyro_bias_rad_s = Vec3::Zero();
  Vec3 accel_bias_mps2 = Vec3::Zero();
  Mat3 gyro_M = Mat3::Identity();   // I + diag(scale) + N(misalignment)
  Mat3 accel_M = Mat3::Identity();
  Vec3 g_sensitivity_rad_per_m = Vec3::Zero();  // rad/s per m/s^2
  Vec3 gravity_anomaly_n_mps2 = Vec3::Zero();
  Vec3 lever_arm_b_m = Vec3::Zero();
  double time_offset_s = 0.0;
  Vec3 gnss_position_bias_n_m = Vec3::Zero();  // NED, added to the predicted GNSS position
  // Land-vehicle aids: the residual rotation of the IMU in the vehicle after the coarse mounting
  // (C_b_v = C_b_v_coarse (I + [mounting x]) to first order), the odometer point and the odometer's scale.
  Vec3 vehicle_mounting_rad = Vec3::Zero();
  Vec3 odometer_lever_arm_b_m = Vec3::Zero();
  double odometer_scale = 0.0;

  void clear_imu_terms() {
    gyro_bias_rad_s.setZero();
    accel_bias_mps2.setZero();
    gyro_M.setIdentity();
    accel_M.setIdentity();
    g_sensitivity_rad_per_m.setZero();
  }

  ImuIncrement correct(const ImuIncrement& raw) const {
    ImuIncrement c = raw;
    c.dvel_b_mps = accel_M.inverse() * (raw.dvel_b_mps - accel_bias_mps2 * raw.dt_s);
    c.dtheta_b_rad = gyro_M.inverse() * (raw.dtheta_b_rad - gyro_bias_rad_s * raw.dt_s -
                                          g_sensitivity_rad_per_m.cwiseProduct(c.dvel_b_mps));
    return c;
  }
};

// N(m) of docs/effects.md: symmetric non-orthogonality matrix.
inline Mat3 misalignment_matrix(const Vec3& m) {
  Mat3 N;
  N << 0.0, m.z(), m.y(), m.z(), 0.0, m.x(), m.y(), m.x(), 0.0;
  return N;
}

}  // namespace ldv::est
