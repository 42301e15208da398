#include "common/bus/message_conversions.hpp"

#include <cmath>

namespace ldv {

ImuIncrement imu_from_message(const ldv_lcm::imu_sample_t& m) {
  ImuIncrement s;
  s.t_s = m.gps_sow_s;
  s.dt_s = m.dt_s;
  s.dtheta_b_rad = Vec3(m.dtheta_b_rad[0], m.dtheta_b_rad[1], m.dtheta_b_rad[2]);
  s.dvel_b_mps = Vec3(m.dvel_b_mps[0], m.dvel_b_mps[1], m.dvel_b_mps[2]);
  return s;
}

ldv_lcm::imu_sample_t message_from_imu(const ImuIncrement& s, int gps_week, int64_t seq) {
  ldv_lcm::imu_sample_t m{};
  m.seq = seq;
  m.gps_week = gps_week;
  m.gps_sow_s = s.t_s;
  m.dt_s = s.dt_s;
  for (int i = 0; i < 3; ++i) {
    m.dtheta_b_rad[i] = s.dtheta_b_rad[i];
    m.dvel_b_mps[i] = s.dvel_b_mps[i];
  }
  return m;
}

GnssFix gnss_from_message(const ldv_lcm::gnss_solution_t& m) {
  GnssFix g;
  g.t_s = m.gps_sow_s;
  g.pos = {m.lat_deg * kDegToRad, m.lon_deg * kDegToRad, m.height_m};
  g.pos_std_ned_m = Vec3(std::sqrt(m.pos_cov_ned_m2[0]), std::sqrt(m.pos_cov_ned_m2[4]), std::sqrt(m.pos_cov_ned_m2[8]));
  g.has_velocity = m.has_velocity;
  g.vel_n_mps = Vec3(m.vel_ned_mps[0], m.vel_ned_mps[1], m.vel_ned_mps[2]);
  g.vel_std_n_mps = Vec3(std::sqrt(m.vel_var_ned_m2s2[0]), std::sqrt(m.vel_var_ned_m2s2[1]), std::sqrt(m.vel_var_ned_m2s2[2]));
  g.quality = static_cast<GnssQuality>(m.fix_quality);
  g.num_sats = m.num_sats;
  g.age_s = m.age_s;
  g.ratio = m.ratio;
  return g;
}

ldv_lcm::gnss_solution_t message_from_gnss(const GnssFix& g, int gps_week, int64_t seq) {
  ldv_lcm::gnss_solution_t m{};
  m.seq = seq;
  m.gps_week = gps_week;
  m.gps_sow_s = g.t_s;
  m.lat_deg = g.pos.lat_rad * kRadToDeg;
  m.lon_deg = g.pos.lon_rad * kRadToDeg;
  m.height_m = g.pos.h_m;
  for (int i = 0; i < 3; ++i) {
    m.pos_cov_ned_m2[4 * i] = g.pos_std_ned_m[i] * g.pos_std_ned_m[i];
    m.vel_ned_mps[i] = g.vel_n_mps[i];
    m.vel_var_ned_m2s2[i] = g.vel_std_n_mps[i] * g.vel_std_n_mps[i];
  }
  m.has_velocity = g.has_velocity;
  m.fix_quality = static_cast<int8_t>(g.quality);
  m.num_sats = static_cast<int16_t>(g.num_sats);
  m.age_s = static_cast<float>(g.age_s);
  m.ratio = static_cast<float>(g.ratio);
  return m;
}

namespace {
bool all_finite(const double* v, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}
}  // namespace

bool is_valid(const ldv_lcm::imu_sample_t& m) {
  return std::isfinite(m.gps_sow_s) && std::isfinite(m.dt_s) && m.dt_s > 0 && m.dt_s < 1.0 &&
         all_finite(m.dtheta_b_rad, 3) && all_finite(m.dvel_b_mps, 3);
}

bool is_valid(const ldv_lcm::gnss_solution_t& m) {
  return std::isfinite(m.gps_sow_s) && std::isfinite(m.lat_deg) && std::abs(m.lat_deg) <= 90 &&
         std::isfinite(m.lon_deg) && std::isfinite(m.height_m) && all_finite(m.pos_cov_ned_m2, 9) &&
         m.pos_cov_ned_m2[0] > 0 && m.pos_cov_ned_m2[4] > 0 && m.pos_cov_ned_m2[8] > 0 &&
         (!m.has_velocity || (all_finite(m.vel_ned_mps, 3) && all_finite(m.vel_var_ned_m2s2, 3) &&
                              m.vel_var_ned_m2s2[0] > 0 && m.vel_var_ned_m2s2[1] > 0 && m.vel_var_ned_m2s2[2] > 0));
}

bool is_valid(const ldv_lcm::wheel_speed_t& m) {
  const size_t n = static_cast<size_t>(m.num_wheels);
  if (m.num_wheels < 1 || m.num_wheels > 8 || m.wheel_id.size() != n || m.speed_mps.size() != n || m.counts.size() != n)
    return false;
  if (!std::isfinite(m.gps_sow_s) || m.gps_sow_s < 0 || m.gps_sow_s >= 604800.0 || m.gps_week < 0) return false;
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(m.speed_mps[i]) || std::abs(m.speed_mps[i]) > 150.0 || m.wheel_id[i] < 0 || m.wheel_id[i] > 4)
      return false;
  return std::isfinite(m.counts_per_m) && std::isfinite(m.latency_s);
}

std::optional<double> odometer_speed_from_message(const ldv_lcm::wheel_speed_t& m) {
  if (!is_valid(m) || !(m.status & kWheelStatusSpeedsValid) || (m.status & kWheelStatusSlipping)) return std::nullopt;
  double rear_sum = 0.0, all_sum = 0.0;
  int rear = 0;
  for (int i = 0; i < m.num_wheels; ++i) {
    if (m.wheel_id[i] == 0) return m.speed_mps[i];
    if (m.wheel_id[i] == 3 || m.wheel_id[i] == 4) {
      rear_sum += m.speed_mps[i];
      ++rear;
    }
    all_sum += m.speed_mps[i];
  }
  return rear > 0 ? rear_sum / rear : all_sum / m.num_wheels;
}

ldv_lcm::wheel_speed_t message_from_odometer(double t_s, double speed_mps, int gps_week, int64_t seq) {
  ldv_lcm::wheel_speed_t m{};
  m.seq = seq;
  m.gps_week = gps_week;
  m.gps_sow_s = t_s;
  m.num_wheels = 1;
  m.wheel_id = {0};
  m.speed_mps = {speed_mps};
  m.counts = {0};
  m.status = kWheelStatusSpeedsValid;
  return m;
}

}  // namespace ldv
