#pragma once
// How late the IMU's time tags are against GNSS time, from the data alone: the turn rate the gyros sense
// about the vertical must match the turn rate of the GNSS track. Consumer IMUs behind USB or serial
// buffers are tagged on arrival, hundreds of milliseconds late; a filter that integrates them at the
// wrong time sees every turn as a lever-arm or heading error and leaves the RTK.
//
// Method: the vertical is the mean specific force over the file (any mounting, upside down included). The
// GNSS course at fix k is the chord from fix k-1 to k+1, i.e. the mean heading over that span; the IMU's
// heading about the vertical is averaged over the same span shifted by the lag, and the course changes
// between consecutive fixes are compared. (Matching the spans keeps turns of any shape consistent and the
// misfit smooth in the lag: with the IMU's heading read at the fix epochs, a MEMS gyro vibrating at 10x its
// datasheet noise made it rough at the scale of an IMU sample, its minimum off by 50-350 ms at a sigma of a
// few ms.) The lag minimises the squared misfit with a constant gyro bias fitted alongside (10 ms grid,
// then 1 ms around its best, parabolic refinement); sigma from the misfit's curvature and residual scatter.
// The course changes a GNSS outlier made (beyond 5 robust sigma of the first fit's residuals) are left out
// and the search is run again.
#include <algorithm>
#include <cmath>
#include <vector>

#include "common/formats/nav_types.hpp"

namespace ldv::est {

struct ImuLatencyOptions {
  double max_lag_s = 1.0;        // searched in [-max, +max]
  double min_speed_mps = 1.0;    // course taken only when moving
  int min_intervals = 20;        // fewer turning intervals: no estimate
  double min_turn_rad_s = 0.02;  // an interval counts as turning above this course rate
  // The sigma from a delete-a-group jackknife over this many contiguous groups of intervals (0: from the misfit's
  // curvature and residual scatter, as if the residuals were independent). Consecutive course changes share a
  // chord, so their errors are correlated: the curvature's sigma was 4-12x too large on simulated drives with the
  // clock offset known (montecarlo_timesync.cpp); the jackknife sees the correlation. `ldv timesync` uses it.
  int jackknife_groups = 0;
};

struct ImuLatencyEstimate {
  bool valid = false;    // enough turning to estimate
  double lag_s = 0.0;    // IMU tags minus true time: add -lag_s to every IMU stamp
  double sigma_s = 0.0;  // 1-sigma
  int intervals = 0;     // GNSS intervals used
  int turning_intervals = 0;
  int outlier_intervals = 0;  // left out of the second search
  double residual_rms_rad = 0.0;  // heading-change misfit at the optimum
  double median_speed_mps = 0.0;  // over the intervals used
  // The antenna's forward lever arm l_x shifts the track's course by w l_x / v, which this estimate
  // cannot tell from a lag of l_x / v (the main job's 0.6 m at 12 m/s read as 50 ms). So a lag counts as
  // an IMU latency only beyond what a lever arm of kMaxLeverArmAlong_m could explain; smaller time
  // offsets are the time_offset effect's to estimate (ldv diagnose finds it).
  static constexpr double kMaxLeverArmAlong_m = 1.5;
  double lever_arm_equivalent_lag_s() const {
    return median_speed_mps > 0 ? kMaxLeverArmAlong_m / median_speed_mps : 1e9;
  }
  // The other way round: the antenna's offset along the track [m] that turns the course as this lag does.
  double equivalent_lever_arm_along_m() const { return std::abs(lag_s) * median_speed_mps; }
  // Worth correcting the data for without asking the filter: beyond 3 sigma, beyond the lever-arm equivalent, at
  // least 5 ms, and known to better than kMaxSigma_s. (`ldv nav` lets the filter decide on a lag beyond 3 sigma
  // that fails the other two: drive_imu_latency.cpp.)
  static constexpr double kMaxSigma_s = 0.02;
  bool significant() const {
    return valid && std::abs(lag_s) > std::max({3.0 * sigma_s, 0.005, lever_arm_equivalent_lag_s()}) &&
           sigma_s < kMaxSigma_s;
  }
};

// imu and gnss in time order on the same time base (GPS seconds of week).
ImuLatencyEstimate estimate_imu_latency(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                                        const ImuLatencyOptions& options = {});

}  // namespace ldv::est
