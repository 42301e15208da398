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
    : filter_(so.filter), session_(so, filter_, [this](const est::NavFilter& f, int week) {
        if (epoch_observer_) epoch_observer_(f, week);
        if (!out_) return;
        FusionOutput o;
        o.gps_week = week;
        o.state = f.state();
        o.gps_sow_s = f.gnss_time_s();
        o.std = f.nav_std();
        o.status = f.status();
        o.mode = (o.status & est::kStatusGnssOutage) ? FusionMode::kFreeInertial : FusionMode::kAided;
        out_->push_back(o);
      }) {}

void FusionEngine::on_imu(const ImuIncrement& imu, int week, double arrival_s, std::vector<FusionOutput>& out) {
  out_ = &out;
  session_.add_imu(imu, week, arrival_s);
  out_ = nullptr;
}

void FusionEngine::on_observation(est::ObservationPtr reading, double arrival_s, std::vector<FusionOutput>& out) {
  out_ = &out;
  session_.add_observation(std::move(reading), arrival_s);
  out_ = nullptr;
}

WarmState FusionEngine::warm_state(double host_time_s) const {
  return {host_time_s, filter_.state(), filter_.nav_std(),
          filter_.options().input_gyro_bias_rad_s + filter_.error_model().gyro_bias_rad_s};
}

bool FusionEngine::wants_odometer() const { return filter_.options().aids.has("odometer"); }

void FusionEngine::on_wheel_speed(const ldv_lcm::wheel_speed_t& m, double arrival_s, std::vector<FusionOutput>& out) {
  if (!wants_odometer()) return;
  if (const auto v = odometer_speed_from_message(m))
    on_observation(std::make_shared<est::OdometerObservation>(m.gps_sow_s, *v), arrival_s, out);
}

void FusionEngine::on_idle(double now_s, std::vector<FusionOutput>& out) {
  out_ = &out;
  session_.idle(now_s);
  out_ = nullptr;
}

void FusionEngine::on_end(std::vector<FusionOutput>& out) {
  out_ = &out;
  session_.finish();
  out_ = nullptr;
}

}  // namespace ldv
