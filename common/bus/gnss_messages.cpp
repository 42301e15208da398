#include "common/bus/gnss_messages.hpp"

#include <cmath>
#include <numbers>

namespace ldv::gnss {
namespace {
constexpr double kRadToDeg = 180.0 / std::numbers::pi;
}

ldv_lcm::gnss_solution_t to_message(const GnssSolution& s, std::int64_t seq, double host_time_s) {
  ldv_lcm::gnss_solution_t m{};
  m.seq = seq;
  m.gps_week = s.time.week;
  m.gps_sow_s = s.time.sow_s;
  m.host_time_s = host_time_s;
  m.lat_deg = s.fix.pos.lat_rad * kRadToDeg;
  m.lon_deg = s.fix.pos.lon_rad * kRadToDeg;
  m.height_m = s.fix.pos.h_m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m.pos_cov_ned_m2[3 * r + c] = s.pos_cov_ned_m2(r, c);
  m.has_velocity = s.fix.has_velocity;
  for (int i = 0; i < 3; ++i) {
    m.vel_ned_mps[i] = s.fix.has_velocity ? s.fix.vel_n_mps[i] : 0.0;
    m.vel_var_ned_m2s2[i] = s.fix.has_velocity ? s.fix.vel_std_n_mps[i] * s.fix.vel_std_n_mps[i] : 0.0;
  }
  m.fix_quality = static_cast<int8_t>(s.fix.quality);
  m.num_sats = static_cast<int16_t>(s.fix.num_sats);
  m.age_s = static_cast<float>(s.fix.age_s);
  m.ratio = static_cast<float>(s.fix.ratio);
  return m;
}

std::int64_t label_total_second(const PpsTimeLabel& label) {
  return static_cast<std::int64_t>(label.pulse_time.week) * 604800 + std::llround(label.pulse_time.sow_s);
}

ldv_lcm::pps_event_t to_message(const PpsTimeLabel& label, std::int64_t seq, double host_time_s,
                                std::int64_t previous_second) {
  ldv_lcm::pps_event_t m{};
  m.seq = seq;
  const std::int64_t second = label_total_second(label);
  m.gps_week = static_cast<int32_t>(second / 604800);
  m.gps_sow_s = static_cast<double>(second % 604800);
  m.counter_raw = kNoCounter;
  m.host_time_s = host_time_s;
  m.flags = 0;
  if (previous_second >= 0 && second > previous_second + 1) m.flags |= kPpsFlagMissingPrevious;
  if (label.refers == PpsTimeLabel::Refers::kNextPulse) m.flags |= kPpsFlagLabelsNextPulse;
  return m;
}

PpsTimeLabel label_from_message(const ldv_lcm::pps_event_t& m) {
  PpsTimeLabel l;
  l.pulse_time = GpsTime{m.gps_week, m.gps_sow_s};
  l.refers = (m.flags & kPpsFlagLabelsNextPulse) ? PpsTimeLabel::Refers::kNextPulse : PpsTimeLabel::Refers::kLastPulse;
  return l;
}

}  // namespace ldv::gnss
