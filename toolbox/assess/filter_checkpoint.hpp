#pragma once
// A copy of a running NavFilter that outage segments restart from.
//
// NavFilter is not copyable (its StateLayout owns its effects through unique_ptr), so a checkpoint keeps
// what determines the future of a filter without measurements: the navigation state, the full error
// covariance and the effect estimates. The estimates are carried as the priors of a new filter (the
// options' `init` values), which `initialize` puts into its nominal effect state; `set_covariance` then
// restores P with all its correlations. Not carried: the mechanisation's previous increment (the first
// step after a restore has no coning/sculling correction) and the ramp rate of a moving bias (its
// current total bias is carried); `not_carried` names what was lost.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "estimator/filter/nav_filter.hpp"

namespace ldv::assess {

struct FilterCheckpoint {
  est::FilterOptions options;  // with the effect estimates as priors
  est::NavState state;
  Eigen::MatrixXd covariance;
  std::vector<std::string> not_carried;  // effect parts a restore cannot reproduce
};

FilterCheckpoint capture_checkpoint(const est::NavFilter& filter);

// A new filter in the checkpoint's state (zero-velocity updates, when enabled, still act during outages).
std::unique_ptr<est::NavFilter> restore_filter(const FilterCheckpoint& checkpoint);

}  // namespace ldv::assess
