#include "services/fusion/fusion_engine.hpp"

#include <algorithm>
#include <cmath>

#include "common/geo/earth_model.hpp"

namespace ldv {

FusionEngine::FusionEngine(const est::FilterOptions& fo, const est::AlignmentOptions& ao, double align_wait_s)
    : filter_(fo),
      aligner_(ao),
      speed_min_mps_(ao.speed_min_mps),
      cog_yaw_std_rad_(ao.cog_yaw_std_rad),
      align_wait_s_(align_wait_s) {}

void FusionEngine::on_imu(const ImuIncrement& imu, int week, double arrival_s, std::vector<FusionOutput>& out) {
  if (filter_.initialized()) {
    navigate(imu, week, out);
    return;
  }
  if (warm_ && try_warm_start(imu)) {
    navigate(imu, week, out);
    return;
  }
  imu_queue_.push_back({imu, week, arrival_s});
  drain_alignment_queue(arrival_s, out);
}

void FusionEngine::on_gnss(const GnssFix& fix, double arrival_s) {
  if (filter_.initialized()) {
    filter_.add_gnss(fix);
    return;
  }
  if (warm_ && !warm_fix_) warm_fix_ = fix;
  // Keep time order for the aligner (a receiver never reorders, but a replayed log might).
  auto it = std::upper_bound(gnss_queue_.begin(), gnss_queue_.end(), fix.t_s,
                             [](double t, const GnssFix& g) { return t < g.t_s; });
  gnss_queue_.insert(it, fix);
  latest_gnss_t_s_ = std::max(latest_gnss_t_s_, fix.t_s);
}

void FusionEngine::on_idle(double now_s, std::vector<FusionOutput>& out) {
  if (!filter_.initialized()) drain_alignment_queue(now_s, out);
}

void FusionEngine::drain_alignment_queue(double now_s, std::vector<FusionOutput>& out) {
  while (!imu_queue_.empty() && !filter_.initialized()) {
    const QueuedImu& head = imu_queue_.front();
    // The offline order: an IMU sample, then every fix up to its epoch. Wait until a fix beyond this
    // epoch has arrived, so none that belongs before it is still in flight.
    const bool gnss_beyond = latest_gnss_t_s_ > head.imu.t_s;
    if (!gnss_beyond && now_s - head.arrival_s < align_wait_s_) return;
    aligner_.add_imu(head.imu);
    while (!gnss_queue_.empty() && gnss_queue_.front().t_s <= head.imu.t_s) {
      aligner_.add_gnss(gnss_queue_.front());
      gnss_queue_.pop_front();
    }
    imu_queue_.pop_front();
    if (aligner_.aligned()) {
      start_navigation(aligner_.state(), aligner_.std(), aligner_.method());
      // A turn-on bias the static start showed, taken out as ldv nav does (not kept by a warm start).
      filter_.set_input_gyro_bias(aligner_.gyro_bias_seed().value_or(Vec3::Zero()));
      // As offline: fixes up to the initial epoch are not used, the rest go to the filter.
      for (const GnssFix& g : gnss_queue_)
        if (g.t_s > filter_.state().t_s) filter_.add_gnss(g);
      gnss_queue_.clear();
      std::deque<QueuedImu> rest;
      rest.swap(imu_queue_);
      for (const auto& q : rest) navigate(q.imu, q.week, out);
    }
  }
}

bool FusionEngine::try_warm_start(const ImuIncrement& imu) {
  if (!warm_fix_) return false;
  const GnssFix fix = *warm_fix_;
  const WarmState w = *warm_;
  warm_.reset();
  if (imu.t_s < fix.t_s || imu.t_s - fix.t_s > 1.0) return false;
  est::NavState s = w.state;
  s.t_s = imu.t_s - imu.dt_s;
  const Vec3 v_n = fix.has_velocity ? fix.vel_n_mps : w.state.v_n_mps;
  const Vec3& v_saved = w.state.v_n_mps;
  const bool course_turned =
      fix.has_velocity && v_n.head<2>().norm() > speed_min_mps_ && v_saved.head<2>().norm() > speed_min_mps_;
  if (course_turned) {
    const double turn = std::remainder(std::atan2(v_n.y(), v_n.x()) - std::atan2(v_saved.y(), v_saved.x()), 2.0 * M_PI);
    s.q_b_n = (Quat(Eigen::AngleAxisd(turn, Vec3::UnitZ())) * s.q_b_n).normalized();
  }
  // Antenna fix -> IMU centre, then carried to the start of this sample with the velocity.
  const Vec3 lever_n = s.C_b_n() * filter_.options().lever_arm.init;
  s.pos = earth::offset_ned(fix.pos, -lever_n + v_n * (s.t_s - fix.t_s));
  s.v_n_mps = v_n;
  est::NavStd sd;
  sd.pos_ned_m = 2.0 * fix.pos_std_ned_m + Vec3::Constant(0.05);
  sd.vel_n_mps = fix.has_velocity ? Vec3(2.0 * fix.vel_std_n_mps + Vec3::Constant(0.05)) : Vec3::Constant(2.0);
  // Attitude kept through a restart gap of a few seconds: heading may have turned meanwhile. Moving
  // then and now: the saved attitude turned by the change of the course over ground.
  sd.att_rad = w.std.att_rad + Vec3(0.5, 0.5, 5.0) * kDegToRad;
  if (course_turned) sd.att_rad.z() = w.std.att_rad.z() + cog_yaw_std_rad_;
  start_navigation(s, sd, "warm start");
  return true;
}

void FusionEngine::start_navigation(const est::NavState& s, const est::NavStd& sd, const std::string& how) {
  filter_.initialize(s, sd);
  initialisation_ = how;
}

void FusionEngine::navigate(const ImuIncrement& imu, int week, std::vector<FusionOutput>& out) {
  filter_.add_imu(imu);
  FusionOutput o;
  o.gps_week = week;
  o.state = filter_.state();
  o.std = filter_.nav_std();
  o.status = filter_.status();
  o.mode = (o.status & est::kStatusGnssOutage) ? FusionMode::kFreeInertial : FusionMode::kAided;
  out.push_back(o);
}

}  // namespace ldv
