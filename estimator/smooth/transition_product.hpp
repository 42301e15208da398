#pragma once
// Phi * M for a navigation filter's transition matrix: its first 9 rows (navigation errors) are dense, the rows
// of the effect states are sparse (each effect's own dynamics: identity, Gauss-Markov decay, a ramp's rate), so
// they are multiplied through their nonzeros. Exact; 5-10x cheaper than the dense product for 51 states, which
// the smoother does once per epoch forward (merging epochs) and once backward.
#include <Eigen/Core>

namespace ldv::est {

Eigen::MatrixXd transition_times(const Eigen::MatrixXd& Phi, const Eigen::MatrixXd& M);

}  // namespace ldv::est
