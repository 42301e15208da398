#include "toolbox/allan/nonnegative_lsq.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace ldv::allan {
namespace {

// The normal equations of A c = y, formed once: every subset's solution and residual come from them (the
// likelihood fit's scoring calls this some 10^5 times per record on a thousand rows).
struct NormalEquations {
  Eigen::MatrixXd gram;  // A^T A
  Eigen::VectorXd aty;   // A^T y
  double yty = 0.0;
};

// Least squares restricted to the columns in `active` (bit mask), others 0; false when singular.
bool solve_subset(const NormalEquations& ne, unsigned active, Eigen::VectorXd& c) {
  const int p = static_cast<int>(ne.gram.cols());
  std::vector<int> idx;
  for (int k = 0; k < p; ++k)
    if (active & (1u << k)) idx.push_back(k);
  c = Eigen::VectorXd::Zero(p);
  if (idx.empty()) return true;
  const int q = static_cast<int>(idx.size());
  // Columns scaled to unit norm, so rcond judges the geometry, not the units.
  Eigen::VectorXd scale(q);
  for (int j = 0; j < q; ++j) {
    scale(j) = std::sqrt(ne.gram(idx[j], idx[j]));
    if (!(scale(j) > 0)) return false;
  }
  Eigen::MatrixXd n(q, q);
  Eigen::VectorXd b(q);
  for (int i = 0; i < q; ++i) {
    b(i) = ne.aty(idx[i]) / scale(i);
    for (int j = 0; j < q; ++j) n(i, j) = ne.gram(idx[i], idx[j]) / (scale(i) * scale(j));
  }
  Eigen::LDLT<Eigen::MatrixXd> ldlt(n);
  if (ldlt.info() != Eigen::Success || ldlt.rcond() < 1e-14) return false;
  const Eigen::VectorXd cs = ldlt.solve(b);
  for (int j = 0; j < q; ++j) c(idx[j]) = cs(j) / scale(j);
  return true;
}

}  // namespace

Eigen::VectorXd nonnegative_least_squares(const Eigen::MatrixXd& A, const Eigen::VectorXd& y, double* chi2) {
  const int p = static_cast<int>(A.cols());
  const NormalEquations ne{A.transpose() * A, A.transpose() * y, y.squaredNorm()};
  Eigen::VectorXd best = Eigen::VectorXd::Zero(p);
  double best_r2 = std::numeric_limits<double>::infinity();
  for (unsigned mask = 0; mask < (1u << p); ++mask) {
    Eigen::VectorXd c;
    if (!solve_subset(ne, mask, c)) continue;
    if ((c.array() < 0).any()) continue;
    // |A c - y|^2 from the normal equations; the chosen one's is recomputed from the rows below.
    const double r2 = ne.yty - 2.0 * c.dot(ne.aty) + c.dot(ne.gram * c);
    if (r2 < best_r2) best_r2 = r2, best = c;
  }
  if (chi2) *chi2 = std::isfinite(best_r2) ? (A * best - y).squaredNorm() : best_r2;
  return best;
}

}  // namespace ldv::allan
