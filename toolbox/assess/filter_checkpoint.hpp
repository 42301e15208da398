#pragma once
// A checkpoint of a running NavFilter that outage segments restart from: a copy of the filter.
//
// NavFilter keeps its whole state in value members (its effects are shared, immutable), so a copy continues
// exactly as the original would on the same data: navigation state, covariance, every effect estimate (the
// moving biases' split and ramp rates, the GNSS position bias, ...), the mechanisation's previous increment
// (coning/sculling), the adapted IMU noise scale, the ZUPT detector, the snapshots and IMU history a late fix
// rewinds to. What the copy does not take over from the original:
//  - its observer (no copy of a NavFilter does: nav_filter.hpp); set one on the restored filter to watch a
//    restart;
//  - innovation records not yet taken (outputs of the original's past, not state);
//  - fixes queued ahead of the IMU with a time tag after `gnss_until_s`: a checkpoint restarts into a GNSS
//    outage, and those fixes belong to it. Fixes up to it stay (one due at the restart epoch, e.g. with a
//    time offset, is applied as in the run that has the outage).
// Tests: tests/assess/test_checkpoint_exact.cpp (equal to 1e-9 m to the original, and to a re-run with the
// outage's fixes removed).
#include "estimator/filter/nav_filter.hpp"

namespace ldv::assess {

struct FilterCheckpoint {
  est::NavFilter filter;  // never run: each restart runs its own copy (restore_filter)
};

// `gnss_until_s`: the last fix time tag the restart may still apply (+infinity: every queued fix).
FilterCheckpoint capture_checkpoint(const est::NavFilter& running, double gnss_until_s);

// A filter in the checkpoint's state, ready for add_imu / add_gnss (zero-velocity updates, when enabled,
// still act during outages).
est::NavFilter restore_filter(const FilterCheckpoint& checkpoint);

}  // namespace ldv::assess
