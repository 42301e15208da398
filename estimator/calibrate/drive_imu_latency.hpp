#pragma once
// Whether a drive's IMU stamps are late against GNSS time (a consumer IMU behind a USB or serial buffer), decided
// over the whole file before the filter runs: the turns' estimate (imu_latency.hpp) is taken out when significant
// and beyond what a lever arm within 2 sigma of its prior explains; a lag such a lever arm along the track could
// explain, or one the turns know only roughly, is judged by filter passes
// with and without it (the IMU noise they need, the GNSS positions' likelihood) and against a lever arm estimated
// on the way; a lag taken out is refined by the likelihood over further shifts. `ldv nav`, `outage`, `diagnose`
// read it through toolbox/assess/nav_inputs.
#include <cmath>
#include <string>
#include <vector>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/nav_types.hpp"
#include "estimator/calibrate/imu_latency.hpp"
#include "estimator/options.hpp"

namespace ldv::est {

struct DriveImuLatency {
  ImuLatencyEstimate turns;  // from the turns (valid when estimated)
  bool applied = false;      // a lag taken out of the stamps
  // Not taken out because a forward lever arm explained the fixes as well or better (the pair is the model's).
  bool lever_explains = false;
  // Where the filter judged the turns' lag over the whole file: -2 ln L of the GNSS positions without it minus with
  // it (positive: the lag fits better), NaN where it was not judged.
  double likelihood_gain = NAN;
  // The 1-parameter likelihood-ratio test at 99.9 %: -2 ln L must move by more than this to take a side.
  static constexpr double kLikelihoodTest = 10.83;
  // The fixes refute the turns' lag (its pass raises -2 ln L beyond the test: the real walk's 406 ms).
  bool refuted() const { return likelihood_gain < -kLikelihoodTest; }
  // The latency after the GNSS likelihood over further IMU shifts refined a lag taken out.
  struct Refined {
    bool done = false;
    double lag_s = 0.0, sigma_s = 0.0;
  } refined;
  std::string note;  // "; IMU latency ...": what was found and decided, for `ldv nav`'s first line
};

// The largest lever arm along the track a model could hold instead of a lag [m]: 2 sigma of the lever-arm prior (2 m a
// component by default: a van's antenna sits up to 4 m from an IMU under a seat).
double largest_lever_arm_along_m(const FilterOptions& options);

// -2 ln L of the GNSS positions over the whole file without minus with the IMU stamps shifted by lag_s (positive:
// the lag fits better), judged by filter passes as decide_drive_imu_latency judges a lag; NaN where a pass failed.
// The walk's turns read 406 ms, the fixes refute it (-5800): `ldv timesync` says so when given a configuration.
double likelihood_gain_of_lag(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                              const KfGinsConfig& config, const FilterOptions& options, double lag_s);

// imu and gnss in time order on one time base; a lag taken out is taken out of `imu` (in place). options: the run's
// filter options (the passes judge with them); refine_in_filter: refine a lag taken out (off in `ldv diagnose`,
// which names a time_offset itself).
DriveImuLatency decide_drive_imu_latency(std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                                         const KfGinsConfig& config, const FilterOptions& options,
                                         bool refine_in_filter);

}  // namespace ldv::est
