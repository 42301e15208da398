#include "services/fusion/fusion_engine.hpp"

#include "common/bus/message_conversions.hpp"
#include "estimator/run/run_navigation.hpp"
#include "estimator/update/odometer.hpp"

namespace ldv {

est::SessionOptions live_session_options(const KfGinsConfig& cfg, const est::FilterOptions& filter,
                                         const est::AlignmentOptions* alignment) {
  est::SessionOptions so = est::session_options_from(cfg, filter, alignment);
  const bool shift_given = est::ldv_number(cfg, "imu_time_shift_s", 0.0) != 0.0;
  if (est::imu_latency_wanted(cfg, filter, "", shift_given)) so.imu_latency_window = est::ImuLatencyWindowOptions{};
  return so;
}

FusionEngine::FusionEngine(const est::SessionOptions& so)
    : options_(so), run_(std::make_unique<Run>(so, [this](const est::NavFilter& f, int week) { on_epoch(f, week); })) {}

void FusionEngine::on_epoch(const est::NavFilter& f, int reference_week) {
  if (epoch_observer_) epoch_observer_(f, reference_week);
  if (!out_) return;
  FusionOutput o;
  const GpsTime t = time_.week_time(f.gnss_time_s());
  o.gps_week = t.week;
  o.gps_sow_s = t.sow_s;
  o.state = f.state();
  o.std = f.nav_std();
  o.status = f.status();
  o.mode = (o.status & est::kStatusGnssOutage) ? FusionMode::kFreeInertial : FusionMode::kAided;
  out_->push_back(o);
}

void FusionEngine::restart_on_new_time_line(double host_time_s) {
  const bool warm = navigating();
  const WarmState saved = warm ? warm_state(host_time_s) : WarmState{};
  run_ = std::make_unique<Run>(options_, [this](const est::NavFilter& f, int week) { on_epoch(f, week); });
  time_ = ContinuousGpsTime{};
  if (warm) set_warm_start(saved);
}

void FusionEngine::on_imu(const ImuIncrement& imu, int week, double arrival_s, std::vector<FusionOutput>& out) {
  ImuIncrement continuous = imu;
  continuous.t_s = time_.seconds(week, imu.t_s);
  out_ = &out;
  run_->session.add_imu(continuous, time_.reference_week(), arrival_s);
  out_ = nullptr;
}

void FusionEngine::on_gnss(const GnssFix& fix, int week, double arrival_s) {
  GnssFix continuous = fix;
  continuous.t_s = time_.seconds(week, fix.t_s);
  run_->session.add_gnss(continuous, arrival_s);
}

void FusionEngine::on_observation(est::ObservationPtr reading, double arrival_s, std::vector<FusionOutput>& out) {
  out_ = &out;
  run_->session.add_observation(std::move(reading), arrival_s);
  out_ = nullptr;
}

WarmState FusionEngine::warm_state(double host_time_s) const {
  const est::NavFilter& f = run_->filter;
  return {host_time_s, f.state(), f.nav_std(), f.options().input_gyro_bias_rad_s + f.error_model().gyro_bias_rad_s};
}

bool FusionEngine::wants_odometer() const { return run_->filter.options().aids.has("odometer"); }

void FusionEngine::on_wheel_speed(const ldv_lcm::wheel_speed_t& m, double arrival_s, std::vector<FusionOutput>& out) {
  if (!wants_odometer()) return;
  if (const auto v = odometer_speed_from_message(m))
    on_observation(std::make_shared<est::OdometerObservation>(time_.seconds(m.gps_week, m.gps_sow_s), *v), arrival_s,
                   out);
}

void FusionEngine::on_idle(double now_s, std::vector<FusionOutput>& out) {
  out_ = &out;
  run_->session.idle(now_s);
  out_ = nullptr;
}

void FusionEngine::on_end(std::vector<FusionOutput>& out) {
  out_ = &out;
  run_->session.finish();
  out_ = nullptr;
}

}  // namespace ldv
