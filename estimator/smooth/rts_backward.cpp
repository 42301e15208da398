#include "estimator/smooth/rts_backward.hpp"

#include <Eigen/Cholesky>

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
  };
  keep(N - 1, next);
  for (std::size_t k = N - 1; k-- > 0;) {
    RtsEpoch cur = store.read(k);
    if (next.Phi.isZero(0.0)) {
      // A restart at `next`: nothing after it says anything about `cur`.
      e_s.setZero();
      P_s = cur.P_post;
    } else {
      // C = P+ Phi^T (P-)^-1, through an LDL^T of P- (semi-definite: a state without noise or variance
      // has a zero pivot, which the solve skips).
      const Eigen::LDLT<Eigen::MatrixXd> ldlt(next.P_prior);
      const Eigen::MatrixXd C = ldlt.solve(next.Phi * cur.P_post).transpose();
      const Eigen::VectorXd e_prior_next = e_s + next.dx;
      e_s = C * e_prior_next;
      P_s = cur.P_post + C * (P_s - next.P_prior) * C.transpose();
      P_s = 0.5 * (P_s + P_s.transpose()).eval();
    }
    keep(k, cur);
    next = std::move(cur);
    if (progress && k % 1000 == 0) progress(1.0 - static_cast<double>(k) / N);
  }
  return out;
}

}  // namespace ldv::est
