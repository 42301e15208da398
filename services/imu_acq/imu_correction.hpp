#pragma once
// The hook where raw device increments become body-frame (front-right-down) increments: the
// mounting rotation (device axes -> body axes) now, and the calibration toolbox's corrections
// (bias, scale factor, non-orthogonality from `ldv calib`) once a calibration file is loaded.
// Identity by default, so the published increments are the device's.
#include "common/math/rotation.hpp"

namespace ldv::imu {

struct ImuCorrection {
  Mat3 C_device_to_body = Mat3::Identity();
  // Calibration: omega_corrected = gyro_matrix * (omega - gyro_bias), same for the accelerometers.
  Mat3 gyro_matrix = Mat3::Identity();
  Vec3 gyro_bias_radps = Vec3::Zero();
  Mat3 accel_matrix = Mat3::Identity();
  Vec3 accel_bias_mps2 = Vec3::Zero();

  void apply(Vec3& dtheta_rad, Vec3& dvel_mps, double dt_s) const {
    dtheta_rad = C_device_to_body * (gyro_matrix * (dtheta_rad - gyro_bias_radps * dt_s));
    dvel_mps = C_device_to_body * (accel_matrix * (dvel_mps - accel_bias_mps2 * dt_s));
  }
};

}  // namespace ldv::imu
