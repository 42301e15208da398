#include "toolbox/calib/gyro_earth_rate_model.hpp"

#include "common/geo/earth_model.hpp"

namespace ldv::calib {

GyroEarthRateModel::GyroEarthRateModel(const TriadCalibration& accel, double lat_rad, double h_m) : accel_(accel) {
  const Vec3 up_n = -earth::gravity_n(lat_rad, h_m).normalized();  // specific force at rest points up
  omega_up_component_ = earth::omega_ie_n(lat_rad).dot(up_n);
}

std::vector<std::string> GyroEarthRateModel::param_names() const {
  return {"gyro_bias_x",         "gyro_bias_y",         "gyro_bias_z",         "gyro_scale_x",
          "gyro_scale_y",        "gyro_scale_z",        "gyro_misalignment_x", "gyro_misalignment_y",
          "gyro_misalignment_z", "gyro_rotation_x",     "gyro_rotation_y",     "gyro_rotation_z"};
}

VectorXd GyroEarthRateModel::param_ranges() const {
  // A bias we cannot tell from Earth rate itself, 20 % scale, 0.2 rad angles.
  VectorXd r(12);
  r << Vec3::Constant(earth::kOmegaIe_rad_s), Vec3::Constant(0.2), Vec3::Constant(0.2), Vec3::Constant(0.2);
  return r;
}

VectorXd GyroEarthRateModel::misclosure(const VectorXd& l, const VectorXd& x) const {
  TriadCalibration g = to_triad(x, VectorXd::Zero(12));
  const Vec3 w_b = g.correct(l.head<3>());
  const Vec3 f_b = accel_.correct(l.tail<3>());
  VectorXd f(2);
  f << w_b.norm() - earth::kOmegaIe_rad_s, w_b.dot(f_b) / f_b.norm() - omega_up_component_;
  return f;
}

void GyroEarthRateModel::evaluate(int, const VectorXd& l, const VectorXd& x, VectorXd& f, MatrixXd& A,
                                  MatrixXd& B) const {
  VectorXd dx(12), dl(6);
  dx << Vec3::Constant(1e-9), Vec3::Constant(1e-6), Vec3::Constant(1e-6), Vec3::Constant(1e-6);
  dl << Vec3::Constant(1e-9), Vec3::Constant(1e-5);
  numeric_jacobians([this](const VectorXd& ll, const VectorXd& xx) { return misclosure(ll, xx); }, l, x, dl, dx, f,
                    A, B);
}

std::vector<ConditionBlock> GyroEarthRateModel::blocks(const std::vector<Pose>& poses) {
  std::vector<ConditionBlock> out;
  for (const Pose& p : poses) {
    ConditionBlock b;
    b.l.resize(6);
    b.l << p.w_mean_rad_s, p.f_mean_mps2;
    b.Sigma_l = MatrixXd::Zero(6, 6);
    b.Sigma_l.topLeftCorner<3, 3>() = p.w_mean_cov;
    b.Sigma_l.bottomRightCorner<3, 3>() = p.f_mean_cov;
    out.push_back(b);
  }
  return out;
}

TriadCalibration GyroEarthRateModel::to_triad(const VectorXd& x, const VectorXd& sigma) {
  TriadCalibration t;
  t.bias = x.segment<3>(0);
  t.scale = x.segment<3>(3);
  t.misalignment_rad = x.segment<3>(6);
  t.frame_rotation_rad = x.segment<3>(9);
  t.bias_sigma = sigma.segment<3>(0);
  t.scale_sigma = sigma.segment<3>(3);
  t.misalignment_sigma_rad = sigma.segment<3>(6);
  t.frame_rotation_sigma_rad = sigma.segment<3>(9);
  return t;
}

VectorXd GyroEarthRateModel::initial_guess(const std::vector<Pose>& poses) {
  VectorXd x = VectorXd::Zero(12);
  if (poses.empty()) return x;
  Vec3 mean = Vec3::Zero();
  for (const Pose& p : poses) mean += p.w_mean_rad_s;
  x.head<3>() = mean / static_cast<double>(poses.size());
  return x;
}

}  // namespace ldv::calib
