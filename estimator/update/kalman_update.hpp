#pragma once
// The measurement update shared by every updater: chi-square gate on the NIS, then the Joseph form
// P+ = (I - K H) P (I - K H)^T + K R K^T, evaluated as P - K (PH^T)^T - (PH^T) K^T + K S K^T
// (algebraically identical, O(n^2 m) instead of O(n^3)), symmetrised.
#include <Eigen/Core>

#include "estimator/filter/records.hpp"
#include "estimator/update/measurement.hpp"

namespace ldv::est {

// Fills rec (innovation, S, NIS, decision). When accepted (NIS <= gate or force_accept), updates P and
// returns the error-state estimate in dx; K (n x 3) is written when K_out is given.
bool kalman_update(Eigen::MatrixXd& P, const Measurement& m, double gate, bool force_accept, InnovationRecord& rec,
                   Eigen::VectorXd& dx, Eigen::MatrixXd* K_out = nullptr);

}  // namespace ldv::est
