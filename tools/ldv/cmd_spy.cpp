// `ldv spy`: a terminal view of the bus (Debian's lcm-spy does not start with Java 17).
// Channels, message counts, rates, sequence gaps, malformed messages, and the decoded latest
// values of our own types (recognised by their LCM fingerprint, whatever the channel name).
#include <chrono>
#include <cmath>
#include <cstring>
#include <ldv_lcm/gnss_solution_t.hpp>
#include <ldv_lcm/imu_sample_t.hpp>
#include <ldv_lcm/imu_timing_t.hpp>
#include <ldv_lcm/nav_innovation_t.hpp>
#include <ldv_lcm/nav_state_t.hpp>
#include <ldv_lcm/pps_event_t.hpp>
#include <ldv_lcm/service_status_t.hpp>
#include <ldv_lcm/tspi_v1_t.hpp>
#include <ldv_lcm/wheel_speed_t.hpp>
#include <map>
#include <sstream>
#include <thread>

#include "common/bus/bus.hpp"
#include "common/bus/decode_message.hpp"
#include "common/bus/lcm_log_reader.hpp"
#include "common/bus/message_conversions.hpp"
#include "services/fusion/nav_message.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"

namespace ldv::cli {
namespace {

struct ChannelView {
  std::string type = "?";
  long count = 0;
  long malformed = 0;
  SequenceTracker seq;
  std::string latest;
  std::vector<double> arrivals_s;  // recent arrival times for the rate
};

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

int64_t fingerprint_of(const uint8_t* data, int size) {
  if (size < 8) return 0;
  uint64_t h = 0;
  for (int i = 0; i < 8; ++i) h = (h << 8) | data[i];
  return static_cast<int64_t>(h);
}

std::string fixed(double v, int d) {
  std::ostringstream o;
  o.setf(std::ios::fixed);
  o.precision(d);
  o << v;
  return o.str();
}

// Decodes one message of a known type into (type name, one-line summary, seq); false if unknown.
bool describe(const uint8_t* data, int size, std::string& type, std::string& text, int64_t& seq, bool& bad) {
  bad = false;
  const int64_t fp = fingerprint_of(data, size);
  auto decode = [&](auto& m) {
    if (!decode_message(data, size, m)) {
      bad = true;
      return false;
    }
    seq = m.seq;
    return true;
  };
  if (fp == ldv_lcm::imu_sample_t::getHash()) {
    ldv_lcm::imu_sample_t m{};
    type = "imu_sample_t";
    if (!decode(m)) return true;
    text = "sow " + fixed(m.gps_sow_s, 4) + " dt " + fixed(m.dt_s * 1e3, 3) + " ms  |w| " +
           fixed(std::sqrt(m.dtheta_b_rad[0] * m.dtheta_b_rad[0] + m.dtheta_b_rad[1] * m.dtheta_b_rad[1] +
                           m.dtheta_b_rad[2] * m.dtheta_b_rad[2]) / std::max(m.dt_s, 1e-9) * 57.29578, 2) +
           " deg/s  |f| " +
           fixed(std::sqrt(m.dvel_b_mps[0] * m.dvel_b_mps[0] + m.dvel_b_mps[1] * m.dvel_b_mps[1] +
                           m.dvel_b_mps[2] * m.dvel_b_mps[2]) / std::max(m.dt_s, 1e-9), 3) + " m/s2";
  } else if (fp == ldv_lcm::gnss_solution_t::getHash()) {
    ldv_lcm::gnss_solution_t m{};
    type = "gnss_solution_t";
    if (!decode(m)) return true;
    text = "sow " + fixed(m.gps_sow_s, 3) + " " + fixed(m.lat_deg, 8) + " " + fixed(m.lon_deg, 8) + " " +
           fixed(m.height_m, 3) + " Q" + std::to_string(m.fix_quality) + " ns " + std::to_string(m.num_sats) +
           " sdN " + fixed(std::sqrt(std::max(0.0, m.pos_cov_ned_m2[0])), 3);
  } else if (fp == ldv_lcm::nav_state_t::getHash()) {
    ldv_lcm::nav_state_t m{};
    type = "nav_state_t";
    if (!decode(m)) return true;
    text = "sow " + fixed(m.gps_sow_s, 3) + " " + fixed(m.lat_deg, 8) + " " + fixed(m.lon_deg, 8) + " " +
           fixed(m.height_m, 3) + " v " + fixed(m.vel_ned_mps[0], 2) + " " + fixed(m.vel_ned_mps[1], 2) + " " +
           fixed(m.vel_ned_mps[2], 2) + " yaw " + fixed(m.rpy_deg[2], 2) + " mode " + std::to_string(m.mode) +
           " status 0x" + [&] { std::ostringstream o; o << std::hex << m.status; return o.str(); }();
  } else if (fp == ldv_lcm::tspi_v1_t::getHash()) {
    ldv_lcm::tspi_v1_t m{};
    type = "tspi_v1_t";
    if (!decode(m)) return true;
    text = "sow " + fixed(m.gps_sow_s, 3) + " " + fixed(m.lat_deg, 8) + " " + fixed(m.lon_deg, 8) + " " +
           fixed(m.height_m, 3) + " std_h " + fixed(std::hypot(m.pos_std_ned_m[0], m.pos_std_ned_m[1]), 3) +
           " q " + std::to_string(m.quality);
  } else if (fp == ldv_lcm::nav_innovation_t::getHash()) {
    ldv_lcm::nav_innovation_t m{};
    type = "nav_innovation_t";
    if (!decode(m)) return true;
    text = "sow " + fixed(m.gps_sow_s, 3) + " " + sensor_of_code(m.sensor) + " (" + std::to_string(m.dim) +
           " rows) nis " + fixed(m.nis, 2) + (m.accepted ? " accepted" : " REJECTED");
  } else if (fp == ldv_lcm::wheel_speed_t::getHash()) {
    ldv_lcm::wheel_speed_t m{};
    type = "wheel_speed_t";
    if (!decode(m)) return true;
    const auto v = odometer_speed_from_message(m);
    text = "sow " + fixed(m.gps_sow_s, 3) + " " + std::to_string(m.num_wheels) + " wheel(s) odometer " +
           (v ? fixed(*v, 3) + " m/s" : std::string("unusable")) + " status " + std::to_string(m.status);
  } else if (fp == ldv_lcm::pps_event_t::getHash()) {
    ldv_lcm::pps_event_t m{};
    type = "pps_event_t";
    if (!decode(m)) return true;
    text = "sow " + fixed(m.gps_sow_s, 3) + " counter " + std::to_string(m.counter_raw) + " flags " +
           std::to_string(m.flags);
  } else if (fp == ldv_lcm::service_status_t::getHash()) {
    ldv_lcm::service_status_t m{};
    type = "service_status_t";
    if (!decode(m)) return true;
    text = m.name + " state " + std::to_string(m.state) + " rx " + std::to_string(m.received) + " drop " +
           std::to_string(m.dropped) + " bad " + std::to_string(m.malformed) + " faults 0x" +
           [&] { std::ostringstream o; o << std::hex << m.fault_bits; return o.str(); }() + " cpu " +
           fixed(m.cpu_s, 2) + " s";
  } else if (fp == ldv_lcm::imu_timing_t::getHash()) {
    ldv_lcm::imu_timing_t m{};
    type = "imu_timing_t";
    if (!decode(m)) return true;
    text = "interval " + fixed(m.interval_mean_s * 1e3, 5) + " ms +- " + fixed(m.interval_std_s * 1e6, 2) +
           " us  drift " + fixed(m.clock_drift_ppm, 2) + " ppm  missing PPS " + std::to_string(m.missing_pps);
  } else {
    return false;
  }
  return true;
}

void print_table(const std::map<std::string, ChannelView>& channels, double now, bool clear) {
  if (clear) std::printf("\033[H\033[2J");
  std::printf("%-18s %-18s %9s %8s %6s %5s  %s\n", "channel", "type", "count", "rate Hz", "gaps", "bad", "latest");
  for (const auto& [name, v] : channels) {
    double rate = 0;
    size_t n = 0;
    for (double t : v.arrivals_s)
      if (t > now - 2.0) ++n;
    rate = n / 2.0;
    std::printf("%-18s %-18s %9ld %8.1f %6ld %5ld  %s\n", name.c_str(), v.type.c_str(), v.count, rate,
                static_cast<long>(v.seq.lost()), v.malformed, v.latest.c_str());
  }
  std::fflush(stdout);
}

void add_spy_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("spy", "terminal view of the LCM bus: channels, rates, gaps, decoded latest values");
  static std::string url;
  static double duration_s = 0;
  static bool once = false;
  cmd->add_option("--url", url,
                  "LCM URL (default: LCM_DEFAULT_URL or LCM's default); file://LOG reads a recorded log to its end");
  cmd->add_option("--duration", duration_s, "stop after this many seconds (0: until Ctrl-C)")
      ->check(ldv::cli::finite_range(0, 1e7));
  cmd->add_flag("--once", once, "print one table at the end instead of refreshing the screen");
  cmd->callback([] {
    std::map<std::string, ChannelView> channels;
    auto take = [&](const std::string& channel, const uint8_t* data, int size, double arrival_s) {
      auto& v = channels[channel];
      ++v.count;
      v.arrivals_s.push_back(arrival_s);
      if (v.arrivals_s.size() > 4000) v.arrivals_s.erase(v.arrivals_s.begin(), v.arrivals_s.begin() + 2000);
      std::string type, text;
      int64_t seq = 0;
      bool bad = false;
      if (describe(data, size, type, text, seq, bad)) {
        v.type = type;
        if (bad) {
          ++v.malformed;
        } else {
          v.seq.observe(seq);
          v.latest = text;
        }
      } else {
        v.type = "(not ours)";
        v.latest = std::to_string(size) + " bytes";
      }
    };
    // A recorded log (file://PATH[?options]) is read with our own reader: LCM's file provider trusts the length
    // fields (a corrupt 2 GB event crashed it) and never ends. Rates are over the logger's receive times.
    if (url.rfind("file://", 0) == 0) {
      const size_t query = url.find('?');
      const std::string path = url.substr(7, query == std::string::npos ? std::string::npos : query - 7);
      LcmLogReader log(path);
      LcmLogEvent ev;
      double last_s = 0.0;
      while (log.next(ev)) {
        last_s = ev.timestamp_us * 1e-6;
        take(ev.channel, ev.data.data(), static_cast<int>(ev.data.size()), last_s);
      }
      print_table(channels, last_s, false);
      if (log.corrupt_events() + log.truncated_events() > 0)
        std::printf("%s: %ld corrupt log events skipped, %ld cut short at the end\n", path.c_str(),
                    log.corrupt_events(), log.truncated_events());
      return;
    }
    Bus bus(url);
    bus.subscribe_raw(
        ".*", [&](const std::string& channel, const uint8_t* data, int size) { take(channel, data, size, now_s()); });
    const double start = now_s();
    double next_print = start + 1.0;
    while (duration_s <= 0 || now_s() - start < duration_s) {
      bus.handle(50);
      if (!once && now_s() >= next_print) {
        print_table(channels, now_s(), true);
        next_print += 1.0;
      }
    }
    print_table(channels, now_s(), false);
  });
}

const RegisterCommand kRegisterSpyCommand{"spy", &add_spy_command};

}  // namespace
}  // namespace ldv::cli
