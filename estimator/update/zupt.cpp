#include "estimator/update/zupt.hpp"

#include <algorithm>
#include <cmath>

namespace ldv::est {

Measurement zero_velocity_measurement(const NavState& s, const StateLayout& layout, double std_mps) {
  Measurement m;
  m.kind = MeasurementKind::kZeroVelocity;
  m.y = s.v_n_mps;
  m.H = Mat3X::Zero(3, layout.size());
  m.H.middleCols<3>(kVel).setIdentity();
  m.R = Mat3::Identity() * std_mps * std_mps;
  return m;
}

void StaticDetector::reset() {
  window_.clear();
  sum_f_ = sum_f2_ = sum_dt_s_ = 0.0;
  sum_w_.setZero();
  static_ = false;
}

bool StaticDetector::add(double dt_s, const Vec3& omega_ib_b, const Vec3& f_b) {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s) || !omega_ib_b.allFinite() || !f_b.allFinite()) {
    reset();  // a hole or a bad sample: start the window again
    return false;
  }
  const Sample in{f_b.norm(), omega_ib_b, dt_s};
  window_.push_back(in);
  sum_f_ += in.f;
  sum_f2_ += in.f * in.f;
  sum_w_ += in.w;
  sum_dt_s_ += in.dt_s;
  const double mean_dt_s = sum_dt_s_ / static_cast<double>(window_.size());
  const size_t target = std::min(kMaxSamples, std::max<size_t>(2, static_cast<size_t>(std::lround(window_s_ / mean_dt_s))));
  while (window_.size() > target) {
    const Sample& out = window_.front();
    sum_f_ -= out.f;
    sum_f2_ -= out.f * out.f;
    sum_w_ -= out.w;
    sum_dt_s_ -= out.dt_s;
    window_.pop_front();
  }
  if (window_.size() < target) return static_ = false;
  const double n = static_cast<double>(window_.size());
  const double mean_f = sum_f_ / n;
  const double var_f = std::max(0.0, sum_f2_ / n - mean_f * mean_f);
  const double sigma_f = vrw_ / std::sqrt(dt_s), sigma_w = arw_ / std::sqrt(dt_s);
  static_ = std::sqrt(var_f) < f_std_ + 2.0 * sigma_f && (sum_w_ / n).norm() < w_max_ + 4.0 * sigma_w / std::sqrt(n);
  return static_;
}

}  // namespace ldv::est
