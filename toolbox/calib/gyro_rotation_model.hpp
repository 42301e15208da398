#pragma once
// Gyro calibration for gyros that cannot sense Earth rate (MEMS), after Tedaldi et al. 2014 (imu_tk):
// between two consecutive static poses, integrate the calibrated gyro; the gravity direction measured in
// the first pose, rotated by the integrated attitude change, must match the direction measured in the next.
// Two conditions per transition (the direction's two degrees of freedom, in a tangent basis), observations
// = the two poses' mean specific force, and the integrated gyro white noise as extra condition covariance.
// The bias is not adjusted: it is measured in every static pose and interpolated over each motion (this
// follows a MEMS bias that drifts during the log). 9 unknowns x = [scale(3), misalignment(3) rad,
// frame_rotation(3) rad].
#include "toolbox/calib/gauss_helmert.hpp"
#include "common/formats/imu_calibration.hpp"
#include "toolbox/calib/imu_log.hpp"
#include "toolbox/calib/static_poses.hpp"

namespace ldv::calib {

// Attitude change C (v_start = C v_end) from integrating rates w(t) = correct(w_meas(t)) - with the bias
// interpolated linearly in time from bias_begin to bias_end - over samples [begin, end].
Mat3 integrate_attitude(const ImuLog& log, size_t begin, size_t end, const TriadCalibration& gyro,
                        const Vec3& bias_begin, const Vec3& bias_end);

// Samples where the gyro output is clipped at its full-scale range: per axis, the log's extreme value when
// it is reached at least 3 times (a measured peak repeats its exact value rarely; a clipped output sits
// there), or |w| >= full_scale_rad_s when given (> 0).
std::vector<bool> find_clipped_samples(const ImuLog& log, double full_scale_rad_s = 0.0);

class GyroRotationModel : public ConditionModel {
 public:
  // Uses the transitions between consecutive poses whose motion has no clipped gyro sample.
  GyroRotationModel(const ImuLog& log, const std::vector<Pose>& poses, const TriadCalibration& accel,
                    const std::vector<bool>& clipped);
  int num_params() const override { return 9; }
  std::vector<std::string> param_names() const override;
  VectorXd param_ranges() const override;
  void evaluate(int k, const VectorXd& l, const VectorXd& x, VectorXd& f, MatrixXd& A, MatrixXd& B) const override;

  std::vector<ConditionBlock> blocks() const;
  VectorXd misclosure(int k, const VectorXd& l, const VectorXd& x) const;
  // Gyro calibration from x plus the bias of the whole log (mean of the pose means, with its scatter).
  TriadCalibration to_triad(const VectorXd& x, const VectorXd& sigma) const;
  // Angle between predicted and measured gravity direction per transition [rad].
  double angle_residual_rad(int k, const VectorXd& x) const;
  // Pose index k of each transition k -> k+1 used, and those left out because the gyro clipped.
  const std::vector<size_t>& transitions() const { return transitions_; }
  const std::vector<size_t>& clipped_transitions() const { return clipped_transitions_; }

 private:
  const ImuLog& log_;
  const std::vector<Pose>& poses_;
  TriadCalibration accel_;
  std::vector<size_t> transitions_, clipped_transitions_;
  std::vector<int> basis_axis_;  // per transition: the body axis its misclosure's tangent basis is built from
};

}  // namespace ldv::calib
