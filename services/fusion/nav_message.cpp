#include "services/fusion/nav_message.hpp"

#include <algorithm>
#include <iterator>

namespace ldv {

ldv_lcm::nav_state_t nav_message(const FusionOutput& o, int64_t seq) {
  ldv_lcm::nav_state_t m{};
  m.seq = seq;
  m.gps_week = o.gps_week;
  m.gps_sow_s = o.gps_sow_s;
  m.lat_deg = o.state.pos.lat_rad * kRadToDeg;
  m.lon_deg = o.state.pos.lon_rad * kRadToDeg;
  m.height_m = o.state.pos.h_m;
  const Vec3 rpy = o.state.rpy_rad() * kRadToDeg;
  for (int i = 0; i < 3; ++i) {
    m.vel_ned_mps[i] = o.state.v_n_mps[i];
    m.rpy_deg[i] = rpy[i];
    m.pos_std_ned_m[i] = static_cast<float>(o.std.pos_ned_m[i]);
    m.vel_std_ned_mps[i] = static_cast<float>(o.std.vel_n_mps[i]);
    m.att_std_deg[i] = static_cast<float>(o.std.att_rad[i] * kRadToDeg);
  }
  m.status = static_cast<int32_t>(o.status);
  m.mode = static_cast<int32_t>(o.mode);
  return m;
}

namespace {
// The codes of nav_innovation_t.sensor: index + 1; 0 for a sensor that has none yet.
constexpr est::SensorName kSensorCodes[] = {est::sensors::kGnssPosition, est::sensors::kGnssVelocity,
                                            est::sensors::kZeroVelocity, est::sensors::kZeroAngularRate,
                                            est::sensors::kNonHolonomic, est::sensors::kOdometer};
}  // namespace

int8_t sensor_code(est::SensorName sensor) {
  for (size_t i = 0; i < std::size(kSensorCodes); ++i)
    if (kSensorCodes[i] == sensor) return static_cast<int8_t>(i + 1);
  return 0;
}

std::string sensor_of_code(int8_t code) {
  if (code >= 1 && code <= static_cast<int>(std::size(kSensorCodes))) return std::string(kSensorCodes[code - 1]);
  return "sensor " + std::to_string(code);
}

ldv_lcm::nav_innovation_t innovation_message(const est::InnovationRecord& r, const GpsTime& t, int64_t seq) {
  ldv_lcm::nav_innovation_t m{};
  m.seq = seq;
  m.gps_week = t.week;
  m.gps_sow_s = t.sow_s;
  m.sensor = sensor_code(r.sensor);
  const int rows = std::min<int>(3, static_cast<int>(r.innovation.size()));
  m.dim = static_cast<int8_t>(rows);
  for (int i = 0; i < rows; ++i) {
    m.innovation[i] = r.innovation[i];
    m.s_diag[i] = r.S(i, i);
  }
  m.nis = r.nis;
  m.accepted = r.used();  // an outlier the robust update kept with a trace of weight is reported rejected
  return m;
}

}  // namespace ldv
