#include "toolbox/allan/nonnegative_lsq.hpp"

#include <limits>
#include <vector>

namespace ldv::allan {
namespace {

// Least squares restricted to the columns in `active` (bit mask), others 0; false when singular.
bool solve_subset(const Eigen::MatrixXd& A, const Eigen::VectorXd& y, unsigned active, Eigen::VectorXd& c) {
  const int p = static_cast<int>(A.cols());
  std::vector<int> idx;
  for (int k = 0; k < p; ++k)
    if (active & (1u << k)) idx.push_back(k);
  c = Eigen::VectorXd::Zero(p);
  if (idx.empty()) return true;
  Eigen::MatrixXd As(A.rows(), idx.size());
  for (size_t j = 0; j < idx.size(); ++j) As.col(j) = A.col(idx[j]);
  Eigen::VectorXd scale(idx.size());
  for (size_t j = 0; j < idx.size(); ++j) {
    scale(j) = As.col(j).norm();
    if (!(scale(j) > 0)) return false;
    As.col(j) /= scale(j);
  }
  const Eigen::MatrixXd N = As.transpose() * As;
  Eigen::LDLT<Eigen::MatrixXd> ldlt(N);
  if (ldlt.info() != Eigen::Success || ldlt.rcond() < 1e-14) return false;
  const Eigen::VectorXd cs = ldlt.solve(As.transpose() * y);
  for (size_t j = 0; j < idx.size(); ++j) c(idx[j]) = cs(j) / scale(j);
  return true;
}

}  // namespace

Eigen::VectorXd nonnegative_least_squares(const Eigen::MatrixXd& A, const Eigen::VectorXd& y, double* chi2) {
  const int p = static_cast<int>(A.cols());
  Eigen::VectorXd best = Eigen::VectorXd::Zero(p);
  double best_chi2 = std::numeric_limits<double>::infinity();
  for (unsigned mask = 0; mask < (1u << p); ++mask) {
    Eigen::VectorXd c;
    if (!solve_subset(A, y, mask, c)) continue;
    if ((c.array() < 0).any()) continue;
    const double r2 = (A * c - y).squaredNorm();
    if (r2 < best_chi2) best_chi2 = r2, best = c;
  }
  if (chi2) *chi2 = best_chi2;
  return best;
}

}  // namespace ldv::allan
