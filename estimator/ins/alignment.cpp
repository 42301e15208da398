#include "estimator/ins/alignment.hpp"

#include <algorithm>
#include <cmath>

#include "common/geo/earth_model.hpp"

namespace ldv::est {

Vec3 level_from_specific_force(const Vec3& f) {
  // Static: f_b = C_n_b (0, 0, -g) = g (sin p, -sin r cos p, -cos r cos p).
  const double roll = std::atan2(-f.y(), -f.z());
  const double pitch = std::atan2(f.x(), std::sqrt(f.y() * f.y() + f.z() * f.z()));
  return {roll, pitch, 0.0};
}

double gyrocompass_yaw(double roll, double pitch, const Vec3& w_b) {
  // Rotate the sensed Earth rate into the levelled frame (yaw 0): w_l = Rz(-yaw) w_ie_n, whose
  // horizontal part is Omega cos(lat) (cos yaw, -sin yaw).
  const Vec3 w_l = C_b_n_from_euler(Vec3(roll, pitch, 0.0)) * w_b;
  return std::atan2(-w_l.y(), w_l.x());
}

double gyrocompass_yaw_std(double lat, double bias, double arw, double T) {
  const double sigma_w = std::sqrt(bias * bias + arw * arw / T);
  return sigma_w / (earth::kOmegaIe_rad_s * std::cos(lat));
}

Aligner::Aligner(AlignmentOptions o)
    : o_(o), detector_(0.5, 0.05, 0.5 * kDegToRad, o.vrw_mps_per_sqrt_s, o.arw_rad_per_sqrt_s) {}

void Aligner::add_imu(const ImuIncrement& raw) {
  t_s_ = raw.t_s;
  if (first_imu_t_s_ < -1e299) first_imu_t_s_ = raw.t_s;
  const bool stat = detector_.add(raw.dt_s, raw.dtheta_b_rad / raw.dt_s, raw.dvel_b_mps / raw.dt_s);
  if (!moving_seen_) {
    // Accumulate from the start until the first motion (the detector needs one full window first).
    const bool window_full = static_s_ >= 0.6;
    if (o_.gnss_checks && window_full && (!stat || gnss_moving_)) {
      // Moving by the IMU, or by the GNSS while the IMU looks still (a smooth acceleration or cruise).
      hold_until_gnss_says(raw);
    } else if (window_full && !stat) {
      moving_seen_ = true;
    } else {
      for (const ImuIncrement& held : held_) add_static(held);  // the IMU stopped: it was a blip
      held_.clear();
      add_static(raw);
    }
  }
  if (!levelled_ && (moving_seen_ || static_s_ >= o_.static_min_s)) level();
  if (levelled_ && moving_seen_ && !just_moved_) carry_attitude(raw);
  just_moved_ = false;
}

void Aligner::resume_levelled(const Quat& q_b_n, const Vec3& level_std_rad, const std::optional<Vec3>& seed) {
  Vec3 rpy = euler_from_C_b_n(q_b_n.toRotationMatrix());
  rpy.z() = 0.0;  // the course decides the heading
  q_b_l_ = quat_from_euler(rpy);
  level_std_rad_ = Vec3(level_std_rad.x(), level_std_rad.y(), 0.0);
  gyro_bias_seed_ = seed;
  levelled_ = true;
  moving_seen_ = true;
  held_.clear();
}

void Aligner::add_static(const ImuIncrement& raw) {
  sum_dv_ += raw.dvel_b_mps;
  sum_dtheta_ += raw.dtheta_b_rad;
  static_s_ += raw.dt_s;
  second_dtheta_ += raw.dtheta_b_rad;
  second_dt_s_ += raw.dt_s;
  if (second_dt_s_ >= 1.0) {
    static_seconds_.push_back({second_dtheta_ / second_dt_s_, raw.t_s});
    second_dtheta_.setZero();
    second_dt_s_ = 0.0;
  }
}

void Aligner::carry_attitude(const ImuIncrement& raw) {
  const Vec3 dtheta = gyro_bias_seed_ ? Vec3(raw.dtheta_b_rad - *gyro_bias_seed_ * raw.dt_s) : raw.dtheta_b_rad;
  q_b_l_ = (q_b_l_ * quat_from_rotvec(dtheta)).normalized();
}

void Aligner::release_held() {
  moving_seen_ = true;
  level();  // again, from the whole standstill (an early levelling had its first static_min_s only)
  for (const ImuIncrement& held : held_) carry_attitude(held);
  held_.clear();
}

void Aligner::hold_until_gnss_says(const ImuIncrement& raw) {
  // The IMU says moving. An installed IMU vibrates above the datasheet noise the detector expects, so the
  // samples are held until the GNSS decides: motion (two chords that agree) -> the motion began with the
  // first held sample; no motion while fixes come -> the held samples older than kHoldMax_s were at rest.
  held_.push_back(raw);
  const bool gnss_silent = t_s_ - std::max(last_fix_t_s_, first_imu_t_s_) > kGnssSilent_s;
  if (gnss_moving_ || gnss_silent) {
    release_held();
    just_moved_ = true;  // this sample was the last of them
    return;
  }
  while (!held_.empty() && held_.front().t_s < t_s_ - kHoldMax_s) {
    add_static(held_.front());
    held_.pop_front();
  }
}

std::vector<Vec3> Aligner::rest_second_rates() const {
  std::vector<Vec3> rates;
  for (const StaticSecond& s : static_seconds_)
    if (!rest_left_ || s.t_end_s <= rest_end_t_s_) rates.push_back(s.rate_rad_s);
  return rates;
}

void Aligner::track_rest(const GnssFix& fix) {
  if (rest_left_ || moving_seen_) return;
  if (!rest_fix_) {
    rest_fix_ = fix;
    rest_end_t_s_ = fix.t_s;
    return;
  }
  // Beyond 3 sigma of two fixes' difference (at least 10 cm: a stated std is often optimistic, and a car that
  // pulls away covers it within a second); a single fix out is an outlier until the next one is out too.
  const double sigma_h_m = std::hypot(fix.pos_std_ned_m.x(), fix.pos_std_ned_m.y());
  const double out_m = std::max(0.1, 3.0 * std::sqrt(2.0) * sigma_h_m);
  if (earth::ned_between(rest_fix_->pos, fix.pos).head<2>().norm() <= out_m) {
    rest_end_t_s_ = fix.t_s;
    rest_out_once_ = false;
  } else if (rest_out_once_) {
    rest_left_ = true;
  } else {
    rest_out_once_ = true;
  }
}

std::vector<Vec3> Aligner::still_seconds() const {
  // A turn-on bias is constant; a turn on the spot (the GNSS shows no chord, the IMU's held samples are taken
  // for vibration) is a rate that comes and goes. Seconds whose mean rate leaves the median of all by more than
  // 4 robust sigma (1.4826 MAD, at least what the ARW makes of a second) on any axis were turning.
  const std::vector<Vec3> rates = rest_second_rates();
  if (rates.size() < 3) return rates;
  Vec3 median, spread;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> v;
    for (const Vec3& r : rates) v.push_back(r(axis));
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    median(axis) = *mid;
    for (double& x : v) x = std::abs(x - median(axis));
    std::nth_element(v.begin(), mid, v.end());
    spread(axis) = std::max(1.4826 * *mid, o_.arw_rad_per_sqrt_s);
  }
  std::vector<Vec3> still;
  for (const Vec3& r : rates)
    if (((r - median).cwiseAbs().array() <= 4.0 * spread.array()).all()) still.push_back(r);
  return still;
}

void Aligner::seed_gyro_bias() {
  gyro_bias_seed_.reset();  // levelled again from a longer standstill: that one decides
  gyro_bias_seed_std_.setZero();
  const std::vector<Vec3> still = still_seconds();
  // Less than static_min_s of rest (a drive that starts moving): the bias starts at zero with its prior.
  if (static_cast<double>(still.size()) < o_.static_min_s) return;
  Vec3 sum = Vec3::Zero(), sum_sq = Vec3::Zero();
  for (const Vec3& r : still) sum += r, sum_sq += r.cwiseAbs2();
  const double n = static_cast<double>(still.size());
  const Vec3 mean_rate = sum / n;
  if (mean_rate.norm() <= 10.0 * earth::kOmegaIe_rad_s) return;
  gyro_bias_seed_ = mean_rate;
  gyro_bias_seed_std_ = ((sum_sq / n - (sum / n).cwiseAbs2()).cwiseMax(0.0) / (n - 1.0)).cwiseSqrt();
}

void Aligner::level() {
  const Vec3 rpy = level_from_specific_force(sum_dv_ / std::max(static_s_, 1e-9));
  q_b_l_ = quat_from_euler(rpy);
  // Levelling error = accelerometer bias / g (plus the gyro-carried drift, small over seconds).
  const double s = std::max(o_.accel_bias_std_mps2 / 9.8, 0.05 * kDegToRad);
  level_std_rad_ = Vec3(s, s, 0.0);
  if (static_s_ < 1.0) level_std_rad_ = Vec3::Constant(5.0 * kDegToRad);  // no static start: rough
  // At rest the gyros read Earth rate plus their bias. Far above Earth rate the mean is the bias
  // (Earth rate's share, whatever the heading, stays under a tenth of it); a tactical gyro's mean is
  // Earth rate and stays in the data (gyrocompassing reads it).
  seed_gyro_bias();
  levelled_ = true;
  levelled_at_static_s_ = static_s_;
}

bool Aligner::chords_agree(const Vec3& previous, const Vec3& chord, double speed_min) const {
  const double a = previous.head<2>().norm(), b = chord.head<2>().norm();
  if (a < speed_min || b < speed_min) return false;
  const double cos_angle = previous.head<2>().dot(chord.head<2>()) / (a * b);
  return cos_angle > std::cos(30.0 * kDegToRad) && b < 2.0 * a && a < 2.0 * b;
}

void Aligner::add_gnss(const GnssFix& fix) {
  // The chord from the previous fix (at most 1.5 s before; a longer gap says little about the course now).
  std::optional<Vec3> chord;
  if (prev_fix_ && fix.t_s - prev_fix_->t_s > 0.0 && fix.t_s - prev_fix_->t_s <= 1.5)
    chord = earth::ned_between(prev_fix_->pos, fix.pos) / (fix.t_s - prev_fix_->t_s);
  const std::optional<Vec3> chord_before = prev_chord_mps_;
  track_rest(fix);
  prev_fix_ = fix;
  prev_chord_mps_ = chord;
  last_fix_t_s_ = fix.t_s;
  constexpr double kWalkingPace_mps = 0.5;
  gnss_moving_ = chord && chord_before && chords_agree(*chord_before, *chord, kWalkingPace_mps);
  if (result_ || !levelled_) return;
  // Samples held for the GNSS to decide: motion now confirmed, the attitude is carried through them first.
  // Still held (no motion yet), only gyrocompassing may align (at rest they are vibration); a course would miss
  // their rotation.
  if (!held_.empty() && gnss_moving_) release_held();

  NavState s;
  s.t_s = t_s_;
  NavStd sd;
  sd.pos_ned_m = fix.pos_std_ned_m.cwiseMax(0.05) * 2.0;
  const Vec3 rpy_l = euler_from_C_b_n(q_b_l_.toRotationMatrix());
  // Gyrocompassing while still static, when the gyros can do it.
  const double yaw_std = gyrocompass_yaw_std(fix.pos.lat_rad, o_.gyro_bias_std_rad_s, o_.arw_rad_per_sqrt_s, static_s_);
  if (!moving_seen_ && static_s_ >= o_.gyrocompass_min_s && yaw_std <= o_.gyrocompass_max_yaw_std_rad) {
    const Vec3 rpy(rpy_l.x(), rpy_l.y(), gyrocompass_yaw(rpy_l.x(), rpy_l.y(), sum_dtheta_ / static_s_));
    s.q_b_n = quat_from_euler(rpy);
    s.v_n_mps.setZero();
    sd.vel_n_mps = Vec3::Constant(0.05);
    sd.att_rad = Vec3(level_std_rad_.x(), level_std_rad_.y(), 2.0 * yaw_std);
    method_ = "levelling + gyrocompassing";
  } else {
    if (!held_.empty()) return;
    // Still at rest by the IMU when the GNSS course comes (a smooth start): levelled after static_min_s, the
    // standstill went on; the level and the turn-on bias from all of it (5 s of a 60 s standstill left a 3DM-GX2's
    // bias 0.022 deg/s uncertain, all of it 0.0065).
    if (!moving_seen_ && static_s_ > levelled_at_static_s_) level();
    // Course over ground, from the fix's velocity or from consecutive positions.
    Vec3 v_n;
    double v_std = 0.0;
    if (fix.has_velocity && o_.use_fix_velocity) {
      v_n = fix.vel_n_mps;
      v_std = fix.vel_std_n_mps.maxCoeff();
    } else if (chord && !o_.gnss_checks) {
      v_n = *chord;
      v_std = 0.5;  // difference over up to 1 s while accelerating
    } else if (chord && chord_before && chords_agree(*chord_before, *chord, o_.speed_min_mps)) {
      // The chord's velocity holds half an interval before the fix: carried to the fix's epoch with the
      // change from the chord before.
      v_n = *chord + 0.5 * (*chord - *chord_before);
      v_std = 0.25;
    } else {
      return;
    }
    if (v_n.head<2>().norm() < o_.speed_min_mps) return;
    const double cog = std::atan2(v_n.y(), v_n.x());
    const Vec3 x_l = q_b_l_ * Vec3::UnitX();
    const double heading_l = std::atan2(x_l.y(), x_l.x());
    s.q_b_n = (Quat(Eigen::AngleAxisd(cog - heading_l, Vec3::UnitZ())) * q_b_l_).normalized();
    s.v_n_mps = v_n;
    sd.vel_n_mps = Vec3::Constant(std::max(v_std, 0.05) * 2.0);
    sd.att_rad = Vec3(level_std_rad_.x() + 0.5 * kDegToRad, level_std_rad_.y() + 0.5 * kDegToRad, o_.cog_yaw_std_rad);
    method_ = "levelling + GNSS course over ground";
    if (rest_s() < o_.static_min_s)
      method_ += "; no standstill at the start: the gyro bias starts at zero with its prior";
  }
  // The fix is at the antenna: move to the IMU, and carried from the IMU time the fix was taken at to this sample's
  // (a 60 ms IMU lag is 0.6 m along the track at 10 m/s).
  const double taken_at_s = fix.t_s - o_.time_offset_s;
  s.pos = earth::offset_ned(fix.pos, -(s.C_b_n() * o_.lever_arm_b_m) + s.v_n_mps * (s.t_s - taken_at_s));
  result_ = std::make_pair(s, sd);
}

}  // namespace ldv::est
