#pragma once
// Holes in an IMU record, found the same way by every IMU reader: intervals longer than 1.5 median intervals
// are counted (a missed sample), those beyond long_gap_factor median intervals are listed, so the estimator can
// stop integrating across them and a summary can name them.
#include <vector>

#include "common/formats/nav_types.hpp"

namespace ldv {

struct ImuGapSummary {
  double nominal_dt_s = 0.0;          // the median interval
  long gaps = 0;                      // intervals > 1.5 nominal
  std::vector<ImuTimeGap> long_gaps;  // intervals > long_gap_factor nominal
  double longest_gap_s = 0.0;
};

// `lines[i]` is the file line of imu[i] (empty: the sample index + 1 is given as the line).
ImuGapSummary find_imu_gaps(const std::vector<ImuIncrement>& imu, const std::vector<long>& lines,
                            double long_gap_factor = 10.0);

}  // namespace ldv
