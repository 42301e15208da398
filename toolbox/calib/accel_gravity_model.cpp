#include "toolbox/calib/accel_gravity_model.hpp"

#include <Eigen/Dense>

namespace ldv::calib {

std::vector<std::string> AccelGravityModel::param_names() const {
  return {"accel_bias_x",         "accel_bias_y",         "accel_bias_z",
          "accel_scale_x",        "accel_scale_y",        "accel_scale_z",
          "accel_misalignment_x", "accel_misalignment_y", "accel_misalignment_z"};
}

VectorXd AccelGravityModel::param_ranges() const {
  VectorXd r(9);
  r << Vec3::Constant(0.5 * g_), Vec3::Constant(0.2), Vec3::Constant(0.2);  // 0.5 g, 20 %, 0.2 rad
  return r;
}

void AccelGravityModel::evaluate(int, const VectorXd& l, const VectorXd& x, VectorXd& f, MatrixXd& A,
                                 MatrixXd& B) const {
  const Vec3 b = x.segment<3>(0), s = x.segment<3>(3), m = x.segment<3>(6);
  const Mat3 S = Mat3::Identity() + Mat3(s.asDiagonal()) + non_orthogonality_matrix(m);
  const Mat3 Sinv = S.inverse();
  const Vec3 u = Sinv * (l.head<3>() - b);  // calibrated specific force
  const double norm = u.norm();
  f.resize(1);
  f[0] = norm - g_;
  // d|u| = (u/|u|)' du, du = S^-1 (dl - db) - S^-1 dS u; gT = (u/|u|)' S^-1.
  const Eigen::RowVector3d gT = (u / norm).transpose() * Sinv;
  B = gT;
  A.resize(1, 9);
  A.block<1, 3>(0, 0) = -gT;
  for (int i = 0; i < 3; ++i) A(0, 3 + i) = -gT[i] * u[i];
  A(0, 6) = -(gT[1] * u[2] + gT[2] * u[1]);  // m_x couples y-z
  A(0, 7) = -(gT[2] * u[0] + gT[0] * u[2]);  // m_y couples z-x
  A(0, 8) = -(gT[0] * u[1] + gT[1] * u[0]);  // m_z couples x-y
}

std::vector<ConditionBlock> AccelGravityModel::blocks(const std::vector<Pose>& poses) {
  std::vector<ConditionBlock> out;
  for (const Pose& p : poses) out.push_back({p.f_mean_mps2, p.f_mean_cov, MatrixXd()});
  return out;
}

TriadCalibration AccelGravityModel::to_triad(const VectorXd& x, const VectorXd& sigma) {
  TriadCalibration t;
  t.bias = x.segment<3>(0);
  t.scale = x.segment<3>(3);
  t.misalignment_rad = x.segment<3>(6);
  t.bias_sigma = sigma.segment<3>(0);
  t.scale_sigma = sigma.segment<3>(3);
  t.misalignment_sigma_rad = sigma.segment<3>(6);
  return t;
}

VectorXd AccelGravityModel::initial_guess(const std::vector<Pose>& poses, double gravity_mps2) {
  VectorXd x = VectorXd::Zero(9);
  if (poses.size() < 6) return x;
  // sum_i a_i l_i^2 + c_i l_i = 1 is linear in (a, c); the ellipsoid is sum_i a_i (l_i - b_i)^2 = rho.
  MatrixXd J(poses.size(), 6);
  for (size_t k = 0; k < poses.size(); ++k) {
    const Vec3& l = poses[k].f_mean_mps2;
    J.row(k) << l.x() * l.x(), l.y() * l.y(), l.z() * l.z(), l.x(), l.y(), l.z();
  }
  const VectorXd p = J.colPivHouseholderQr().solve(VectorXd::Ones(poses.size()));
  const Vec3 a = p.head<3>(), c = p.tail<3>();
  if ((a.array() <= 0.0).any() || !p.allFinite()) return x;
  const Vec3 b = -c.cwiseQuotient(2.0 * a);
  const double rho = 1.0 + (a.array() * b.array().square()).sum();
  for (int i = 0; i < 3; ++i) {
    x[i] = b[i];
    x[3 + i] = std::sqrt(rho / a[i]) / gravity_mps2 - 1.0;
  }
  return x.allFinite() ? x : VectorXd::Zero(9);
}

}  // namespace ldv::calib
