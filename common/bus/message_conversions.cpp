#include "common/bus/message_conversions.hpp"

#include <cmath>

#include "common/formats/gnss_solution_checks.hpp"
#include "common/formats/imu_sample_checks.hpp"

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

gnss::GnssSolution solution_from_message(const ldv_lcm::gnss_solution_t& m) {
  gnss::GnssSolution s;
  s.time = {m.gps_week, m.gps_sow_s};
  s.fix = gnss_from_message(m);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) s.pos_cov_ned_m2(r, c) = m.pos_cov_ned_m2[3 * r + c];
  return s;
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

// The bus-input contract: each message is checked by the code that checks the files and decoders' output
// (gnss_solution_checks, imu_sample_checks), so a value refused in a file is refused on the bus too.
std::optional<std::string> implausibility(const ldv_lcm::imu_sample_t& m) {
  // Host-clock stamps (before imu_acq's PPS fit) carry no GPS week to check; they are still seconds of week.
  if (has_gps_time(m)) {
    if (auto why = gnss::implausibility(GpsTime{m.gps_week, m.gps_sow_s})) return why;
  } else if (!(std::isfinite(m.gps_sow_s) && m.gps_sow_s >= 0.0 && m.gps_sow_s < kSecondsPerWeek)) {
    return "time of week not in [0, 604800)";
  }
  const ImuIncrement s = imu_from_message(m);
  return imu_increment_implausibility(s.dtheta_b_rad, s.dvel_b_mps, s.dt_s);
}

std::optional<std::string> implausibility(const ldv_lcm::gnss_solution_t& m) {
  if (m.has_velocity) {
    for (double var : m.vel_var_ned_m2s2)
      if (!(var >= 0.0)) return "velocity variance not finite and >= 0";
  }
  if (auto why = gnss::implausibility(solution_from_message(m))) return why;
  if (m.fix_quality < 0 || m.fix_quality > 6) return "fix quality " + std::to_string(m.fix_quality) + " not in [0, 6]";
  return std::nullopt;
}

std::optional<std::string> implausibility(const ldv_lcm::wheel_speed_t& m) {
  const size_t n = static_cast<size_t>(m.num_wheels);
  if (m.num_wheels < 1 || m.num_wheels > 8 || m.wheel_id.size() != n || m.speed_mps.size() != n || m.counts.size() != n)
    return "wheel count and arrays disagree or not in [1, 8]";
  if (auto why = gnss::implausibility(GpsTime{m.gps_week, m.gps_sow_s})) return why;
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(m.speed_mps[i]) || std::abs(m.speed_mps[i]) > 150.0 || m.wheel_id[i] < 0 || m.wheel_id[i] > 4)
      return "wheel speed not finite within +-150 m/s, or a wheel id not in [0, 4]";
  if (!std::isfinite(m.counts_per_m) || !std::isfinite(m.latency_s)) return "counts per metre or latency not finite";
  return std::nullopt;
}

bool is_valid(const ldv_lcm::imu_sample_t& m) { return !implausibility(m); }
bool is_valid(const ldv_lcm::gnss_solution_t& m) { return !implausibility(m); }
bool is_valid(const ldv_lcm::wheel_speed_t& m) { return !implausibility(m); }

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
