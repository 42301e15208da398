#pragma once
// The hook where raw device increments become body-frame (front-right-down) increments. In the order the
// sensor model asks for (docs/effects.md; common/formats/imu_calibration.hpp: meas = M true + bias, in the
// device's axes, which are the ones `ldv calib static` saw):
//   1. calibration, in the device frame: true_device = M^-1 (meas - bias * dt)
//   2. mounting rotation: body = C_device_to_body * true_device
// Identity and zero by default, so the published increments are the device's.
#include "common/math/rotation.hpp"
#include "common/formats/imu_calibration.hpp"

namespace ldv::imu {

struct ImuCorrection {
  Mat3 C_device_to_body = Mat3::Identity();
  // Calibration: omega_corrected = gyro_matrix * (omega - gyro_bias), same for the accelerometers.
  Mat3 gyro_matrix = Mat3::Identity();
  Vec3 gyro_bias_radps = Vec3::Zero();
  Mat3 accel_matrix = Mat3::Identity();
  Vec3 accel_bias_mps2 = Vec3::Zero();

  // Takes the calibration's inverse sensor matrices and biases; the mounting rotation is left as it is.
  void set_calibration(const calib::ImuCalibration& cal) {
    gyro_matrix = cal.gyro.sensor_matrix().inverse();
    gyro_bias_radps = cal.gyro.bias;
    accel_matrix = cal.accel.sensor_matrix().inverse();
    accel_bias_mps2 = cal.accel.bias;
  }

  void apply(Vec3& dtheta_rad, Vec3& dvel_mps, double dt_s) const {
    dtheta_rad = C_device_to_body * (gyro_matrix * (dtheta_rad - gyro_bias_radps * dt_s));
    dvel_mps = C_device_to_body * (accel_matrix * (dvel_mps - accel_bias_mps2 * dt_s));
  }
};

}  // namespace ldv::imu
