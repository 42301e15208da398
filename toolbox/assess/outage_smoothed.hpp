#pragma once
// `ldv outage --smooth`: what a post-processing user gets inside a GNSS gap. For each outage length, one run
// with the fixes of every planned gap of that length removed (they are recovery_s apart), filtered forward and
// smoothed backward (estimator/smooth); inside each gap, the smoothed error against the reference. The figure
// survey users ask for is the largest error inside the gap: the smoother ties both of its ends.
#include <vector>

#include "common/formats/kfgins_config.hpp"
#include "estimator/options.hpp"
#include "estimator/update/observation.hpp"
#include "toolbox/assess/nav_series.hpp"
#include "toolbox/assess/outage_plan.hpp"

namespace ldv::assess {

struct SmoothedGap {
  double max_horizontal_m = 0.0;          // largest smoothed horizontal error inside the gap
  double t_max_s = 0.0;                   // where
  double std_horizontal_at_max_m = 0.0;   // the smoother's horizontal 1-sigma there
  double max_vertical_m = 0.0;            // largest |down| error inside the gap
  double forward_max_horizontal_m = 0.0;  // the forward filter's, in the same run
  int samples = 0;                        // reference epochs compared inside the gap
};

// `windows` must not overlap (one length of a plan). Results in the order of `windows`. eval_period_s:
// the error is compared this often. reference_on_gps_time: the reference is a truth on GPS time (rows are
// compared with it at IMU epoch + time_offset), not the uncut run on the filter's IMU time.
std::vector<SmoothedGap> smooth_through_gaps(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                                             const KfGinsConfig& cfg, const est::FilterOptions& options,
                                             const std::vector<OutageWindow>& windows, const NavSeries& reference,
                                             const std::vector<est::ObservationPtr>& others, double eval_period_s,
                                             bool reference_on_gps_time);

}  // namespace ldv::assess
