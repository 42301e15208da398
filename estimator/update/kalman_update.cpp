#include "estimator/update/kalman_update.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

namespace ldv::est {

double noise_scale_for_nis(const Mat3& HPHt, const Mat3& R, const Vec3& y, double target_nis) {
  const Eigen::LLT<Mat3> llt_r(R);
  if (llt_r.info() != Eigen::Success || !(target_nis > 0.0)) return -1.0;
  // With R = L L^T, A = L^-1 HPHt L^-T = Q diag(a) Q^T and z = Q^T L^-1 y:
  // NIS(lambda) = sum z_i^2 / (a_i + lambda), decreasing in lambda.
  const Mat3 L_inv = llt_r.matrixL().solve(Mat3::Identity());
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(L_inv * HPHt * L_inv.transpose());
  const Vec3 a = eig.eigenvalues().cwiseMax(0.0);
  const Vec3 z = eig.eigenvectors().transpose() * (L_inv * y);
  auto nis = [&](double lambda) { return (z.array().square() / (a.array() + lambda)).sum(); };
  if (nis(1.0) <= target_nis) return 1.0;
  double lo = 0.0, hi = std::log(std::max(1.0, z.squaredNorm() / target_nis));  // NIS(e^hi) <= target
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (nis(std::exp(mid)) > target_nis ? lo : hi) = mid;
  }
  return std::exp(hi);
}

bool kalman_update(Eigen::MatrixXd& P, const Measurement& m, const UpdatePolicy& policy, InnovationRecord& rec,
                   Eigen::VectorXd& dx, Eigen::MatrixXd* K_out) {
  const Eigen::MatrixXd PHt = P * m.H.transpose();  // n x 3
  const Mat3 HPHt = m.H * PHt;
  Mat3 S = HPHt + m.R;
  rec.kind = m.kind;
  rec.innovation = m.y;
  rec.S = S;
  rec.noise_scale = 1.0;
  const Eigen::LLT<Mat3> llt(S);
  if (llt.info() != Eigen::Success || !S.allFinite() || !m.y.allFinite()) {
    rec.nis = std::numeric_limits<double>::infinity();
    rec.accepted = false;
    if (K_out) K_out->setZero(P.rows(), 3);
    return false;
  }
  rec.nis = m.y.dot(llt.solve(m.y));
  bool accept = policy.force_accept || rec.nis <= policy.gate;
  Eigen::LLT<Mat3> llt_used = llt;
  if (!accept && policy.robust) {
    const double lambda = noise_scale_for_nis(HPHt, m.R, m.y, policy.gate * policy.gate / rec.nis);
    if (lambda >= 1.0 && std::isfinite(lambda)) {
      rec.noise_scale = lambda;
      S = HPHt + lambda * m.R;
      llt_used.compute(S);
      accept = llt_used.info() == Eigen::Success;
    }
  }
  rec.accepted = accept;
  if (!accept) {
    if (K_out) K_out->setZero(P.rows(), 3);
    return false;
  }
  const Eigen::MatrixXd K = llt_used.solve(PHt.transpose()).transpose();  // P H^T S^-1
  dx = K * m.y;
  const Eigen::MatrixXd KPHt = K * PHt.transpose();
  P += K * S * K.transpose() - KPHt - KPHt.transpose();
  P = 0.5 * (P + P.transpose()).eval();
  if (K_out) *K_out = K;
  return true;
}

}  // namespace ldv::est
