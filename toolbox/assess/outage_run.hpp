#pragma once
// `ldv outage` as a library: the uncut filter runs once over the data, a checkpoint is taken at each
// planned outage start, and every outage segment then runs from its checkpoint without GNSS (so an
// outage costs only its own length), on all cores. Drift = outage solution minus the reference
// (truth, or the uncut solution where there is no truth), with the filter's own 1-sigma beside it.
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/formats/kfgins_config.hpp"
#include "estimator/ins/nav_state.hpp"
#include "estimator/options.hpp"
#include "estimator/update/observation.hpp"
#include "toolbox/assess/nav_difference.hpp"
#include "toolbox/assess/outage_plan.hpp"
#include "toolbox/assess/outage_smoothed.hpp"

namespace ldv::assess {

struct OutageRunOptions {
  std::vector<double> lengths_s = {60.0, 120.0, 300.0, 600.0};
  OutagePlanOptions plan;
  int threads = 0;                 // 0: every available core
  double eval_period_s = 0.1;      // drift evaluated this often for the maxima over an outage
  double curve_period_s = 1.0;     // drift curve points kept (report)
  // Reference mode for tests: each outage re-runs the filter from the start with its fixes removed
  // (what a user cutting the GNSS file would get); costs a whole run per outage.
  bool exact_rerun = false;
  std::function<void(const std::string&)> progress;  // human-readable progress lines
  // Other sensors' readings (odometer with --aid odometer), time order; they go on during the outages.
  std::vector<est::ObservationPtr> others;
  // Also smooth: per length, one forward + RTS run with every gap of that length cut (outage_smoothed.hpp).
  bool smooth = false;
  // The reference is on GPS time (a truth), not the filter's IMU time (the uncut run): the filter's epoch t is
  // compared with it at t + time_offset (NavFilter::gnss_time_s). run_outages sets it when given a truth.
  bool reference_on_gps_time = false;
};

struct DriftPoint {
  double t_since_start_s = 0.0;
  Vec3 pos_ned_m = Vec3::Zero();
  Vec3 pos_std_ned_m = Vec3::Zero();  // filter 1-sigma
  double yaw_deg = 0.0;
};

struct OutageResult {
  OutageWindow window;
  double t_end_s = 0.0;               // IMU epoch the end drift is taken at (last one <= start + length)
  NavDifference end_drift;            // at t_end_s (when end_measured)
  bool end_measured = false;          // the reference had a sample at t_end_s
  est::NavStd end_std;                // the outage filter's 1-sigma at t_end_s (att: phi, NED)
  std::array<double, 9> max_abs{};    // max over the outage of |component| (solution_comparison.hpp order)
  double max_horizontal_m = 0.0;      // max over the outage of the horizontal position drift
  std::optional<NavDifference> uncut_error;  // uncut solution minus truth at t_end_s (truth given)
  std::optional<SmoothedGap> smoothed;       // with OutageRunOptions::smooth
  std::vector<DriftPoint> curve;
};

struct OutageRun {
  std::string reference;  // "truth" or "uncut solution"
  std::vector<OutageResult> outages;              // sorted by length, then start
  std::vector<OutageWindow> unmeasured;           // planned, but the reference had no sample at their end
  double uncut_run_s = 0.0, outages_run_s = 0.0;  // wall time
  long imu_samples = 0;
  int threads = 1;
};

struct FilterCheckpoint;
// One outage from a checkpoint: the IMU samples after the checkpoint epoch up to start + length, no
// GNSS, drift against `reference` (also used directly by tests: a checkpoint made from the truth state).
OutageResult run_outage_segment(const FilterCheckpoint& checkpoint, const OutageWindow& window,
                                const std::vector<ImuIncrement>& imu, const NavSeries& reference,
                                const OutageRunOptions& options);

// `truth` may be empty (real data). Throws InputError / std::invalid_argument on unusable inputs.
OutageRun run_outages(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss, const KfGinsConfig& cfg,
                      const est::FilterOptions& filter_options, const NavSeries& truth, const OutageRunOptions& options);

}  // namespace ldv::assess
