#include "estimator/update/zupt.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "estimator/update/updater.hpp"

namespace ldv::est {
namespace {
// A continuing ZUPT whose innovation exceeds the 95 % chi-square point (3 dof) is taken as motion:
// skipping one at a real stop costs nothing (the next comes a period later), applying one while the
// vehicle creeps off costs meters.
constexpr double kZuptMovingNis = 7.81;
// How far the speed gate of a ZUPT may open with the filter's velocity uncertainty [m/s].
constexpr double kZuptSpeedAllowance_mps = 0.7;

// The ZUPT policy. Only without recent GNSS: with RTK it adds nothing, and the detector cannot tell a
// smooth start from rest (|f| ~ g) from standing still; the gate catches the rest.
class ZuptUpdater final : public Updater {
 public:
  const char* name() const override { return "zupt"; }
  std::unique_ptr<Updater> clone() const override { return std::make_unique<ZuptUpdater>(*this); }
  bool due(const AidContext& c) const override {
    const ZuptOptions& z = c.options.zupt;
    // The filter's own speed must be small, allowing for its uncertainty (a MEMS IMU seconds into an
    // outage is already off by tenths of m/s at a real stop), but never beyond speed_max + 0.7 m/s:
    // a smooth crawl looks static to the detector, and a ZUPT there would zero a real speed.
    const double sigma_v_h = std::sqrt(std::max(0.0, c.P(kVel, kVel) + c.P(kVel + 1, kVel + 1)));
    const double speed_gate = z.speed_max_mps + std::min(3.0 * sigma_v_h, kZuptSpeedAllowance_mps);
    return c.detector.is_static() && !c.gnss_recent && c.nav.v_n_mps.norm() < speed_gate &&
           c.f_n_smooth_mps2.head<2>().norm() < z.f_horizontal_max_mps2 && c.nav.t_s - last_zupt_t_s_ >= z.period_s;
  }
  void measure(const AidContext& c, std::vector<Measurement>& out) override {
    const ZuptOptions& z = c.options.zupt;
    Measurement m = zero_velocity_measurement(c.nav, c.layout, z.std_mps);
    // A ZUPT that continues a stop must agree with the velocity the previous ones left: the detector
    // cannot see a smooth start (|f| ~ g, a small horizontal force at first), and zeroing the 2-3
    // cm/s the vehicle then already has, with a 2 cm/s std, corrupts the velocity and tilt for the
    // rest of an outage (meters after a minute). The first ZUPT of a stop goes to the usual gate.
    const bool continuing = c.nav.t_s - last_zupt_t_s_ < 2.0 * z.period_s;
    const Mat3 s_zupt = c.P.block<3, 3>(kVel, kVel) + m.R;
    const Vec3 y = m.y;
    const double nis = y.dot(s_zupt.ldlt().solve(y));
    last_zupt_t_s_ = c.nav.t_s;
    if (continuing && nis > kZuptMovingNis) {
      ++c.faults.zupts_skipped_moving;
      return;
    }
    ++c.faults.zupts_applied;
    out.push_back(std::move(m));
  }

 private:
  double last_zupt_t_s_ = -1e300;
};
}  // namespace

std::unique_ptr<Updater> make_zupt_updater(const FilterOptions&) { return std::make_unique<ZuptUpdater>(); }

Measurement zero_velocity_measurement(const NavState& s, const StateLayout& layout, double std_mps) {
  Measurement m(sensors::kZeroVelocity, 3, layout.size());
  m.y = s.v_n_mps;
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
  const double sigma_f = std::max(vrw_ / std::sqrt(dt_s), f_scatter_at_rest_), sigma_w = arw_ / std::sqrt(dt_s);
  static_ = std::sqrt(var_f) < f_std_ + 2.0 * sigma_f && (sum_w_ / n).norm() < w_max_ + 4.0 * sigma_w / std::sqrt(n);
  return static_;
}

}  // namespace ldv::est
