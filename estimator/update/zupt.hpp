#pragma once
// Zero-velocity update: when the static detector fires, the IMU velocity is zero (z = 0, y = v_hat); the
// updater holding its policy (when to trust the detector) is in zupt.cpp (registered as "zupt").
// StaticDetector: over a sliding window, the std of |f| and the norm of the mean angular rate are
// both small, against thresholds that include the sensor's own white noise.
#include <deque>

#include "estimator/ins/nav_state.hpp"
#include "estimator/update/measurement.hpp"

namespace ldv::est {

Measurement zero_velocity_measurement(const NavState& s, const StateLayout& layout, double std_mps);

class StaticDetector {
 public:
  // Static when std(|f|) < f_std + 2 sigma_f (or 2x the scatter at rest where larger) and |mean w| < omega_max + 4
  // sigma_w / sqrt(n) (the 99.9 % point of the norm of a 3-D mean of n noisy samples), sigma = white-noise density /
  // sqrt(dt) per sample. A MEMS gyro at rest reads about a degree per second in every sample; the
  // mean over the window (not the mean of the norms) and the noise term let it stop too.
  // f_scatter_at_rest_mps2: the std of |f| a standstill showed (InstalledImuNoise::f_norm_scatter_mps2), taken
  // for sigma_f where larger (an engine's harmonics at idle).
  StaticDetector(double window_s, double f_std_mps2, double omega_max_rad_s, double vrw_mps_per_sqrt_s = 0.0,
                 double arw_rad_per_sqrt_s = 0.0, double f_scatter_at_rest_mps2 = 0.0)
      : window_s_(window_s),
        f_std_(f_std_mps2),
        w_max_(omega_max_rad_s),
        vrw_(vrw_mps_per_sqrt_s),
        arw_(arw_rad_per_sqrt_s),
        f_scatter_at_rest_(f_scatter_at_rest_mps2) {}
  // One compensated sample (mean rate and specific force over dt); returns whether static now. The window
  // holds window_s / (mean dt) samples, re-sized as the rate goes, at most kMaxSamples: one odd interval
  // (two samples 3 ns apart) cannot size it.
  static constexpr size_t kMaxSamples = 1 << 16;
  bool add(double dt_s, const Vec3& omega_ib_b, const Vec3& f_b);
  bool is_static() const { return static_; }
  // Mean compensated angular rate over the window and the window's length [s] (ZARU).
  Vec3 mean_rate_rad_s() const {
    return window_.empty() ? Vec3::Zero() : Vec3(sum_w_ / static_cast<double>(window_.size()));
  }
  double window_length_s() const { return sum_dt_s_; }

 private:
  struct Sample {
    double f = 0.0;
    Vec3 w = Vec3::Zero();
    double dt_s = 0.0;
  };
  void reset();
  double window_s_, f_std_, w_max_, vrw_, arw_, f_scatter_at_rest_;
  std::deque<Sample> window_;
  double sum_f_ = 0, sum_f2_ = 0, sum_dt_s_ = 0;
  Vec3 sum_w_ = Vec3::Zero();
  bool static_ = false;
};

}  // namespace ldv::est
