#pragma once
// Static-interval detector (Tedaldi et al. 2014 / imu_tk): the norm of the per-axis accelerometer variance
// over a sliding window, compared with a threshold that is a multiple of the same norm over the initial
// static period (so the threshold follows the sensor's own noise, whatever its grade or units). Every
// detected interval longer than the minimum pose duration becomes a pose: its mean and the covariance of
// that mean from its own sample scatter.
#include <string>
#include <vector>

#include "toolbox/calib/imu_log.hpp"

namespace ldv::calib {

struct StaticDetectorOptions {
  double init_static_s = 30.0;  // initial static period that sets the noise level
  double window_s = 1.0;        // variance window (imu_tk: 101 samples at 100 Hz)
  double min_pose_s = 2.0;      // shorter quiet spells are not poses
  double threshold_multiplier = 0.0;  // k in threshold = k * init variance norm; 0: choose by sweeping 2..10
};

struct Pose {
  size_t begin = 0, end = 0;  // sample indices [begin, end)
  double t_begin_s = 0.0, t_end_s = 0.0;
  Vec3 f_mean_mps2 = Vec3::Zero();
  Mat3 f_mean_cov = Mat3::Zero();  // covariance of the mean: sample covariance / n
  Vec3 w_mean_rad_s = Vec3::Zero();
  Mat3 w_mean_cov = Mat3::Zero();
  Mat3 w_sample_cov = Mat3::Zero();  // per-sample gyro scatter (white-noise level for integration weights)
  size_t samples() const { return end - begin; }
};

struct StaticDetection {
  double window_variance_init = 0.0;  // ||per-axis variance|| of the initial static period [(m/s^2)^2]
  double threshold_multiplier = 0.0;
  double threshold = 0.0;             // [(m/s^2)^2]
  std::vector<Pose> poses;            // in time order; the initial static period is the first pose
};

// Detects static poses with one threshold multiplier (> 0). Throws InputError when the initial static
// period is longer than the log or not quiet.
StaticDetection detect_static_poses(const ImuLog& log, const StaticDetectorOptions& opt);

// Mean and covariance of the mean of samples [begin, end).
Pose make_pose(const ImuLog& log, size_t begin, size_t end);

}  // namespace ldv::calib
