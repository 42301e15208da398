#pragma once
// Gyro conditions per static pose for gyros that resolve Earth rate (navigation / tactical grade):
//   |w_b| - Omega_ie = 0                           (magnitude: bias, scale, non-orthogonality)
//   (w_b . f_b) / |f_b| - Omega_ie sin(lat) = 0     (angle to gravity: the gyro triad's rotation to the
//                                                   accelerometer triad)
// with w_b = C_g_b S^-1 (w_meas - b) and f_b the pose's specific force corrected with the (fixed)
// accelerometer calibration. 12 unknowns x = [bias(3) rad/s, scale(3), misalignment(3) rad,
// frame_rotation(3) rad]. For a MEMS gyro the Earth-rate signal is buried in noise and bias: the
// observability check reports it unresolved and the solve is refused.
#include "toolbox/calib/gauss_helmert.hpp"
#include "common/formats/imu_calibration.hpp"
#include "toolbox/calib/static_poses.hpp"

namespace ldv::calib {

class GyroEarthRateModel : public ConditionModel {
 public:
  GyroEarthRateModel(const TriadCalibration& accel, double lat_rad, double h_m);
  int num_params() const override { return 12; }
  std::vector<std::string> param_names() const override;
  VectorXd param_ranges() const override;
  void evaluate(int k, const VectorXd& l, const VectorXd& x, VectorXd& f, MatrixXd& A, MatrixXd& B) const override;

  VectorXd misclosure(const VectorXd& l, const VectorXd& x) const;
  static std::vector<ConditionBlock> blocks(const std::vector<Pose>& poses);
  static TriadCalibration to_triad(const VectorXd& x, const VectorXd& sigma);
  // Start: the bias from the pose means (Earth rate averages out over varied poses), the rest nominal.
  static VectorXd initial_guess(const std::vector<Pose>& poses);

 private:
  TriadCalibration accel_;
  double omega_up_component_;  // Omega_ie sin(lat): the projection of Earth rate on the up direction
};

}  // namespace ldv::calib
