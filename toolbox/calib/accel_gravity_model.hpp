#pragma once
// Accelerometer condition per static pose: the calibrated specific force has the magnitude of local
// gravity, |S^-1 (f_meas - b)| - g = 0, with S = I + diag(s) + N(m) symmetric (docs/effects.md). Gravity's
// magnitude cannot see a rotation of the triad, which is why the symmetric (non-orthogonality) form is
// the complete observable model: 9 unknowns, x = [bias(3) m/s^2, scale(3), misalignment(3) rad].
#include "toolbox/calib/gauss_helmert.hpp"
#include "common/formats/imu_calibration.hpp"
#include "toolbox/calib/static_poses.hpp"

namespace ldv::calib {

class AccelGravityModel : public ConditionModel {
 public:
  explicit AccelGravityModel(double gravity_mps2) : g_(gravity_mps2) {}
  int num_params() const override { return 9; }
  std::vector<std::string> param_names() const override;
  VectorXd param_ranges() const override;
  void evaluate(int k, const VectorXd& l, const VectorXd& x, VectorXd& f, MatrixXd& A, MatrixXd& B) const override;

  static std::vector<ConditionBlock> blocks(const std::vector<Pose>& poses);
  static TriadCalibration to_triad(const VectorXd& x, const VectorXd& sigma);
  // Start values from a closed-form axis-aligned ellipsoid fit (bias and scale; needs >= 6 poses,
  // otherwise the nominal sensor).
  static VectorXd initial_guess(const std::vector<Pose>& poses, double gravity_mps2);

 private:
  double g_;
};

}  // namespace ldv::calib
