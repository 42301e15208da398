#include "estimator/smooth/rts_backward.hpp"

#include <Eigen/Cholesky>

#include "estimator/smooth/transition_product.hpp"

namespace ldv::est {

std::vector<SmoothedEpoch> rts_backward(const RtsEpochStore& store, const std::function<void(double)>& progress) {
  const std::size_t N = store.size();
  std::vector<SmoothedEpoch> out(N);
  if (N == 0) return out;
  RtsEpoch next = store.read(N - 1);
  Eigen::VectorXd e_s = Eigen::VectorXd::Zero(store.n());  // e^s of `next`, post-update
  Eigen::MatrixXd P_s = next.P_post;
  auto keep = [&](std::size_t k, const RtsEpoch& ep) {
    SmoothedEpoch& o = out[k];
    o.t_s = ep.t_s;
    o.dx_post = e_s;
    o.dx_prior = e_s + ep.dx;
    o.var_smoothed = P_s.diagonal();
    o.var_forward_post = ep.P_post.diagonal();
    o.var_forward_prior = ep.P_prior.diagonal();
    o.x_eff = ep.x_eff;
    o.restart = ep.Phi.isZero(0.0);
  };
  keep(N - 1, next);
  for (std::size_t k = N - 1; k-- > 0;) {
    RtsEpoch cur = store.read(k);
    const bool finite = next.Phi.allFinite() && next.P_prior.allFinite() && cur.P_post.allFinite() &&
                        next.dx.allFinite() && e_s.allFinite() && P_s.allFinite();
    if (next.Phi.isZero(0.0) || !finite) {
      // A restart at `next`: nothing after it says anything about `cur`.
      e_s.setZero();
      P_s = cur.P_post;
    } else {
      // C = P+ Phi^T (P-)^-1, through a Cholesky factor of P-; an LDL^T where P- is only semi-definite (a
      // state without noise or variance has a zero pivot, which the solve skips).
      const Eigen::MatrixXd G = transition_times(next.Phi, cur.P_post);  // Phi P+ = C^T P-
      const Eigen::LLT<Eigen::MatrixXd> llt(next.P_prior);
      const Eigen::MatrixXd C =
          (llt.info() == Eigen::Success ? Eigen::MatrixXd(llt.solve(G)) : Eigen::MatrixXd(next.P_prior.ldlt().solve(G)))
              .transpose();
      const Eigen::VectorXd e_prior_next = e_s + next.dx;
      e_s = C * e_prior_next;
      // P^s = P+ + C (P^s_next - P-) C^T, symmetric: only its lower half is computed, then mirrored.
      const Eigen::MatrixXd CD = C * (P_s - next.P_prior);
      P_s = cur.P_post;
      P_s.triangularView<Eigen::Lower>() += CD * C.transpose();
      P_s.triangularView<Eigen::StrictlyUpper>() = P_s.transpose();
    }
    keep(k, cur);
    next = std::move(cur);
    if (progress && k % 1000 == 0) progress(1.0 - static_cast<double>(k) / N);
  }
  return out;
}

}  // namespace ldv::est
