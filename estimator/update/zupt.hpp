#pragma once
// Zero-velocity update: when the static detector fires, the IMU velocity is zero (z = 0, y = v_hat).
// StaticDetector: over a sliding window, the std of |f| and the mean of |w| are both small.
#include <vector>

#include "estimator/ins/nav_state.hpp"
#include "estimator/update/measurement.hpp"

namespace ldv::est {

Measurement zero_velocity_measurement(const NavState& s, const StateLayout& layout, double std_mps);

class StaticDetector {
 public:
  StaticDetector(double window_s, double f_std_mps2, double omega_max_rad_s)
      : window_s_(window_s), f_std_(f_std_mps2), w_max_(omega_max_rad_s) {}
  // One compensated sample (mean rate and specific force over dt); returns whether static now.
  bool add(double dt_s, const Vec3& omega_ib_b, const Vec3& f_b);
  bool is_static() const { return static_; }

 private:
  struct Sample {
    double f, w;
  };
  double window_s_, f_std_, w_max_;
  std::vector<Sample> ring_;
  size_t head_ = 0, count_ = 0;
  double sum_f_ = 0, sum_f2_ = 0, sum_w_ = 0;
  bool static_ = false;
};

}  // namespace ldv::est
