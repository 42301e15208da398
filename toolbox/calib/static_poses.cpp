#include "toolbox/calib/static_poses.hpp"

#include <cmath>

#include "common/io/input_error.hpp"

namespace ldv::calib {

namespace {

// Per-axis variance of samples [b, e) from running sums (shifted by the first sample so the sums of squares
// do not lose precision on raw-count offsets).
struct RunningMoments {
  std::vector<Vec3> s1, s2;
  Vec3 shift;
  explicit RunningMoments(const std::vector<Vec3>& x) : s1(x.size() + 1, Vec3::Zero()), s2(x.size() + 1, Vec3::Zero()) {
    shift = x.empty() ? Vec3::Zero() : x.front();
    for (size_t i = 0; i < x.size(); ++i) {
      const Vec3 d = x[i] - shift;
      s1[i + 1] = s1[i] + d;
      s2[i + 1] = s2[i] + d.cwiseProduct(d);
    }
  }
  Vec3 variance(size_t b, size_t e) const {
    const double n = static_cast<double>(e - b);
    const Vec3 m = (s1[e] - s1[b]) / n;
    return ((s2[e] - s2[b]) / n - m.cwiseProduct(m)).cwiseMax(0.0);
  }
};

void mean_and_cov(const std::vector<Vec3>& x, size_t b, size_t e, Vec3& mean, Mat3& cov) {
  const double n = static_cast<double>(e - b);
  mean.setZero();
  for (size_t i = b; i < e; ++i) mean += x[i];
  mean /= n;
  cov.setZero();
  for (size_t i = b; i < e; ++i) cov += (x[i] - mean) * (x[i] - mean).transpose();
  cov /= std::max(1.0, n - 1.0);
}

}  // namespace

Pose make_pose(const ImuLog& log, size_t begin, size_t end) {
  Pose p;
  p.begin = begin;
  p.end = end;
  p.t_begin_s = log.t_s[begin];
  p.t_end_s = log.t_s[end - 1];
  const double n = static_cast<double>(end - begin);
  Mat3 cov;
  mean_and_cov(log.f_mps2, begin, end, p.f_mean_mps2, cov);
  p.f_mean_cov = cov / n;
  if (log.has_gyro()) {
    mean_and_cov(log.w_rad_s, begin, end, p.w_mean_rad_s, p.w_sample_cov);
    p.w_mean_cov = p.w_sample_cov / n;
  }
  return p;
}

StaticDetection detect_static_poses(const ImuLog& log, const StaticDetectorOptions& opt) {
  const size_t n = log.size();
  const size_t n_init = static_cast<size_t>(std::llround(opt.init_static_s / log.dt_s));
  size_t half = static_cast<size_t>(std::llround(0.5 * opt.window_s / log.dt_s));
  half = std::max<size_t>(half, 5);
  if (n_init < 2 * half + 1 || n_init > n)
    throw InputError(log.source, 0, "initial static period of " + std::to_string(opt.init_static_s) +
                                        " s does not fit the log (" + std::to_string(n * log.dt_s) +
                                        " s) or is shorter than the variance window");
  if (!(opt.threshold_multiplier > 0.0)) throw InputError(log.source, 0, "threshold multiplier must be positive");
  const RunningMoments moments(log.f_mps2);
  StaticDetection det;
  det.window_variance_init = moments.variance(0, n_init).norm();
  if (!(det.window_variance_init > 0.0))
    throw InputError(log.source, 0, "accelerometer constant over the initial static period (no noise): "
                                    "cannot set a detection threshold");
  det.threshold_multiplier = opt.threshold_multiplier;
  det.threshold = opt.threshold_multiplier * det.window_variance_init;
  const size_t min_len = static_cast<size_t>(std::ceil(opt.min_pose_s / log.dt_s));
  size_t start = 0;
  bool in_static = false;
  auto close = [&](size_t end) {
    if (end - start >= min_len) det.poses.push_back(make_pose(log, start, end));
  };
  for (size_t i = half; i + half < n; ++i) {
    const bool quiet = moments.variance(i - half, i + half + 1).norm() < det.threshold;
    if (quiet && !in_static) {
      start = i;
      in_static = true;
    } else if (!quiet && in_static) {
      close(i);
      in_static = false;
    }
  }
  if (in_static) close(n - half);
  return det;
}

}  // namespace ldv::calib
