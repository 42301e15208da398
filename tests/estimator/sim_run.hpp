#pragma once
// Test helper: run the filter over a simulator run and measure errors against the simulator's truth
// (position / velocity / attitude RMS, outage drift, NEES against the filter's own covariance).
#include <string>
#include <vector>

#include "estimator/options.hpp"
#include "estimator/smooth/rts_recorder.hpp"
#include "estimator/update/observation.hpp"
#include "sim/simulator.hpp"
#include "toolbox/allan/phase_series.hpp"

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

// A simulator request for 6 min standing (seed 7) from an IMU whose gyros have white noise N [deg/sqrt(h)] and
// quantisation Q [rad] and nothing else, the accelerometers perfect: the scenes that study one gyro term alone.
sim::SimRequest gyro_noise_only_request(double n_deg_per_sqrt_h, double q_rad = 0.0);

// The gyro and accelerometer rates of a (static) simulated record as Allan channels gyro_x.. (rad/s), then
// accel_x.. (m/s^2).
std::vector<allan::PhaseSeries> allan_channels_of(const sim::SimResult& s);

// Runs `options` on `sim` (initial state from the simulator's KF-GINS config, i.e. truth with its std)
// and returns the errors, evaluated after `settle_s`.
// `others`: readings of other sensors (odometer) fed with the fixes.
Accuracy evaluate(const sim::SimResult& sim, FilterOptions options, double settle_s = 60.0,
                  const std::vector<ObservationPtr>& others = {});

// The simulated run filtered forward with these options (the simulator's configuration, to the end of the data)
// and smoothed (estimator/smooth).
SmoothedRun smooth_run(const sim::SimResult& sim, const FilterOptions& options);

// A simulated figure-8 drive with GNSS outages, filtered forward (kfgins21 + gnss_position_bias, which the
// simulator's RTK errors need) and smoothed (estimator/smooth); both against truth at 10 Hz.
struct GapErrors {
  double forward_end_m = 0.0;   // forward horizontal error at the gap's last epoch
  double smoothed_max_m = 0.0;  // largest smoothed horizontal error inside the gap
};
struct SmoothedDrive {
  std::vector<GapErrors> gaps;
  double forward_aided_rms_m = 0.0, smoothed_aided_rms_m = 0.0;  // horizontal, outside the gaps
  double within_3sigma_aided = 0.0, within_3sigma_gaps = 0.0;    // fraction of smoothed errors (9 components)
  double nees_per_dof_aided = 0.0, nees_per_dof_gaps = 0.0;      // mean (e / sigma)^2 of the 9 components
  double forward_nees_per_dof_gaps = 0.0;                          // the same of the forward filter
};
SmoothedDrive smooth_drive(const std::string& grade, std::uint64_t seed, const std::vector<sim::Outage>& outages,
                           double duration_s);
// The issue 15 criteria (gtest expectations): aided RMS no worse than forward, and the smoothed errors consistent
// with the smoothed covariance, in the gaps too;
void expect_smoothed_consistent(const SmoothedDrive& d);
// and the largest smoothed horizontal error inside each gap at most max_ratio of the forward drift at its end
// (1/10 tactical, 1/4 MEMS).
void expect_smoothing_works(const SmoothedDrive& d, double max_ratio);

}  // namespace ldv::est::test
