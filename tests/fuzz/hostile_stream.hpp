#pragma once
// Valid-but-extreme bus message streams for fusion's input gate and engine. A vehicle at rest (level, heading
// north) sends 100 Hz IMU and 5 Hz GNSS over a GPS week rollover (week 2300 sow 604790 to week 2301); each byte
// pair of the script may change one message (a field set to an extreme value, a week or time of week moved, a
// duplicate, a swap with the next, a drop). The last 2 s are left clean, so a consumer that survived must be
// navigating again by the end. replay_hostile_stream runs the messages through the live code (FusionInputGate,
// FusionEngine) and returns what a subscriber of NAV would check.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "common/bus/message_conversions.hpp"
#include "common/formats/gnss_solution_checks.hpp"
#include "common/formats/kfgins_config.hpp"
#include "estimator/run/run_navigation.hpp"
#include "services/fusion/fusion_engine.hpp"
#include "services/fusion/fusion_input_gate.hpp"

namespace ldv::fuzz {

constexpr int kFirstWeek = 2300;
constexpr double kFirstSow_s = 604790.0;
constexpr double kImuRate_hz = 100.0, kGnssRate_hz = 5.0, kStreamLength_s = 20.0, kCleanTail_s = 2.0;
constexpr double kLat_deg = 30.5, kLon_deg = 114.3, kHeight_m = 20.0;

inline double extreme_value(uint8_t v) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double table[] = {0.0,   -0.0,    1e30,       -1e30, std::nan(""), kInf, -kInf, 1e-300,
                          1e300, 604800., 604799.999, -1.0,  1e6,          3.0,  -3.0,  1e-9};
  return table[v % 16];
}

struct Message {
  bool is_imu = true;
  ldv_lcm::imu_sample_t imu{};
  ldv_lcm::gnss_solution_t gnss{};
  double arrival_s = 0.0;
};

// The clean stream: (week, sow) of continuous time t after the stream's start.
inline std::vector<Message> clean_stream() {
  std::vector<Message> out;
  const double g = 9.7936;  // near-enough gravity at the site (a level IMU at rest senses -g on z, FRD)
  const int n_imu = static_cast<int>(kStreamLength_s * kImuRate_hz);
  const int per_fix = static_cast<int>(kImuRate_hz / kGnssRate_hz);
  for (int i = 0; i < n_imu; ++i) {
    const double t = kFirstSow_s + (i + 1) / kImuRate_hz;
    const int week = kFirstWeek + static_cast<int>(std::floor(t / kSecondsPerWeek));
    const double sow = t - (week - kFirstWeek) * kSecondsPerWeek;
    Message m;
    m.imu.seq = i;
    m.imu.gps_week = week;
    m.imu.gps_sow_s = sow;
    m.imu.dt_s = 1.0 / kImuRate_hz;
    m.imu.dvel_b_mps[2] = -g / kImuRate_hz;
    m.arrival_s = t - kFirstSow_s;
    out.push_back(m);
    if ((i + 1) % per_fix == 0) {
      Message f;
      f.is_imu = false;
      f.gnss.seq = i / per_fix;
      f.gnss.gps_week = week;
      f.gnss.gps_sow_s = sow;
      f.gnss.lat_deg = kLat_deg;
      f.gnss.lon_deg = kLon_deg;
      f.gnss.height_m = kHeight_m;
      f.gnss.pos_cov_ned_m2[0] = f.gnss.pos_cov_ned_m2[4] = 4e-4;
      f.gnss.pos_cov_ned_m2[8] = 1e-3;
      f.gnss.fix_quality = 1;
      f.gnss.num_sats = 14;
      f.arrival_s = m.arrival_s + 0.1;
      out.push_back(f);
    }
  }
  return out;
}

// Applies the script: byte pair k (selector, value) acts on message k.
inline std::vector<Message> hostile_stream(const uint8_t* script, size_t size) {
  std::vector<Message> s = clean_stream();
  size_t clean_from = s.size();
  while (clean_from > 0 && s[clean_from - 1].arrival_s > kStreamLength_s - kCleanTail_s) --clean_from;
  std::vector<Message> out;
  out.reserve(s.size() + size);
  for (size_t k = 0; k < s.size(); ++k) {
    Message m = s[k];
    if (k >= clean_from || 2 * k + 1 >= size) {
      out.push_back(m);
      continue;
    }
    const uint8_t sel = script[2 * k], val = script[2 * k + 1];
    const double x = extreme_value(val);
    ldv_lcm::imu_sample_t& u = m.imu;
    ldv_lcm::gnss_solution_t& g = m.gnss;
    switch (sel % 24) {
      case 0:
        if (m.is_imu)
          u.dt_s = x;
        else
          g.age_s = static_cast<float>(x);
        break;
      case 1:
        (m.is_imu ? u.gps_sow_s : g.gps_sow_s) += m.is_imu ? x * 1e-3 : x;
        break;
      case 2:
        (m.is_imu ? u.gps_sow_s : g.gps_sow_s) = x;
        break;
      case 3:
        (m.is_imu ? u.gps_week : g.gps_week) += (val % 3) - 1;
        break;
      case 4:
        (m.is_imu ? u.gps_week : g.gps_week) = val % 2 ? 0 : 99999;
        break;
      case 5:
        if (m.is_imu)
          u.dtheta_b_rad[val % 3] = x;
        else
          g.lat_deg = x;
        break;
      case 6:
        if (m.is_imu)
          u.dvel_b_mps[val % 3] = x;
        else
          g.lon_deg = x;
        break;
      case 7:
        if (m.is_imu)
          u.status = val % 8;
        else
          g.height_m = x;
        break;
      case 8:
        if (!m.is_imu) g.pos_cov_ned_m2[val % 9] = x;
        break;
      case 9:
        if (!m.is_imu) {
          g.has_velocity = true;
          g.vel_ned_mps[val % 3] = x;
          g.vel_var_ned_m2s2[0] = g.vel_var_ned_m2s2[1] = g.vel_var_ned_m2s2[2] = 1e-4;
        }
        break;
      case 10:
        if (!m.is_imu) {
          g.has_velocity = true;
          g.vel_var_ned_m2s2[val % 3] = x;
        }
        break;
      case 11:
        if (!m.is_imu) g.fix_quality = static_cast<int8_t>(val);
        break;
      case 12:
        out.push_back(m);
        break;  // a duplicate
      case 13:
        if (k + 1 < clean_from) std::swap(s[k], s[k + 1]), m = s[k];
        break;  // out of order
      case 14:
        continue;  // lost
      case 15:
        if (!m.is_imu) {
          g.lat_deg += 1e-4 * (val - 128.0);
        }
        break;  // a plausible jump
      default:
        break;  // most messages pass untouched
    }
    out.push_back(m);
  }
  return out;
}

struct StreamOutcome {
  long nav = 0, refused = 0;
  bool finite_and_plausible = true, times_increase = true;
  double last_nav_t_s = -1.0;  // continuous from the stream's first week; -1 without NAV
  double last_imu_t_s = 0.0;
  std::string first_bad;  // the first NAV that was not finite or plausible, described
};

// The configuration of the vehicle at rest: its start given, a tactical-grade noise model.
inline KfGinsConfig hostile_stream_config() {
  KfGinsConfig c;
  c.init_pos = Geodetic{kLat_deg * kDegToRad, kLon_deg * kDegToRad, kHeight_m};
  c.init_vel_n_mps = Vec3::Zero();
  c.init_rpy_rad = Vec3::Zero();
  c.start_time_s = kFirstSow_s;
  c.imu_rate_hz = kImuRate_hz;
  c.imu_noise.arw_rad_per_sqrt_s = Vec3::Constant(0.1 * kDegToRad / 60.0);
  c.imu_noise.vrw_mps_per_sqrt_s = Vec3::Constant(0.1 / 60.0);
  c.imu_noise.gyro_bias_std_rad_s = Vec3::Constant(10.0 * kDegToRad / 3600.0);
  c.imu_noise.accel_bias_std_mps2 = Vec3::Constant(1e-3);
  c.imu_noise.corr_time_s = 3600.0;
  return c;
}

inline StreamOutcome replay_hostile_stream(const std::vector<Message>& stream) {
  const KfGinsConfig cfg = hostile_stream_config();
  est::FilterOptions fo = est::options_from_kfgins(cfg);
  fo.history_s = 3.0;
  FusionEngine engine(live_session_options(cfg, fo));
  FusionInputGate gate({});
  long jumps_back_seen = 0;
  StreamOutcome r;
  std::vector<FusionOutput> outs;
  const auto look = [&](std::vector<FusionOutput>& o) {
    for (const FusionOutput& n : o) {
      const double t = (n.gps_week - kFirstWeek) * kSecondsPerWeek + n.gps_sow_s;
      const auto& s = n.state;
      const bool ok = std::isfinite(t) && n.gps_sow_s >= 0 && n.gps_sow_s < kSecondsPerWeek && s.v_n_mps.allFinite() &&
                      s.v_n_mps.norm() < gnss::kMaxPlausibleSpeed_mps && std::isfinite(s.pos.lat_rad) &&
                      std::abs(s.pos.lat_rad) <= kPi / 2 && std::isfinite(s.pos.h_m) &&
                      s.pos.h_m > gnss::kMinPlausibleHeight_m && s.pos.h_m < gnss::kMaxPlausibleHeight_m &&
                      s.q_b_n.coeffs().allFinite() && n.std.pos_ned_m.allFinite();
      if (!ok && r.finite_and_plausible) {
        char b[240];
        std::snprintf(b, sizeof b, "t %.3f lat %.6f deg h %.3g m |v| %.3g m/s pos std %.3g m", t,
                      s.pos.lat_rad * kRadToDeg, s.pos.h_m, s.v_n_mps.norm(), n.std.pos_ned_m.norm());
        r.first_bad = b;
      }
      r.finite_and_plausible = r.finite_and_plausible && ok;
      if (!(t > r.last_nav_t_s)) r.times_increase = false;
      r.last_nav_t_s = t;
      ++r.nav;
    }
    o.clear();
  };
  for (const Message& m : stream) {
    if (m.is_imu) {
      if (gate.check(m.imu) != InputVerdict::kAccepted) {
        ++r.refused;
        continue;
      }
      if (gate.imu_jumps_back() > jumps_back_seen) {  // as fusion does (services/fusion/main.cpp)
        jumps_back_seen = gate.imu_jumps_back();
        engine.restart_on_new_time_line(m.arrival_s);
        r.last_nav_t_s = -1e300;  // NAV goes on from the new time line
      }
      r.last_imu_t_s = std::max(r.last_imu_t_s, (m.imu.gps_week - kFirstWeek) * kSecondsPerWeek + m.imu.gps_sow_s);
      engine.on_imu(imu_from_message(m.imu), m.imu.gps_week, m.arrival_s, outs);
    } else {
      if (gate.check(m.gnss) != InputVerdict::kAccepted) {
        ++r.refused;
        continue;
      }
      engine.on_gnss(gnss_from_message(m.gnss), m.gnss.gps_week, m.arrival_s);
    }
    look(outs);
  }
  engine.on_end(outs);
  look(outs);
  return r;
}

}  // namespace ldv::fuzz
