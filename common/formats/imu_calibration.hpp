#pragma once
// The result of `ldv calib static` as `ldv nav` and `imu_acq` use it: the docs/effects.md sensor model
//   f_meas = (I + diag(accel_scale) + N(accel_misalignment)) f_b + accel_bias
//   w_meas = (I + diag(gyro_scale) + N(gyro_misalignment)) C_b_g w_b + gyro_bias
// with N(m) = [[0, m_z, m_y], [m_z, 0, m_x], [m_y, m_x, 0]] (symmetric non-orthogonality). The body frame b
// is the accelerometer triad's own frame (the one in which its sensor matrix is symmetric); C_b_g is the small
// rotation of the gyro triad relative to it (zero when the calibration could not observe it).
// Measurements here are already in SI units (the device's nominal conversion applied), so a calibration is
// independent of how the device encodes its samples.
#include <string>

#include "common/formats/nav_types.hpp"
#include "common/math/rotation.hpp"

namespace ldv::calib {

// N(m) of docs/effects.md.
Mat3 non_orthogonality_matrix(const Vec3& misalignment_rad);

struct TriadCalibration {
  Vec3 bias = Vec3::Zero();                // m/s^2 (accel) or rad/s (gyro)
  Vec3 scale = Vec3::Zero();               // dimensionless scale-factor error
  Vec3 misalignment_rad = Vec3::Zero();    // (m_x, m_y, m_z): couple y-z, z-x, x-y
  Vec3 frame_rotation_rad = Vec3::Zero();  // rotation vector of this triad's axes in the body frame (gyro)
  // One-sigma uncertainties of the above (zero when unknown).
  Vec3 bias_sigma = Vec3::Zero();
  Vec3 scale_sigma = Vec3::Zero();
  Vec3 misalignment_sigma_rad = Vec3::Zero();
  Vec3 frame_rotation_sigma_rad = Vec3::Zero();

  // C_b_s: maps body-frame vectors into this triad's (rotated) axes.
  Mat3 C_b_s() const;
  // The full sensor matrix M with meas = M * true + bias.
  Mat3 sensor_matrix() const;
  // Inverse of the model: the true body-frame quantity from a measurement.
  Vec3 correct(const Vec3& measured) const;
};

struct ImuCalibration {
  TriadCalibration accel;  // SI: m/s^2
  TriadCalibration gyro;   // SI: rad/s
  std::string description; // free text: data set, method, date
};

// One rate sample in SI: specific force and angular rate, body front-right-down axes.
struct ImuRates {
  Vec3 f_b_mps2 = Vec3::Zero();
  Vec3 w_b_rad_s = Vec3::Zero();
};

ImuRates apply_calibration(const ImuCalibration& cal, const ImuRates& raw);
// Increments: the model is linear, so the integral over the sample is corrected with the bias times dt.
ImuIncrement apply_calibration(const ImuCalibration& cal, const ImuIncrement& raw);

// YAML file (units in the keys; see toolbox/calib/README.md). Throws InputError naming the file and key, also
// for values no calibration can hold (|scale| > 50 %, an angle > 0.5 rad, a negative sigma): a unit mistake.
ImuCalibration load_calibration(const std::string& path);
void save_calibration(const std::string& path, const ImuCalibration& cal);

}  // namespace ldv::calib
