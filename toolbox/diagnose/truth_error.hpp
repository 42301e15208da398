#pragma once
// Navigation error of a run against truth (truth.nav: IMU centre), at the run's 10 Hz epochs (on the GNSS time
// scale: NavFilter::gnss_time_s), the truth interpolated there.
#include <array>
#include <string>
#include <vector>

#include "toolbox/diagnose/filter_run.hpp"
#include "toolbox/diagnose/segments.hpp"

namespace ldv::diag {

struct TruthError {
  bool available = false;
  bool given = false;         // a truth was given (available false: it did not cover the run: see coverage_note)
  std::string coverage_note;  // "" when the truth covers every compared epoch; else what it covered and what not
  int compared_epochs = 0, run_epochs = 0;  // after the skip
  std::vector<double> t_s;
  std::vector<Vec3> pos_err_ned_m;  // estimate minus truth
  double rms_pos_3d_m = 0.0, rms_horizontal_m = 0.0, rms_vertical_m = 0.0, max_horizontal_m = 0.0;
  double rms_yaw_deg = 0.0;
  std::array<double, kSegmentCount> rms_pos_3d_by_segment_m{};
};

// Epochs before `skip_s` after the start (initial convergence) are left out of the RMS.
TruthError truth_error(const FilterRun& run, const std::vector<Segment>& labels, const std::vector<NavRecord>& truth,
                       double skip_s = 0.0);

}  // namespace ldv::diag
