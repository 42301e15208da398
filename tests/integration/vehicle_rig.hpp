#pragma once
// Shared pieces of the whole-vehicle integration tests (test_faults.cpp): the simulated vehicle in
// real time on ptys (`ldv drive`) with its GPS time aligned to the host clock (as on a vehicle whose
// host clock is GPS/NTP-disciplined), the four services started as systemd would start them, a
// listener on the vehicle bus and the TSPI group, and an LCM-log sequence checker.
#include <poll.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>
#include <ldv_lcm/gnss_solution_t.hpp>
#include <ldv_lcm/imu_sample_t.hpp>
#include <ldv_lcm/imu_timing_t.hpp>
#include <ldv_lcm/nav_innovation_t.hpp>
#include <ldv_lcm/nav_state_t.hpp>
#include <ldv_lcm/pps_event_t.hpp>
#include <ldv_lcm/service_status_t.hpp>
#include <ldv_lcm/tspi_v1_t.hpp>

#include "common/bus/bus.hpp"
#include "common/time/gps_time.hpp"
#include "services/runtime/service_runtime.hpp"
#include "tests/integration/child_process.hpp"

namespace ldv::test {

// The drive of the whole-vehicle tests (an `ldv sim` scenario): a short static start, then straights and
// turns at 10 m/s, repeated.
inline const char* const kShortDriveScenario = R"(name: integration_drive
description: "a short static start, then straights and turns at 10 m/s"
start: {lat_deg: 32.8801, lon_deg: -117.2340, h_m: 100, yaw_deg: 20}
segments:
  - {type: static, duration_s: 8}
  - {type: accelerate, to_speed_mps: 10, duration_s: 5}
loop:
  - {type: straight, duration_s: 5}
  - {type: turn, angle_deg: 90, duration_s: 7}
  - {type: straight, duration_s: 4}
  - {type: turn, angle_deg: -120, duration_s: 8}
)";

inline double steady_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// GPS time now from the host clock (GPS - UTC = 18 s).
inline double gps_total_seconds_now() { return host_time_s() - kGpsEpochInUnixSeconds + 18.0; }

// A service binary started like systemd starts it (stderr to a log file), so a test can kill -9 it and
// start it again as Restart=on-failure would.
inline std::unique_ptr<ChildProcess> start_logged(const std::string& program, const std::vector<std::string>& args,
                                                  const std::string& stderr_log) {
  std::vector<std::string> a{"-c", "exec \"$0\" \"$@\" 2>>'" + stderr_log + "'", program};
  a.insert(a.end(), args.begin(), args.end());
  return std::make_unique<ChildProcess>("/bin/sh", a);
}

// Everything on the vehicle bus and the TSPI group, with host (steady) receipt times.
struct BusWatch {
  struct Tspi {
    double rx_s;
    ldv_lcm::tspi_v1_t m;
  };
  struct Status {
    double rx_s;
    ldv_lcm::service_status_t m;
  };
  Bus vehicle;
  Bus tspi_bus;
  std::vector<Tspi> tspi;
  std::map<std::string, std::vector<Status>> status;  // by channel
  std::vector<ldv_lcm::nav_innovation_t> innovations;
  std::vector<std::pair<double, ldv_lcm::gnss_solution_t>> gnss;
  int64_t nav_count = 0;
  double last_nav_rx_s = 0;

  BusWatch(const std::string& vehicle_url, const std::string& tspi_url) : vehicle(vehicle_url), tspi_bus(tspi_url) {
    tspi_bus.subscribe<ldv_lcm::tspi_v1_t>("TSPI", [this](const ldv_lcm::tspi_v1_t& m, const std::string&) {
      tspi.push_back({steady_s(), m});
    }, 5000);
    vehicle.subscribe<ldv_lcm::service_status_t>("STATUS_.*", [this](const ldv_lcm::service_status_t& m, const std::string& ch) {
      status[ch].push_back({steady_s(), m});
    }, 1000);
    vehicle.subscribe<ldv_lcm::nav_innovation_t>("NAV_INNOVATION", [this](const ldv_lcm::nav_innovation_t& m, const std::string&) {
      innovations.push_back(m);
    }, 1000);
    vehicle.subscribe<ldv_lcm::gnss_solution_t>("GNSS_SOLUTION", [this](const ldv_lcm::gnss_solution_t& m, const std::string&) {
      gnss.emplace_back(steady_s(), m);
    }, 1000);
    vehicle.subscribe<ldv_lcm::nav_state_t>("NAV", [this](const ldv_lcm::nav_state_t&, const std::string&) {
      ++nav_count;
      last_nav_rx_s = steady_s();
    }, 20000);
  }

  // Handles both buses for duration_s, or until pred() holds. Returns pred()'s last value.
  bool spin(double duration_s, const std::function<bool()>& pred = nullptr) {
    const double end = steady_s() + duration_s;
    while (steady_s() < end) {
      if (pred && pred()) return true;
      pollfd fds[2] = {{vehicle.fd(), POLLIN, 0}, {tspi_bus.fd(), POLLIN, 0}};
      const int wait_ms = std::max(0, std::min(5, static_cast<int>((end - steady_s()) * 1000)));
      if (::poll(fds, 2, wait_ms) <= 0) continue;
      if (fds[0].revents & POLLIN) vehicle.handle(0);
      if (fds[1].revents & POLLIN) tspi_bus.handle(0);
    }
    return pred ? pred() : false;
  }
  std::optional<ldv_lcm::service_status_t> latest(const std::string& channel) const {
    const auto it = status.find(channel);
    if (it == status.end() || it->second.empty()) return std::nullopt;
    return it->second.back().m;
  }
};

// Per-channel sequence continuity in an lcm-logger file. Every ldvnav type starts with `int64 seq`
// right after the 8-byte fingerprint; a message that does not decode as its channel's type (a wrong
// fingerprint) is counted apart.
struct ChannelSequence {
  int64_t messages = 0, gaps = 0, missing = 0, resets = 0, undecodable = 0;
  std::vector<int64_t> gap_at;  // seq after each gap
};

inline std::map<std::string, ChannelSequence> log_sequences(const std::string& path) {
  using Decode = std::function<std::optional<int64_t>(const void*, int)>;
  auto dec = [](auto tag) -> Decode {
    using Msg = decltype(tag);
    return [](const void* d, int n) -> std::optional<int64_t> {
      Msg m;
      if (m.decode(d, 0, n) < 0) return std::nullopt;
      return m.seq;
    };
  };
  const std::map<std::string, Decode> types{
      {"IMU", dec(ldv_lcm::imu_sample_t{})},           {"IMU_PPS", dec(ldv_lcm::pps_event_t{})},
      {"IMU_TIMING", dec(ldv_lcm::imu_timing_t{})},    {"GNSS_SOLUTION", dec(ldv_lcm::gnss_solution_t{})},
      {"GNSS_PPS", dec(ldv_lcm::pps_event_t{})},       {"NAV", dec(ldv_lcm::nav_state_t{})},
      {"NAV_INNOVATION", dec(ldv_lcm::nav_innovation_t{})}};
  std::map<std::string, ChannelSequence> out;
  std::map<std::string, int64_t> last;
  lcm::LogFile log(path, "r");
  if (!log.good()) return out;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    const auto it = types.find(e->channel);
    const Decode d = it != types.end() ? it->second
                     : e->channel.rfind("STATUS_", 0) == 0 ? dec(ldv_lcm::service_status_t{})
                                                           : Decode{};
    if (!d) continue;
    ChannelSequence& c = out[e->channel];
    const auto seq = d(e->data, e->datalen);
    if (!seq) {
      ++c.undecodable;
      continue;
    }
    ++c.messages;
    const auto l = last.find(e->channel);
    if (l != last.end()) {
      if (*seq > l->second + 1) {
        ++c.gaps;
        c.missing += *seq - l->second - 1;
        c.gap_at.push_back(*seq);
      } else if (*seq <= l->second) {
        ++c.resets;
      }
    }
    last[e->channel] = *seq;
  }
  return out;
}

}  // namespace ldv::test
