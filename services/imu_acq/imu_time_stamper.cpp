#include "services/imu_acq/imu_time_stamper.hpp"

#include <cmath>

#include "services/imu_acq/timing/counter_unwrap.hpp"

namespace ldv::imu {

ImuTimeStamper::ImuTimeStamper(StamperOptions options, EdgeHandler on_edge)
    : options_(options),
      on_edge_(std::move(on_edge)),
      fit_(options.fit),
      matcher_([this](std::uint64_t c, std::optional<std::int64_t> s) { on_matched_edge(c, s); }, options.matcher) {}

std::int64_t ImuTimeStamper::extend(std::uint64_t raw_counter) {
  // Samples and latches come many times per wrap, so the nearest extension is the right one.
  const std::int64_t e = last_extended_ ? timing::unwrap_nearest(raw_counter, *last_extended_, options_.fit.counter_bits)
                                        : static_cast<std::int64_t>(raw_counter);
  last_extended_ = e;
  return e;
}

void ImuTimeStamper::on_pps_latch(std::uint64_t raw_counter, double host_time_s) {
  latch_host_time_s_ = host_time_s;
  matcher_.on_edge(raw_counter, host_time_s);
}

void ImuTimeStamper::on_label(const gnss::PpsTimeLabel& label, double host_time_s) {
  matcher_.on_label(label, host_time_s);
}

void ImuTimeStamper::poll(double host_time_s) { matcher_.poll(host_time_s); }

void ImuTimeStamper::on_matched_edge(std::uint64_t raw_counter, std::optional<std::int64_t> gps_second) {
  JudgedEdge e;
  e.counter = extend(raw_counter);
  e.host_time_s = latch_host_time_s_;
  e.result = fit_.add_pps_edge(raw_counter, gps_second);
  const bool known = e.result.verdict != timing::PpsEdgeVerdict::kUnlabelled;
  if (known) e.gps_second = e.result.gps_second;
  if (on_edge_) on_edge_(e);
}

void ImuTimeStamper::seed(const FitState& saved, double max_counter_jump_s) {
  seed_ = saved;
  seed_max_jump_s_ = max_counter_jump_s;
}

std::optional<FitState> ImuTimeStamper::fit_state(double host_time_s) const {
  if (!anchor_ || !anchor_is_fit_ || !fit_.locked()) return std::nullopt;
  return FitState{host_time_s, anchor_->first, anchor_->second, anchor_hz_, options_.fit.counter_bits};
}

Stamp ImuTimeStamper::stamp(std::uint64_t raw_counter, double host_time_s) {
  Stamp s;
  if (seed_ && !last_extended_) {
    // First sample after a restart: where the saved line says the counter is now.
    const double predicted = static_cast<double>(seed_->counter) + (host_time_s - seed_->saved_host_time_s) * seed_->counter_hz;
    last_extended_ = static_cast<std::int64_t>(std::llround(predicted));
    const std::int64_t e = extend(raw_counter);
    if (std::abs(static_cast<double>(e) - predicted) / seed_->counter_hz <= seed_max_jump_s_) {
      anchor_ = {seed_->counter, seed_->gps_total_s};
      anchor_hz_ = seed_->counter_hz;
      anchor_is_fit_ = true;
    } else {
      last_extended_.reset();  // the counter restarted: extend from this sample as on a cold start
    }
    seed_.reset();
  }
  s.counter = extend(raw_counter);
  if (const auto t = fit_.stamp(raw_counter)) {
    s.time = *t;
    anchor_ = {s.counter, t->total_seconds()};
    anchor_hz_ = fit_.counter_hz();
    anchor_is_fit_ = true;
    return s;
  }
  // Unlocked: carry on from the last fitted stamp (or the saved fit) at its rate (drift of the oscillator
  // over the gap), or start from the host clock (milliseconds off, but in the right second).
  if (!anchor_) {
    anchor_ = {s.counter, host_time_s - kGpsEpochInUnixSeconds + options_.gps_minus_utc_s};
    anchor_hz_ = options_.fit.nominal_counter_hz;
    anchor_is_fit_ = false;
  }
  const double t_s = anchor_->second + static_cast<double>(s.counter - anchor_->first) / anchor_hz_;
  s.time = GpsTime::from_total_seconds(t_s);
  s.extrapolated = true;
  s.holdover = anchor_is_fit_;
  return s;
}

}  // namespace ldv::imu
