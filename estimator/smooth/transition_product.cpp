#include "estimator/smooth/transition_product.hpp"

#include <algorithm>

#include "estimator/state/state_layout.hpp"

namespace ldv::est {

Eigen::MatrixXd transition_times(const Eigen::MatrixXd& Phi, const Eigen::MatrixXd& M) {
  const Eigen::Index n = Phi.rows(), dense = std::min<Eigen::Index>(kNavDim, n);
  Eigen::MatrixXd out(n, M.cols());
  out.topRows(dense).noalias() = Phi.topRows(dense) * M;
  for (Eigen::Index r = dense; r < n; ++r) {
    out.row(r).setZero();
    for (Eigen::Index c = 0; c < Phi.cols(); ++c)
      if (Phi(r, c) != 0.0) out.row(r) += Phi(r, c) * M.row(c);
  }
  return out;
}

}  // namespace ldv::est
