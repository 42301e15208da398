#pragma once
// Non-negative least squares for the handful of noise terms: min |A c - y|^2 subject to c >= 0,
// exactly, by enumerating the passive sets (2^p subsets; p <= 8 here). Columns are scaled first,
// since the noise terms' columns span many orders of magnitude.
#include <Eigen/Dense>

namespace ldv::allan {

// Returns c (size A.cols()); *chi2 (if given) = |A c - y|^2, infinity when no subset solves.
Eigen::VectorXd nonnegative_least_squares(const Eigen::MatrixXd& A, const Eigen::VectorXd& y, double* chi2 = nullptr);

}  // namespace ldv::allan
