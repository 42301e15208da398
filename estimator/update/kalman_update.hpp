#pragma once
// The measurement update shared by every updater: chi-square gate on the NIS, then the Joseph form
// P+ = (I - K H) P (I - K H)^T + K R K^T, evaluated as P - K (PH^T)^T - (PH^T) K^T + K S K^T
// (algebraically identical, O(n^2 m) instead of O(n^3)), symmetrised.
//
// Beyond the gate a measurement is either rejected (the KF-GINS behaviour) or, with `robust`, kept with
// its noise R inflated by a factor lambda >= 1 chosen so that its NIS becomes gate^2 / NIS: just over
// the gate it keeps almost its full weight, and the further out it is, the less it moves the state
// (the shift falls like 1/|y|^3 far out: a 2 m jump in a 2 cm solution moves the state by microns). The
// effect of one odd measurement on the state is bounded by construction; a real step of the measured
// quantity is taken up by the caller's step confirmation (NavFilter: consecutive measurements that agree).
#include <Eigen/Core>

#include "estimator/filter/records.hpp"
#include "estimator/update/measurement.hpp"

namespace ldv::est {

struct UpdatePolicy {
  double gate = 0.0;          // chi-square quantile on the NIS for the measurement's rows (its dof)
  bool robust = false;        // beyond the gate: down-weight instead of reject
  bool force_accept = false;  // accept in full whatever the NIS (after the caller opened the covariance)
};

// Fills rec (innovation, S, NIS, decision, noise_scale). When accepted, updates P and returns the
// error-state estimate in dx; K (n x rows) is written when K_out is given.
bool kalman_update(Eigen::MatrixXd& P, const Measurement& m, const UpdatePolicy& policy, InnovationRecord& rec,
                   Eigen::VectorXd& dx, Eigen::MatrixXd* K_out = nullptr);

// The factor lambda >= 1 on R that brings the NIS of y under H P H^T + lambda R down to target_nis
// (closed form in the eigenbasis of R^-1/2 H P H^T R^-T/2, solved by bisection in ln lambda).
// Returns 1 when the NIS is already at or below the target, and a negative number when R is not
// positive definite.
double noise_scale_for_nis(const Eigen::MatrixXd& HPHt, const Eigen::MatrixXd& R, const Eigen::VectorXd& y,
                           double target_nis);

}  // namespace ldv::est
