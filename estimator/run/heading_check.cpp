#include "estimator/run/heading_check.hpp"

#include <cmath>

#include "common/geo/earth_model.hpp"

namespace ldv::est {

void HeadingCheck::clear() { *this = HeadingCheck(window_s_); }

void HeadingCheck::add_fix(const GnssFix& fix) {
  if (last_fix_ && fix.t_s - last_fix_->t_s < kMinInterval_s) return;  // decimated: the IMU sum runs on
  if (!last_fix_ || fix.t_s - last_fix_->t_s > 3.0) {                  // a gap: start again
    last_fix_ = fix;
    last_chord_mps_.reset();
    dv_since_fix_.setZero();
    return;
  }
  const double T = fix.t_s - last_fix_->t_s;
  const Eigen::Vector2d chord = earth::ned_between(last_fix_->pos, fix.pos).head<2>() / T;
  const double pos_std_m =
      std::max(0.01, std::max(fix.pos_std_ned_m.head<2>().maxCoeff(), last_fix_->pos_std_ned_m.head<2>().maxCoeff()));
  const double chord_std = std::sqrt(2.0) * pos_std_m / T;
  const Eigen::Vector2d dv_imu = dv_since_fix_;
  if (last_chord_mps_) {
    // Chords hold at the middles of their intervals: the velocity change between them is the IMU's over the
    // second half of the one and the first half of the other.
    const Pair p{fix.t_s, 0.5 * (*last_dv_imu_mps_ + dv_imu), chord - *last_chord_mps_,
                 std::hypot(chord_std, last_chord_std_mps_)};
    // A heading error turns the IMU's velocity change but keeps its size: a pair whose sizes differ is a GNSS
    // outlier (a 2 m jump makes velocity changes of 2-4 m/s the IMU never felt), or a shock; left out.
    const double size_misfit = std::abs(p.dv_gnss_mps.norm() - p.dv_imu_mps.norm());
    if (size_misfit <= 3.0 * p.gnss_std_mps + kSizeTolerance_mps) pairs_.push_back(p);
  }
  while (!pairs_.empty() && pairs_.front().t_s < fix.t_s - window_s_) pairs_.pop_front();
  misfit_rad_ = fit_pairs();
  last_fix_ = fix;
  last_chord_mps_ = chord;
  last_chord_std_mps_ = chord_std;
  last_dv_imu_mps_ = dv_imu;
  dv_since_fix_.setZero();
}

std::optional<double> HeadingCheck::fit_pairs() const {
  // Least squares rotation of g onto a: angle of sum (a . g, g x a); its noise from the chords' std.
  // The GNSS's velocity changes must be real accelerations (25x their noise in power: not a standstill's
  // chord noise against an IMU's vibration), and the fit must stand out of that noise.
  double dot = 0.0, cross = 0.0, noise_var = 0.0, gnss_power = 0.0, gnss_noise_power = 0.0;
  for (const Pair& p : pairs_) {
    dot += p.dv_imu_mps.dot(p.dv_gnss_mps);
    cross += p.dv_gnss_mps.x() * p.dv_imu_mps.y() - p.dv_gnss_mps.y() * p.dv_imu_mps.x();
    noise_var += p.dv_imu_mps.squaredNorm() * p.gnss_std_mps * p.gnss_std_mps;
    gnss_power += p.dv_gnss_mps.squaredNorm();
    gnss_noise_power += 2.0 * p.gnss_std_mps * p.gnss_std_mps;
  }
  if (pairs_.size() < 5 || gnss_power < 25.0 * gnss_noise_power || std::hypot(dot, cross) < 5.0 * std::sqrt(noise_var))
    return std::nullopt;
  return std::atan2(cross, dot);
}

}  // namespace ldv::est
