// Replay with Debian's own lcm-logplayer (issue 16; DESIGN.md: "lcm-logger records everything; lcm-logplayer
// replays it"). A short live run of the whole vehicle system (the simulated IMU time-stamp unit and GNSS
// receiver on ptys in real time, imu_acq, gnss_link, fusion, tspi_pub, the bus logger) is recorded; then
// lcm-logplayer plays its inputs (IMU, GNSS_SOLUTION, GNSS_PPS) at 8x real time into a freshly started
// fusion with the same configuration and a fresh tspi_pub, the logger records what fusion publishes, and:
//  - the replayed NAV equals the live NAV epoch for epoch: fusion's output depends only on its inputs and
//    their order (late fixes rewind the filter, so a NAV is the state given the fixes that had arrived; the
//    log keeps the logger's arrival order and lcm-logplayer keeps the log's order), not on their timing; where
//    the logger saw a fix one IMU message earlier or later than fusion did, one epoch differs and the next
//    is equal again (compare_epochs);
//  - a remote subscriber on the TSPI group receives the replayed TSPI, each equal to the replayed NAV at its epoch;
//  - `ldv nav --lcm-log` of the live log with the same configuration writes the live NAV, epoch for epoch (one
//    navigation session, estimator/run/nav_session.hpp, drives the filter live and offline).
// fusion runs with the non-holonomic constraint on (`ldv: {aids: [nhc]}`): a live run with an aid.
// The channel expression is grouped: LCM anchors it as ^(...)$; `IMU|GNSS_SOLUTION|GNSS_PPS` would anchor only
// its ends (^IMU matches IMU_PPS and IMU_TIMING too).
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ldv_lcm/nav_innovation_t.hpp>
#include <map>
#include <tuple>

#include "common/formats/kfgins_files.hpp"
#include "common/geo/earth_model.hpp"
#include "sim/simulator.hpp"
#include "tests/integration/vehicle_rig.hpp"

using namespace ldv;
namespace fs = std::filesystem;

namespace {
const std::string kBin = LDV_BIN_DIR;
const std::string kBusUrl = "udpm://239.255.76.67:7667?ttl=0";
const std::string kTspiUrl = "udpm://239.255.77.1:7668?ttl=1";
const std::string kLogplayer = "/usr/bin/lcm-logplayer";
constexpr double kDriveDuration_s = 40.0;

// Every message of one channel in an LCM log, decoded, in log order.
template <class Msg>
std::vector<Msg> read_channel(const std::string& path, const std::string& channel) {
  std::vector<Msg> out;
  lcm::LogFile log(path, "r");
  if (!log.good()) return out;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    if (e->channel != channel) continue;
    Msg m;
    if (m.decode(e->data, 0, e->datalen) >= 0) out.push_back(m);
  }
  return out;
}

// Two runs' NAV compared epoch by epoch. They must be equal to the last bit wherever both had seen the same
// inputs; at an epoch where one process saw a GNSS solution one IMU message earlier than the other, that one
// NAV differs (it includes the fix, the other gets it one epoch later through the same rewind), and the next
// epoch is equal again. Such a swap is the multicast's, not fusion's: imu_acq and gnss_link send from two
// processes, and on two cores the kernel may queue two datagrams sent at the same moment in a different order
// into the fusion's socket than into the logger's (seen under load: 1 epoch in 7584, 1.9 mm). So: every run of
// differing epochs is short (a few IMU messages) and followed by an equal epoch, and few epochs differ.
struct EpochDifferences {
  long differing = 0, longest_run = 0, runs_not_rejoined = 0;
  double max_pos_m = 0, max_vel_mps = 0, max_rpy_deg = 0;  // over the epochs that agree (must be ~0)
  double max_transient_pos_m = 0;                          // over the differing ones
};
template <class Diff>
EpochDifferences compare_epochs(size_t n, Diff diff_at, double pos_tol_m, double vel_tol_mps, double rpy_tol_deg) {
  EpochDifferences d;
  long run = 0;
  for (size_t k = 0; k < n; ++k) {
    const auto [pos_m, vel_mps, rpy_deg] = diff_at(k);
    const bool differs = pos_m > pos_tol_m || vel_mps > vel_tol_mps || rpy_deg > rpy_tol_deg;
    if (differs) {
      ++d.differing;
      d.longest_run = std::max(d.longest_run, ++run);
      d.max_transient_pos_m = std::max(d.max_transient_pos_m, pos_m);
      if (k + 1 == n) ++d.runs_not_rejoined;
    } else {
      run = 0;
      d.max_pos_m = std::max(d.max_pos_m, pos_m);
      d.max_vel_mps = std::max(d.max_vel_mps, vel_mps);
      d.max_rpy_deg = std::max(d.max_rpy_deg, rpy_deg);
    }
  }
  return d;
}
void expect_equal_but_for_swaps(const EpochDifferences& d, size_t n, const char* what) {
  std::printf("%s: %ld of %zu epochs differ (longest run %ld, largest %.3g m), the rest agree to %.3g m, %.3g m/s, "
              "%.3g deg\n",
              what, d.differing, n, d.longest_run, d.max_transient_pos_m, d.max_pos_m, d.max_vel_mps, d.max_rpy_deg);
  EXPECT_LE(d.longest_run, 3) << what;
  EXPECT_EQ(d.runs_not_rejoined, 0) << what;
  EXPECT_LE(d.differing, static_cast<long>(n / 200)) << what;
}

// Events per channel in an LCM log.
std::map<std::string, long> channel_counts(const std::string& path) {
  std::map<std::string, long> out;
  lcm::LogFile log(path, "r");
  if (!log.good()) return out;
  while (const lcm::LogEvent* e = log.readNextEvent()) ++out[e->channel];
  return out;
}

Geodetic position_of(const ldv_lcm::nav_state_t& m) {
  return {m.lat_deg * kDegToRad, m.lon_deg * kDegToRad, m.height_m};
}

bool contiguous(const std::vector<ldv_lcm::nav_state_t>& v) {
  for (size_t i = 1; i < v.size(); ++i)
    if (v[i].seq != v[i - 1].seq + 1) return false;
  return !v.empty() && v.front().seq == 0;
}
}  // namespace

TEST(
    LogplayerReplay,
    GivenALiveRunWithNhcsLog_WhenReplayedByLcmLogplayerAndByLdvNav_ThenBothEqualTheLiveNavAndTspiReachesARemoteSubscriber) {
  const fs::path dir = fs::temp_directory_path() / ("ldv_logplayer_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "sim");
  std::ofstream(dir / "scenario.yaml") << test::kShortDriveScenario;

  // Given a tactical-grade drive whose GPS time starts a little after now (a vehicle's host clock is GPS time)
  const double start_total_s = std::ceil(test::gps_total_seconds_now() + 10.0);
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.seed = 16;
  req.duration_s = kDriveDuration_s;
  req.scenario = (dir / "scenario.yaml").string();
  req.gnss_rate_hz = 5.0;
  req.gps_week = static_cast<int>(start_total_s / kSecondsPerWeek);
  req.start_sow_s = start_total_s - req.gps_week * kSecondsPerWeek;
  if (req.start_sow_s + kDriveDuration_s + 5 > kSecondsPerWeek) GTEST_SKIP() << "too close to the end of the GPS week";
  sim::SimResult sim = sim::simulate(req);
  sim::write_outputs(sim, (dir / "sim").string());
  double first_chunk_sow = 0;
  {
    std::ifstream in(dir / "sim" / "device_schedule.txt");
    for (std::string line; std::getline(in, line);)
      if (!line.empty() && line[0] != '#') {
        first_chunk_sow = std::stod(line);
        break;
      }
  }
  const double start_delay_s = req.gps_week * kSecondsPerWeek + first_chunk_sow - test::gps_total_seconds_now();
  ASSERT_GT(start_delay_s, 1.0) << "the simulation took longer than the lead time";

  // And the services configured as deployed (fusion without a warm-start file: a replay started within
  // warm_start_max_age_s of the live run would resume from the live run's last state instead of aligning)
  const std::string imu_tty = (dir / "imu_tty").string(), gnss_tty = (dir / "gnss_tty").string();
  std::ofstream(dir / "imu_acq.yaml")
      << "bus_url: \"" << kBusUrl << "\"\ninput: {type: serial, serial: {device: " << imu_tty
      << ", baud: 460800}}\nprotocol: tsu\ntsu: {counter_hz: 10.0e6}\nsample_rate_hz: 200\n"
      << "pps: {source: device, label_refers: auto}\n";
  std::ofstream(dir / "gnss_link.yaml") << "bus_url: \"" << kBusUrl
                                        << "\"\ninput: {type: serial, serial: {device: " << gnss_tty
                                        << ", baud: 115200}}\nprotocol: nmea\ngps_minus_utc_s: 18\n";
  // The simulator's configuration with the non-holonomic constraint on (the simulated car does not slip).
  const std::string kfgins_nhc = (dir / "kfgins_nhc.yaml").string();
  {
    YAML::Node k = YAML::LoadFile((dir / "sim" / "kfgins.yaml").string());
    k["ldv"]["aids"].push_back("nhc");
    std::ofstream(kfgins_nhc) << k << "\n";
  }
  std::ofstream(dir / "fusion.yaml") << "bus_url: \"" << kBusUrl << "\"\nkfgins_config: " << kfgins_nhc
                                     << "\nhistory_s: 3.0\n";
  std::ofstream(dir / "tspi_pub.yaml") << "bus_url: \"" << kBusUrl
                                       << "\"\ntspi: {rate_hz: 20, group: 239.255.77.1, port: 7668, ttl: 1}\n";
  auto service = [&](const std::string& name, const std::string& log_name) {
    return test::start_logged(kBin + "/" + name, {"--config", (dir / (name + ".yaml")).string()},
                              (dir / log_name).string());
  };

  // When the live run is recorded
  const std::string live_log = (dir / "live.lcmlog").string();
  {
    auto logger =
        test::start_logged(kBin + "/ldv_logger", {"--lcm-url", kBusUrl, live_log}, (dir / "live_logger.log").string());
    test::BusWatch w(kBusUrl, kTspiUrl);
    auto drive = test::start_logged(kBin + "/ldv",
                                    {"drive", (dir / "sim").string(), "--imu-link", imu_tty, "--gnss-link", gnss_tty,
                                     "--start-delay", std::to_string(start_delay_s - 0.1)},
                                    (dir / "drive.log").string());
    w.spin(0.3);
    std::vector<std::unique_ptr<test::ChildProcess>> svc;
    for (const char* name : {"imu_acq", "gnss_link", "fusion", "tspi_pub"})
      svc.push_back(service(name, std::string("live_") + name + ".log"));
    // Until the drive has been played and fusion has published its last NAV
    w.spin(start_delay_s + kDriveDuration_s + 30.0, [&] { return drive->wait_exit(0.01) != 1000; });
    w.spin(10.0, [&] { return w.nav_count > 0 && test::steady_s() - w.last_nav_rx_s > 1.5; });
    for (auto& p : svc) p->signal(SIGTERM);
    for (auto& p : svc) EXPECT_EQ(p->wait_exit(5.0), 0);
    logger->signal(SIGTERM);
    EXPECT_EQ(logger->wait_exit(5.0), 0);
  }
  const auto live_nav = read_channel<ldv_lcm::nav_state_t>(live_log, "NAV");
  ASSERT_GT(live_nav.size(), 200u * 20u) << "live NAV for at least 20 s of driving (see " << dir << "/live_*.log)";
  ASSERT_TRUE(contiguous(live_nav)) << "the live log lost NAV messages: it cannot be compared epoch for epoch";
  const auto live_counts = channel_counts(live_log);
  for (const char* ch : {"IMU", "GNSS_SOLUTION", "GNSS_PPS", "IMU_PPS", "IMU_TIMING"})
    ASSERT_TRUE(live_counts.count(ch)) << ch;

  // And lcm-logplayer replays its inputs at 8x real time into a fresh fusion (and tspi_pub), recorded (the test is
  // about equality, which holds at any pace fusion keeps up with; 2x only made it wait)
  const std::string replay_log = (dir / "replay.lcmlog").string();
  std::vector<ldv_lcm::tspi_v1_t> remote_tspi;
  {
    auto logger = test::start_logged(kBin + "/ldv_logger", {"--lcm-url", kBusUrl, replay_log},
                                     (dir / "replay_logger.log").string());
    test::BusWatch w(kBusUrl, kTspiUrl);
    auto fusion = service("fusion", "replay_fusion.log");
    auto tspi = service("tspi_pub", "replay_tspi_pub.log");
    // Play only once everybody listens (each heartbeat follows its subscriptions).
    ASSERT_TRUE(w.spin(30.0, [&] {
      return w.latest("STATUS_FUSION") && w.latest("STATUS_TSPI_PUB") && w.latest("STATUS_LOGGER");
    })) << "heartbeats of fusion, tspi_pub and the logger within 30 s";
    test::ChildProcess player("/bin/sh",
                              {"-c", "exec \"$0\" \"$@\" >>'" + (dir / "logplayer.log").string() + "' 2>&1", kLogplayer,
                               "--lcm-url=" + kBusUrl, "-e", "(IMU|GNSS_SOLUTION|GNSS_PPS)", "--speed", "8", live_log});
    int played = 1000;
    w.spin(kDriveDuration_s + 60.0, [&] { return (played = player.wait_exit(0.01)) != 1000; });
    EXPECT_EQ(played, 0) << "lcm-logplayer (see " << dir << "/logplayer.log)";
    w.spin(10.0, [&] { return w.nav_count > 0 && test::steady_s() - w.last_nav_rx_s > 1.5; });
    for (auto* p : {fusion.get(), tspi.get()}) p->signal(SIGTERM);
    EXPECT_EQ(fusion->wait_exit(5.0), 0);
    EXPECT_EQ(tspi->wait_exit(5.0), 0);
    logger->signal(SIGTERM);
    EXPECT_EQ(logger->wait_exit(5.0), 0);
    for (const auto& t : w.tspi) remote_tspi.push_back(t.m);
  }

  // Then the replay carried the inputs only (the channels only the live devices and services had are absent)
  const auto replay_counts = channel_counts(replay_log);
  for (const char* ch : {"IMU_PPS", "IMU_TIMING", "STATUS_IMU_ACQ", "STATUS_GNSS_LINK"})
    EXPECT_FALSE(replay_counts.count(ch)) << ch;
  for (const char* ch : {"IMU", "GNSS_SOLUTION", "GNSS_PPS"})
    EXPECT_EQ(replay_counts.count(ch) ? replay_counts.at(ch) : 0, live_counts.at(ch)) << ch << " played completely";

  // And the replayed NAV is the live NAV, epoch for epoch
  const auto replay_nav = read_channel<ldv_lcm::nav_state_t>(replay_log, "NAV");
  ASSERT_TRUE(contiguous(replay_nav)) << "the replay log lost NAV messages";
  EXPECT_EQ(replay_nav.size(), live_nav.size());
  std::map<std::pair<int, double>, const ldv_lcm::nav_state_t*> replay_at;
  for (const auto& m : replay_nav) replay_at[{m.gps_week, m.gps_sow_s}] = &m;
  long missing = 0;
  for (const auto& a : live_nav) missing += !replay_at.count({a.gps_week, a.gps_sow_s});
  std::printf("live NAV %zu, replayed NAV %zu (%.3f .. %.3f s of week); not replayed %ld\n", live_nav.size(),
              replay_nav.size(), live_nav.front().gps_sow_s, live_nav.back().gps_sow_s, missing);
  ASSERT_EQ(missing, 0);
  // The same arithmetic on the same inputs in the same order: equal to the last bit (1e-9 m as for checkpoints),
  // std, status and mode included.
  double max_std = 0;
  long status_differs = 0;
  const EpochDifferences replayed = compare_epochs(
      live_nav.size(),
      [&](size_t k) {
        const auto& a = live_nav[k];
        const auto& b = *replay_at.at({a.gps_week, a.gps_sow_s});
        double vel = 0, rpy = 0, sd = 0;
        for (int i = 0; i < 3; ++i) {
          vel = std::max(vel, std::abs(a.vel_ned_mps[i] - b.vel_ned_mps[i]));
          rpy = std::max(rpy, std::abs(std::remainder(a.rpy_deg[i] - b.rpy_deg[i], 360.0)));
          sd = std::max({sd, std::abs(double(a.pos_std_ned_m[i]) - b.pos_std_ned_m[i]),
                         std::abs(double(a.vel_std_ned_mps[i]) - b.vel_std_ned_mps[i]),
                         std::abs(double(a.att_std_deg[i]) - b.att_std_deg[i])});
        }
        const double pos = earth::ned_between(position_of(a), position_of(b)).norm();
        // std, status and mode are compared where the state agrees (a swapped fix changes them too)
        if (pos <= 1e-9 && vel <= 1e-12 && rpy <= 1e-12) {
          max_std = std::max(max_std, sd);
          status_differs += a.status != b.status || a.mode != b.mode;
        }
        return std::tuple{pos, vel, rpy};
      },
      1e-9, 1e-12, 1e-12);
  expect_equal_but_for_swaps(replayed, live_nav.size(), "replayed NAV against live");
  EXPECT_EQ(max_std, 0.0);
  EXPECT_EQ(status_differs, 0);

  // And NAV_INNOVATION carried the aid's updates live
  long nhc_innovations = 0;
  for (const auto& m : read_channel<ldv_lcm::nav_innovation_t>(live_log, "NAV_INNOVATION"))
    nhc_innovations += m.sensor == 5;
  EXPECT_GT(nhc_innovations, 100) << "NHC updates (sensor 5) published live";

  // And `ldv nav --lcm-log` of the live log, with fusion's configuration, writes the live NAV epoch for epoch
  const std::string offline_nav = (dir / "offline.nav").string();
  {
    auto nav = test::start_logged(kBin + "/ldv",
                                  {"nav", "--lcm-log", live_log, "--kfgins-config", kfgins_nhc, "--out", offline_nav},
                                  (dir / "ldv_nav.log").string());
    ASSERT_EQ(nav->wait_exit(120.0), 0) << "ldv nav --lcm-log (see " << dir << "/ldv_nav.log)";
  }
  const std::vector<NavRecord> offline = read_nav(offline_nav);
  ASSERT_EQ(offline.size(), live_nav.size());
  double off_sow_s = 0;
  long off_missing = 0;
  for (size_t k = 0; k < live_nav.size(); ++k) {  // epoch for epoch, in order
    off_sow_s = std::max(off_sow_s, std::abs(live_nav[k].gps_sow_s - offline[k].sow_s));
    off_missing += live_nav[k].gps_week != offline[k].week;
  }
  std::printf("ldv nav --lcm-log: %zu epochs, %ld with another week, times differ by up to %.3g s\n", offline.size(),
              off_missing, off_sow_s);
  EXPECT_EQ(off_missing, 0);
  EXPECT_LE(off_sow_s, 1e-6);
  // Equal within what the .nav prints (1e-11 deg of latitude and longitude, 1e-5 m of height, 1e-6 m/s, 1e-8 deg),
  // but for swaps as above (the log holds the logger's order).
  const EpochDifferences offline_vs_live = compare_epochs(
      live_nav.size(),
      [&](size_t k) {
        const auto& a = live_nav[k];
        const NavRecord& b = offline[k];
        double vel = 0, rpy = 0;
        for (int i = 0; i < 3; ++i) {
          vel = std::max(vel, std::abs(a.vel_ned_mps[i] - b.vel_n_mps[i]));
          rpy = std::max(rpy, std::abs(std::remainder(a.rpy_deg[i] - b.rpy_rad[i] * kRadToDeg, 360.0)));
        }
        return std::tuple{earth::ned_between(position_of(a), b.pos).norm(), vel, rpy};
      },
      2e-5, 1e-6, 1e-7);
  expect_equal_but_for_swaps(offline_vs_live, live_nav.size(), "ldv nav --lcm-log against live");

  // And the remote TSPI subscriber received the replay's TSPI, each the replayed NAV of its epoch
  ASSERT_GT(remote_tspi.size(), 20u * 20u) << "TSPI at 20 Hz for at least 20 s of driving";
  long tspi_not_nav = 0;
  for (size_t i = 0; i < remote_tspi.size(); ++i) {
    const auto& t = remote_tspi[i];
    EXPECT_EQ(t.seq, static_cast<int64_t>(i)) << "TSPI sequence from the fresh tspi_pub";
    const auto it = replay_at.find({t.gps_week, t.gps_sow_s});
    tspi_not_nav += it == replay_at.end() || it->second->lat_deg != t.lat_deg || it->second->lon_deg != t.lon_deg ||
                    it->second->height_m != t.height_m;
  }
  std::printf("remote TSPI subscriber: %zu messages, %ld not equal to the replayed NAV of their epoch\n",
              remote_tspi.size(), tspi_not_nav);
  EXPECT_EQ(tspi_not_nav, 0);
  if (!HasFailure()) fs::remove_all(dir);
}
