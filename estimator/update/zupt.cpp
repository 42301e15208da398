#include "estimator/update/zupt.hpp"

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

bool StaticDetector::add(double dt_s, const Vec3& omega_ib_b, const Vec3& f_b) {
  if (ring_.empty()) {
    const size_t n = std::max<size_t>(2, static_cast<size_t>(std::lround(window_s_ / dt_s)));
    ring_.assign(n, Sample{});
  }
  const Sample in{f_b.norm(), omega_ib_b};
  if (count_ == ring_.size()) {
    const Sample& out = ring_[head_];
    sum_f_ -= out.f;
    sum_f2_ -= out.f * out.f;
    sum_w_ -= out.w;
  } else {
    ++count_;
  }
  ring_[head_] = in;
  head_ = (head_ + 1) % ring_.size();
  sum_f_ += in.f;
  sum_f2_ += in.f * in.f;
  sum_w_ += in.w;
  if (count_ < ring_.size() || !(dt_s > 0.0)) return static_ = false;
  const double n = static_cast<double>(count_);
  const double mean_f = sum_f_ / n;
  const double var_f = std::max(0.0, sum_f2_ / n - mean_f * mean_f);
  const double sigma_f = vrw_ / std::sqrt(dt_s), sigma_w = arw_ / std::sqrt(dt_s);
  static_ = std::sqrt(var_f) < f_std_ + 2.0 * sigma_f && (sum_w_ / n).norm() < w_max_ + 4.0 * sigma_w / std::sqrt(n);
  return static_;
}

}  // namespace ldv::est
