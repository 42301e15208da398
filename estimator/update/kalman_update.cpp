#include "estimator/update/kalman_update.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

namespace ldv::est {

double noise_scale_for_nis(const Eigen::MatrixXd& HPHt, const Eigen::MatrixXd& R, const Eigen::VectorXd& y,
                           double target_nis) {
  const Eigen::LLT<Eigen::MatrixXd> llt_r(R);
  if (llt_r.info() != Eigen::Success || !(target_nis > 0.0)) return -1.0;
  // With R = L L^T, A = L^-1 HPHt L^-T = Q diag(a) Q^T and z = Q^T L^-1 y:
  // NIS(lambda) = sum z_i^2 / (a_i + lambda), decreasing in lambda.
  const int rows = static_cast<int>(y.size());
  const Eigen::MatrixXd L_inv = llt_r.matrixL().solve(Eigen::MatrixXd::Identity(rows, rows));
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(L_inv * HPHt * L_inv.transpose());
  const Eigen::VectorXd a = eig.eigenvalues().cwiseMax(0.0);
  const Eigen::VectorXd z = eig.eigenvectors().transpose() * (L_inv * y);
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
  const int rows = m.rows();
  const Eigen::MatrixXd PHt = P * m.H.transpose();  // n x rows
  const Eigen::MatrixXd HPHt = m.H * PHt;
  Eigen::MatrixXd S = HPHt + m.R;
  rec.sensor = m.sensor;
  rec.innovation = m.y;
  rec.S = S;
  rec.noise_scale = 1.0;
  Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (rows == 0 || llt.info() != Eigen::Success || !S.allFinite() || !m.y.allFinite()) {
    rec.nis = std::numeric_limits<double>::infinity();
    rec.accepted = false;
    if (K_out) K_out->setZero(P.rows(), rows);
    return false;
  }
  rec.nis = m.y.dot(llt.solve(m.y));
  bool accept = policy.force_accept || rec.nis <= policy.gate;
  if (!accept && policy.robust) {
    const double lambda = noise_scale_for_nis(HPHt, m.R, m.y, policy.gate * policy.gate / rec.nis);
    if (lambda >= 1.0 && std::isfinite(lambda)) {
      rec.noise_scale = lambda;
      S = HPHt + lambda * m.R;
      llt.compute(S);
      accept = llt.info() == Eigen::Success;
    }
  }
  rec.accepted = accept;
  if (!accept) {
    if (K_out) K_out->setZero(P.rows(), rows);
    return false;
  }
  const Eigen::MatrixXd K = llt.solve(PHt.transpose()).transpose();  // P H^T S^-1
  dx = K * m.y;
  const Eigen::MatrixXd KPHt = K * PHt.transpose();
  P += K * S * K.transpose() - KPHt - KPHt.transpose();
  P = 0.5 * (P + P.transpose()).eval();
  if (K_out) *K_out = K;
  return true;
}

}  // namespace ldv::est
