#include "estimator/update/kalman_update.hpp"

#include <Eigen/Cholesky>

namespace ldv::est {

bool kalman_update(Eigen::MatrixXd& P, const Measurement& m, double gate, bool force_accept, InnovationRecord& rec,
                   Eigen::VectorXd& dx, Eigen::MatrixXd* K_out) {
  const Eigen::MatrixXd PHt = P * m.H.transpose();  // n x 3
  const Mat3 S = m.H * PHt + m.R;
  rec.kind = m.kind;
  rec.innovation = m.y;
  rec.S = S;
  const Eigen::LLT<Mat3> llt(S);
  if (llt.info() != Eigen::Success || !S.allFinite()) {
    rec.nis = std::numeric_limits<double>::infinity();
    rec.accepted = false;
    return false;
  }
  rec.nis = m.y.dot(llt.solve(m.y));
  rec.accepted = force_accept || rec.nis <= gate;
  if (!rec.accepted) {
    if (K_out) K_out->setZero(P.rows(), 3);
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
