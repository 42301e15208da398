#include "estimator/run/alignment_options_from.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ldv::est {
AlignmentOptions alignment_options_from(const FilterOptions& fo) {
  AlignmentOptions ao;
  ao.gyro_bias_std_rad_s = fo.gyro_bias.init_std.maxCoeff();
  ao.arw_rad_per_sqrt_s = fo.arw_rad_per_sqrt_s.maxCoeff();
  ao.vrw_mps_per_sqrt_s = fo.vrw_mps_per_sqrt_s.maxCoeff();
  ao.accel_bias_std_mps2 = fo.accel_bias.init_std.maxCoeff();
  ao.lever_arm_b_m = fo.lever_arm.init;
  ao.time_offset_s = fo.time_offset_init_s;
  ao.speed_min_mps = fo.align_speed_mps;
  // Each hypothesis is a filter run side by side: more than one per degree is never useful and a huge
  // count exhausts memory (every path to the alignment passes here).
  if (fo.align_hypotheses > 360)
    throw std::invalid_argument("align_hypotheses " + std::to_string(fo.align_hypotheses) + ": at most 360");
  if (!(std::isfinite(fo.align_speed_mps) && fo.align_speed_mps > 0))
    throw std::invalid_argument("align_speed_mps must be > 0 and finite");
  ao.course_hypotheses = std::max(1, fo.align_hypotheses);
  // KF-GINS-compatible runs keep the aligner as it was; otherwise the GNSS checks standstill and course, and
  // a velocity the velocity check refused is not used for the course either.
  ao.gnss_checks = fo.robust_update;
  ao.use_fix_velocity = !fo.robust_update || fo.use_gnss_velocity;
  return ao;
}
}  // namespace ldv::est
