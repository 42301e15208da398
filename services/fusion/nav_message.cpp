#include "services/fusion/nav_message.hpp"

namespace ldv {

ldv_lcm::nav_state_t nav_message(const FusionOutput& o, int64_t seq) {
  ldv_lcm::nav_state_t m{};
  m.seq = seq;
  m.gps_week = o.gps_week;
  m.gps_sow_s = o.state.t_s;
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

ldv_lcm::nav_innovation_t innovation_message(const est::InnovationRecord& r, int gps_week, int64_t seq) {
  ldv_lcm::nav_innovation_t m{};
  m.seq = seq;
  m.gps_week = gps_week;
  m.gps_sow_s = r.t_s;
  m.sensor = static_cast<int8_t>(static_cast<int>(r.kind) + 1);
  m.dim = 3;
  for (int i = 0; i < 3; ++i) {
    m.innovation[i] = r.innovation[i];
    m.s_diag[i] = r.S(i, i);
  }
  m.nis = r.nis;
  m.accepted = r.used();  // an outlier the robust update kept with a trace of weight is reported rejected
  return m;
}

}  // namespace ldv
