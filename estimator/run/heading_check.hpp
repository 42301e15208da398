#pragma once
// Does the navigated heading still hold? An independent check of a running filter (NavSession's failed-
// alignment detection): the horizontal velocity change the IMU senses, rotated to the navigation frame with
// the filter's attitude, against the one the GNSS track shows. A heading wrong by d_psi rotates the first
// by d_psi against the second; the filter's own innovations cannot be trusted to show it, because an adapted
// IMU noise (FilterOptions::adapt_imu_noise) lets a filter with a heading 150 deg off follow the fixes at a
// NIS of 2. Velocity changes from chords of fixes at least kMinInterval_s apart (decimated: at 5 Hz the
// chord noise of RTK alone would swamp the accelerations), paired with the IMU's over the same spans.
#include <deque>
#include <optional>

#include "common/formats/nav_types.hpp"

namespace ldv::est {

class HeadingCheck {
 public:
  static constexpr double kMinInterval_s = 0.9;
  // How far the sizes of the IMU's and the GNSS's velocity change may differ beyond the chord noise (an IMU
  // latency of 0.3 s under 1 m/s^2 of changing acceleration, a bias of 0.1 m/s^2 over 1 s).
  static constexpr double kSizeTolerance_mps = 0.3;
  explicit HeadingCheck(double window_s = 20.0) : window_s_(window_s) {}
  // The IMU's velocity increment rotated to NED with the navigated attitude (gravity and Coriolis left out:
  // only horizontal components are used, where they are second order), over the sample ending at t_s.
  void add_imu(const Vec3& dv_n_mps) { dv_since_fix_ += dv_n_mps.head<2>(); }
  // A GNSS fix, in time order, between the IMU samples it falls between.
  void add_fix(const GnssFix& fix);
  // The rotation from the GNSS's velocity changes to the IMU's over the window [rad] (~ the navigated heading
  // minus the true one: the correction is a turn by minus this), when
  // the window's velocity changes stand out of the chord noise by a factor of 5; else none.
  std::optional<double> heading_misfit_rad() const { return misfit_rad_; }
  void clear();

 private:
  struct Pair {
    double t_s;
    Eigen::Vector2d dv_imu_mps, dv_gnss_mps;
    double gnss_std_mps;
  };
  double window_s_;
  Eigen::Vector2d dv_since_fix_ = Eigen::Vector2d::Zero();  // IMU since the last kept fix
  std::optional<GnssFix> last_fix_;
  std::optional<Eigen::Vector2d> last_chord_mps_, last_dv_imu_mps_;  // over the interval ending at last_fix_
  double last_chord_std_mps_ = 0.0;
  std::deque<Pair> pairs_;
  std::optional<double> misfit_rad_;  // of pairs_, refreshed when they change (asked after every IMU sample)
  std::optional<double> fit_pairs() const;
};

}  // namespace ldv::est
