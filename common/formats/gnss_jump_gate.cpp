#include "common/formats/gnss_jump_gate.hpp"

#include "common/geo/earth_model.hpp"

namespace ldv::gnss {

JumpVerdict JumpGate::restart(const GnssSolution& s) {
  history_.clear();
  history_.push_back(s);
  consecutive_rejections_ = 0;
  ++counters_.restarts;
  ++counters_.accepted;
  return JumpVerdict::kRestarted;
}

JumpVerdict JumpGate::check(const GnssSolution& s) {
  last_deviation_m_ = 0.0;
  if (history_.empty()) return restart(s);
  const GnssSolution& last = history_.back();
  const double dt_s = s.time.total_seconds() - last.time.total_seconds();
  if (dt_s > options_.max_gap_s) return restart(s);
  if (dt_s <= 0.0) {
    ++counters_.time_rejected;
    // A receiver restarted with a new time base: follow it after the same number of refusals.
    if (++consecutive_rejections_ >= options_.rejections_to_reset) return restart(s);
    return JumpVerdict::kTimeRejected;
  }

  Vec3 predicted_ned_m = Vec3::Zero();
  bool can_predict = true;
  if (last.fix.has_velocity) {
    predicted_ned_m = last.fix.vel_n_mps * dt_s;
  } else if (history_.size() == 2) {
    const GnssSolution& before = history_.front();
    const double span_s = last.time.total_seconds() - before.time.total_seconds();
    predicted_ned_m = earth::ned_between(before.fix.pos, last.fix.pos) * (dt_s / span_s);
  } else {
    can_predict = false;  // one position and no velocity: any nearby place is plausible
  }
  if (can_predict) {
    last_deviation_m_ = (earth::ned_between(last.fix.pos, s.fix.pos) - predicted_ned_m).norm();
    if (last_deviation_m_ > options_.max_jump_m) {
      ++counters_.jumps_rejected;
      if (++consecutive_rejections_ >= options_.rejections_to_reset) return restart(s);
      return JumpVerdict::kJumpRejected;
    }
  }
  consecutive_rejections_ = 0;
  history_.push_back(s);
  if (history_.size() > 2) history_.pop_front();
  ++counters_.accepted;
  return JumpVerdict::kAccepted;
}

}  // namespace ldv::gnss
