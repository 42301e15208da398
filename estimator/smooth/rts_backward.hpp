#pragma once
// The Rauch-Tung-Striebel backward pass over a closed-loop error-state filter's epochs (rts_epoch_store.hpp).
//
// Forward, after epoch k's updates the nominal x_k carries error e_k (estimate minus truth) of mean 0 and
// covariance P_k+; it propagates to e_k+1- = Phi e_k + w (covariance P_k+1-), and the update removes dx:
// e_k+1+ = e_k+1- - dx. Backward, with C_k = P_k+ Phi^T (P_k+1-)^-1:
//   e_k^s = C_k (e_k+1^s + dx_k+1)          (the smoothed error of the post-update nominal)
//   P_k^s = P_k+ + C_k (P_k+1^s - P_k+1-) C_k^T
// starting from e_N^s = 0, P_N^s = P_N+. The smoothed state is x_k with e_k^s taken out (as the filter
// corrects: x -= e). A restart (Phi = 0) passes nothing back: the smoother starts afresh before it; so does an
// epoch whose matrices are not finite (a numerical fault the filter recovered from).
// Forward minus smoothed is e^s, of covariance P+ - P^s (the smoothed error is orthogonal to it): the
// separation and its expected envelope.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "estimator/smooth/rts_epoch_store.hpp"

namespace ldv::est {

struct SmoothedEpoch {
  double t_s = 0.0;
  Eigen::VectorXd dx_post;                              // e^s of the nominal after this epoch's updates
  Eigen::VectorXd dx_prior;                             // e^s of the nominal before them (dx_post + the epoch's dx)
  Eigen::VectorXd var_smoothed;                         // diagonal of P^s
  Eigen::VectorXd var_forward_post, var_forward_prior;  // diagonals of P+ and P-
  Eigen::VectorXd x_eff;                                // the effect states' forward nominal after the updates
  bool restart = false;  // the filter restarted here (Phi = 0): rows before it are not interpolated into it
};

// progress(done fraction) is called now and then.
std::vector<SmoothedEpoch> rts_backward(const RtsEpochStore& store, const std::function<void(double)>& progress = {});

}  // namespace ldv::est
