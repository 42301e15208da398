#pragma once
// A simulated drive written as fusion receives it (IMU, GNSS_SOLUTION on the bus, in an LCM log), with a hook
// that may change any message before it is written (the hostile case), replayed through fusion's engine and
// compared with the simulator's truth. GPS time runs on from `first_sow_s` of `first_week` across week ends, as a
// receiver's does (week + 1, seconds of week from 0).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>

#include "common/bus/message_conversions.hpp"
#include "common/geo/earth_model.hpp"
#include "common/time/gps_time.hpp"
#include "estimator/run/run_navigation.hpp"
#include "services/fusion/log_replay.hpp"
#include "sim/simulator.hpp"

namespace ldv::testing {

template <class Msg>
inline void write_log_event(lcm::LogFile& log, const std::string& channel, const Msg& m, double arrival_s) {
  std::vector<uint8_t> buf(static_cast<size_t>(m.getEncodedSize()));
  ASSERT_GE(m.encode(buf.data(), 0, static_cast<int>(buf.size())), 0);
  lcm::LogEvent e{};
  e.timestamp = static_cast<int64_t>(std::llround(arrival_s * 1e6));
  e.channel = channel;
  e.datalen = static_cast<int32_t>(buf.size());
  e.data = buf.data();
  ASSERT_EQ(log.writeEvent(&e), 0);
}

struct HostileDrive {
  sim::SimResult sim;
  int first_week = 2300;
  double shift_s = 0.0;  // continuous GPS time since first_week's start = simulator time + shift_s
  // Called before each message is written (index among its kind); may change it freely.
  std::function<void(ldv_lcm::imu_sample_t&, size_t)> on_imu;
  std::function<void(ldv_lcm::gnss_solution_t&, size_t)> on_gnss;
};

// grade, duration, first seconds of week: a drive starting at first_sow_s (GPS time, the run's first sample).
inline HostileDrive hostile_drive(const std::string& grade, double duration_s, double first_sow_s, unsigned seed = 3) {
  sim::SimRequest req;
  req.grade = grade;
  req.scenario = "drive";
  req.duration_s = duration_s;
  req.gnss_rate_hz = 5.0;
  req.seed = seed;
  req.start_sow_s = 1000.0;
  HostileDrive d;
  d.sim = sim::simulate(req);
  d.shift_s = first_sow_s - req.start_sow_s;
  return d;
}

struct ReplayedNav {
  LogReplaySummary summary;
  std::vector<FusionOutput> outputs;
  double continuous_s(const FusionOutput& o, int first_week) const {
    return (o.gps_week - first_week) * kSecondsPerWeek + o.gps_sow_s;
  }
};

inline GpsTime week_time(int first_week, double continuous_s) {
  const double weeks = std::floor(continuous_s / kSecondsPerWeek);
  return {first_week + static_cast<int>(weeks), continuous_s - weeks * kSecondsPerWeek};
}

// Writes the drive's log (fixes half a second ahead of the IMU, as the file run hands them over) and replays it
// through fusion's engine with the simulator's configuration (given start from truth).
inline ReplayedNav replay_hostile_drive(const HostileDrive& d) {
  namespace fs = std::filesystem;
  static int serial = 0;
  const fs::path log_path = fs::temp_directory_path() /
                            ("ldv_hostile_" + std::to_string(::getpid()) + "_" + std::to_string(serial++) + ".lcmlog");
  {
    lcm::LogFile log(log_path.string(), "w");
    EXPECT_TRUE(log.good());
    size_t g = 0;
    for (size_t i = 0; i < d.sim.imu.size(); ++i) {
      const ImuIncrement& inc = d.sim.imu[i];
      for (; g < d.sim.gnss.size() && d.sim.gnss[g].t_s <= inc.t_s + 0.5; ++g) {
        const GpsTime t = week_time(d.first_week, d.sim.gnss[g].t_s + d.shift_s);
        GnssFix fix = d.sim.gnss[g];
        fix.t_s = t.sow_s;
        ldv_lcm::gnss_solution_t m = message_from_gnss(fix, t.week, static_cast<int64_t>(g));
        if (d.on_gnss) d.on_gnss(m, g);
        write_log_event(log, "GNSS_SOLUTION", m, inc.t_s);
      }
      const GpsTime t = week_time(d.first_week, inc.t_s + d.shift_s);
      ImuIncrement shifted = inc;
      shifted.t_s = t.sow_s;
      ldv_lcm::imu_sample_t m = message_from_imu(shifted, t.week, static_cast<int64_t>(i));
      if (d.on_imu) d.on_imu(m, i);
      write_log_event(log, "IMU", m, inc.t_s);
    }
  }
  KfGinsConfig cfg = d.sim.kfgins;
  cfg.start_time_s += d.shift_s;
  if (cfg.end_time_s > 0) cfg.end_time_s += d.shift_s;
  est::FilterOptions fo = est::options_from_kfgins(cfg);
  fo.history_s = 3.0;
  FusionEngine engine(live_session_options(cfg, fo));
  ReplayedNav r;
  r.summary = replay_fusion_log(log_path.string(), engine, [&](const FusionOutput& o) { r.outputs.push_back(o); });
  fs::remove(log_path);
  return r;
}

// Largest horizontal and vertical position error of the outputs against the simulator's truth (IMU epochs).
struct TruthErrors {
  double max_horizontal_m = 0.0, max_speed_mps = 0.0;
  size_t compared = 0;
};
inline TruthErrors errors_against_truth(const HostileDrive& d, const ReplayedNav& r) {
  std::map<long, const sim::TruthSample*> truth;
  for (const auto& s : d.sim.truth) truth[std::lround(s.t_s * 1e3)] = &s;
  TruthErrors e;
  for (const FusionOutput& o : r.outputs) {
    e.max_speed_mps = std::max(e.max_speed_mps, o.state.v_n_mps.norm());
    const auto it = truth.find(std::lround((r.continuous_s(o, d.first_week) - d.shift_s) * 1e3));
    if (it == truth.end()) continue;
    const Vec3 dr = earth::ned_between(it->second->pos, o.state.pos);
    e.max_horizontal_m = std::max(e.max_horizontal_m, std::hypot(dr[0], dr[1]));
    ++e.compared;
  }
  return e;
}

}  // namespace ldv::testing
