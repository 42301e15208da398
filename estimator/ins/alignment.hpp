#pragma once
// Alignment without truth (DESIGN.md section 2):
//  1. coarse levelling from the mean specific force while static, for any mounting (upside down too:
//     roll and pitch come from atan2 of the full gravity direction);
//  2. heading by gyrocompassing from the mean angular rate while static, when the gyros resolve Earth
//     rate well enough (theory: sigma_yaw = sigma_w_east / (Omega cos(lat)));
//  3. otherwise heading = course over ground from GNSS velocity once moving faster than speed_min_mps
//     (the body x axis is assumed to point along the velocity), with the attitude carried from the
//     levelling by integrating the gyros in the meantime.
// A gyro turn-on bias far above Earth rate (a MEMS IMU: tenths of a degree per second) shows as the
// mean rate of the static start: it is taken out of the carried attitude and reported
// (gyro_bias_seed), for the filter to take out of the increments too (set_input_gyro_bias). Only the seconds up to
// the last fix the GNSS placed at the resting position feed it: a car creeping off in a slow turn reads like a bias
// to the IMU (a 1 deg/s yaw fails the detector, and the held samples of an idling engine must count as rest) until
// two chords call it motion, while its fixes leave the rest within a second. Without static_min_s of rest the bias
// starts at zero with its prior, and the start says so.
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "common/formats/nav_types.hpp"
#include "estimator/ins/nav_state.hpp"
#include "estimator/update/zupt.hpp"

namespace ldv::est {

// Roll and pitch [rad] from the mean specific force f_b [m/s^2] of a static IMU.
Vec3 level_from_specific_force(const Vec3& f_b_mps2);
// Yaw [rad] from the mean static angular rate w_b [rad/s] given roll and pitch.
double gyrocompass_yaw(double roll_rad, double pitch_rad, const Vec3& omega_ib_b_rad_s);
// Theoretical 1-sigma of gyrocompass yaw for this gyro bias [rad/s], white noise [rad/sqrt(s)] and averaging time.
double gyrocompass_yaw_std(double lat_rad, double gyro_bias_rad_s, double arw_rad_per_sqrt_s, double averaging_s);

struct AlignmentOptions {
  double gyro_bias_std_rad_s = 1.0 * kDegToRad / 3600.0;
  double arw_rad_per_sqrt_s = 0.003 * kDegToRad;
  double vrw_mps_per_sqrt_s = 0.0;  // with arw: the static detector allows for the sensor's noise
  double accel_bias_std_mps2 = 1e-3 * 9.8;
  double static_min_s = 5.0;        // levelling needs this much static data
  double gyrocompass_min_s = 60.0;  // and gyrocompassing this much
  double gyrocompass_max_yaw_std_rad = 3.0 * kDegToRad;  // use it only when theory promises this
  double speed_min_mps = 2.0;       // course over ground usable above this
  double cog_yaw_std_rad = 3.0 * kDegToRad;
  // Mounting unknown (hand-held): the course gives the heading of the motion, not of the body x axis.
  // With N > 1, run_navigation tries N body headings 360/N deg apart for course_trial_s of aided
  // navigation and keeps the one whose GNSS position innovations are smallest (sum of NIS, each fix's capped
  // at the gate).
  int course_hypotheses = 1;
  double course_trial_s = 8.0;
  // A window whose accelerations do not tell the headings apart (a straight at constant speed) is doubled up to
  // this (NavSession::run_heading_trial).
  double course_trial_max_s = 64.0;
  Vec3 lever_arm_b_m = Vec3::Zero();
  double time_offset_s = 0.0;  // GNSS tag minus IMU tag: the fix labelled t was taken at IMU time t - time_offset
  // The GNSS has a say (off in KF-GINS-compatible runs, FilterOptions::robust_update):
  //  - standstill: an IMU vibrating in a car at rest (engine, 10x its datasheet noise) never looks static to
  //    a detector tuned to the datasheet; motion is taken from the IMU only once the GNSS shows it too (two
  //    consecutive chords that agree), or when there has been no fix for kGnssSilent_s;
  //  - course: from two consecutive chords that agree in direction and speed, extrapolated to the fix's epoch
  //    (one outlying fix while standing gives one fast chord out and one back: no course from it).
  bool gnss_checks = false;
  bool use_fix_velocity = true;  // the fixes' own velocity for the course (off when the velocity check refused it)
};

class Aligner {
 public:
  explicit Aligner(AlignmentOptions o);
  // A redo while moving (a failed alignment, NavSession): the level of `q_b_n` (its roll and pitch, with
  // this std) is kept, the course is taken again from the GNSS, and the turn-on gyro bias stays as seeded.
  void resume_levelled(const Quat& q_b_n, const Vec3& level_std_rad, const std::optional<Vec3>& gyro_bias_seed);
  void add_imu(const ImuIncrement& raw);
  void add_gnss(const GnssFix& fix);
  bool aligned() const { return result_.has_value(); }
  const NavState& state() const { return result_->first; }
  const NavStd& std() const { return result_->second; }
  const std::string& method() const { return method_; }
  // The static start's mean rate when it is a turn-on bias (> 10 x Earth rate, from >= static_min_s at rest).
  const std::optional<Vec3>& gyro_bias_seed() const { return gyro_bias_seed_; }
  // Its 1-sigma per axis: the scatter of the seconds it was averaged over, over sqrt(their number). Seconds, not
  // samples: a sample's rate carries the angle quantization, which does not accumulate and averages out of the
  // mean; the scatter of 1 s means is the angle random walk's.
  const Vec3& gyro_bias_seed_std() const { return gyro_bias_seed_std_; }

 private:
  void level();
  void add_static(const ImuIncrement& raw);
  void carry_attitude(const ImuIncrement& raw);
  void hold_until_gnss_says(const ImuIncrement& raw);
  void release_held();  // motion confirmed: level from the whole standstill, carry the held samples' rotation
  // A chord between consecutive fixes that goes on in the previous chord's direction at a similar speed.
  bool chords_agree(const Vec3& previous_mps, const Vec3& chord_mps, double speed_min_mps) const;
  static constexpr double kGnssSilent_s = 3.0;
  static constexpr double kHoldMax_s = 3.0;
  AlignmentOptions o_;
  StaticDetector detector_;
  double t_s_ = 0.0;
  bool moving_seen_ = false;
  Vec3 sum_dv_ = Vec3::Zero(), sum_dtheta_ = Vec3::Zero();
  // The gyro's mean rate over each second of the static window (the turn-on bias and its sigma).
  Vec3 second_dtheta_ = Vec3::Zero();
  double second_dt_s_ = 0.0;
  struct StaticSecond {
    Vec3 rate_rad_s;
    double t_end_s;
  };
  std::vector<StaticSecond> static_seconds_;
  std::vector<Vec3> rest_second_rates() const;  // those before the GNSS showed the vehicle leave the rest
  // Seconds of the static start up to the last fix at the resting position (the seed needs static_min_s of them).
  double rest_s() const { return static_cast<double>(rest_second_rates().size()); }
  std::vector<Vec3> still_seconds() const;      // those without the seconds that turned
  // Where the GNSS placed the rest: the first fix, and the last fix within the fixes' noise of it before two in a row
  // left it (then rest_left_: the seconds after rest_end_t_s_ may have moved).
  void track_rest(const GnssFix& fix);
  std::optional<GnssFix> rest_fix_;
  double rest_end_t_s_ = 0.0;
  bool rest_out_once_ = false, rest_left_ = false;
  void seed_gyro_bias();  // at levelling: the static window's mean rate, when it is a turn-on bias
  double static_s_ = 0.0;
  bool levelled_ = false;
  double levelled_at_static_s_ = 0.0;  // the standstill the level and the seed are from
  Quat q_b_l_ = Quat::Identity();  // body to a levelled frame of arbitrary yaw, carried by the gyros
  Vec3 level_std_rad_ = Vec3::Zero();
  std::optional<GnssFix> prev_fix_;
  std::optional<Vec3> prev_chord_mps_;  // the chord that ended at prev_fix_
  bool gnss_moving_ = false;            // the last two chords agree above a walking pace
  double first_imu_t_s_ = -1e300, last_fix_t_s_ = -1e300;
  std::deque<ImuIncrement> held_;  // moving by the IMU, not yet by the GNSS (AlignmentOptions::gnss_checks)
  bool just_moved_ = false;        // the held samples, this one included, were just carried
  std::optional<std::pair<NavState, NavStd>> result_;
  std::optional<Vec3> gyro_bias_seed_;
  Vec3 gyro_bias_seed_std_ = Vec3::Zero();
  std::string method_;
};

}  // namespace ldv::est
