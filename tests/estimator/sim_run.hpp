#pragma once
// Test helper: run the filter over a simulator run and measure errors against the simulator's truth
// (position / velocity / attitude RMS, outage drift, NEES against the filter's own covariance).
#include <string>
#include <vector>

#include "estimator/filter/nav_filter.hpp"
#include "sim/simulator.hpp"

namespace ldv::est::test {

struct Accuracy {
  double horiz_rms_m = 0, vert_rms_m = 0, vel_rms_mps = 0, roll_pitch_rms_deg = 0, yaw_rms_deg = 0;
  double outage_drift_m = 0;     // largest horizontal error during the outages
  double outage_drift_sigma_m = 0;  // the filter's horizontal 1-sigma at that moment
  double nees_pos = 0, nees_vel = 0, nees_att = 0;  // averages, 3 dof each (1 Hz samples, aided only)
  long samples = 0, gate_rejections = 0;
};

// Errors of the filter's state against truth: NED position [m], velocity, attitude phi [rad] (C_hat = (I - [phi x]) C).
Eigen::Matrix<double, 9, 1> nav_error(const NavState& s, const sim::TruthSample& t);

// Runs `options` on `sim` (initial state from the simulator's KF-GINS config, i.e. truth with its std)
// and returns the errors, evaluated after `settle_s`.
// `others`: readings of other sensors (odometer) fed with the fixes.
Accuracy evaluate(const sim::SimResult& sim, FilterOptions options, double settle_s = 60.0,
                  const std::vector<ObservationPtr>& others = {});

}  // namespace ldv::est::test
