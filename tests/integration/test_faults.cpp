// Faults on the whole vehicle system (issue 4, "what it must show"): the simulated IMU time-stamp
// unit and GNSS receiver in real time on ptys (`ldv drive`), imu_acq, gnss_link, fusion (with its
// warm-start state file; imu_acq with its saved PPS fit), tspi_pub and the bus logger (ldv_logger), in a private
// network namespace. The vehicle's GPS time is the host's (a vehicle host clock is GPS/NTP-disciplined). During
// the drive:
//  - each service in turn is killed with SIGKILL and started again 200 ms later (systemd's
//    Restart=on-failure, RestartSec=200ms): TSPI flows again within 2 s of the restart;
//  - imu_acq once more, back only 2.5 s later (a device slow to come back): the fixes of the hole hold TSPI;
//  - before the kills, a 20 m GNSS jump (below gnss_link's 30 m gate) reaches fusion: its innovation gate rejects it,
//    the heartbeat counts it, TSPI stays accurate;
//  - messages with wrong LCM fingerprints on IMU, GNSS_SOLUTION, GNSS_PPS and NAV: counted in the
//    heartbeats (malformed), rejected, everybody keeps running;
// and afterwards the logger's file has no sequence gap on any channel, and sequence resets only on
// the channels of the killed service.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

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
constexpr double kGnssRate_hz = 5.0;
constexpr double kDriveDuration_s = 66.0;
// Events, in seconds of drive time (sim time since the start).
constexpr double kNavigatingBy_s = 20.0;
constexpr double kJumpAt_s = 17.0;  // navigating and settled, before the kills
constexpr double kJump_m = 20.0;
struct Kill {
  std::string service;
  double at_s, restart_after_s;
};
const std::vector<Kill> kKills{{"imu_acq", 23.0, 0.2},
                               {"gnss_link", 31.0, 0.2},
                               {"imu_acq", 37.0, 2.5},
                               {"fusion", 48.0, 0.2},
                               {"tspi_pub", 55.0, 0.2}};
constexpr double kFingerprintsAt_s = 58.5;
constexpr double kEnd_s = 62.5;

// Shifts the latitude of the GGA sentence nearest to `at_s` after the first one by `north_m`, keeping
// its length (the device schedule holds byte offsets). Returns the GPS time of day of that epoch.
double inject_gga_jump(const fs::path& nmea_path, double at_s, double north_m) {
  std::string text;
  {
    std::ifstream in(nmea_path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    text = ss.str();
  }
  auto tod = [](const std::string& hhmmss) {
    return std::stoi(hhmmss.substr(0, 2)) * 3600.0 + std::stoi(hhmmss.substr(2, 2)) * 60.0 + std::stod(hhmmss.substr(4));
  };
  std::optional<double> first_tod;
  size_t pos = 0;
  while ((pos = text.find("GGA,", pos)) != std::string::npos) {
    const size_t start = text.rfind('$', pos), star = text.find('*', pos);
    std::vector<std::string> f;
    std::stringstream fs_(text.substr(start, star - start));
    for (std::string x; std::getline(fs_, x, ',');) f.push_back(x);
    const double t = tod(f[1]);
    if (!first_tod) first_tod = t;
    if (t - *first_tod < at_s) {
      pos = star;
      continue;
    }
    // ddmm.mmmmmmm: add the jump in minutes of arc, same width
    const std::string& lat = f[2];
    const size_t dot = lat.find('.');
    const int decimals = static_cast<int>(lat.size() - dot - 1);
    const double deg = std::stod(lat.substr(0, dot - 2));
    const double min = std::stod(lat.substr(dot - 2)) + north_m / 1852.0 * (f[3] == "S" ? -1.0 : 1.0);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%0*.0f%0*.*f", static_cast<int>(dot - 2), deg, decimals + 3, decimals, min);
    if (std::string(buf).size() != lat.size()) throw std::runtime_error("latitude width changed");
    const size_t lat_at = text.find(lat, start);
    text.replace(lat_at, lat.size(), buf);
    unsigned char cs = 0;
    for (size_t i = start + 1; i < star; ++i) cs ^= static_cast<unsigned char>(text[i]);
    std::snprintf(buf, sizeof buf, "%02X", cs);
    text.replace(star + 1, 2, buf);
    std::ofstream(nmea_path, std::ios::binary) << text;
    return t + 18.0;  // GPS time of day
  }
  throw std::runtime_error("no GGA at the requested time");
}

struct Truth {
  std::map<double, NavRecord> by_sow;
  std::optional<NavRecord> at(double sow) const {
    auto it = by_sow.lower_bound(sow - 0.0026);
    if (it == by_sow.end() || std::abs(it->first - sow) > 0.0026) return std::nullopt;
    return it->second;
  }
};

double horizontal_error_m(const Truth& truth, const ldv_lcm::tspi_v1_t& t) {
  const auto r = truth.at(t.gps_sow_s);
  if (!r) return NAN;
  const Vec3 d = earth::ned_between(r->pos, {t.lat_deg * kDegToRad, t.lon_deg * kDegToRad, t.height_m});
  return d.head<2>().norm();
}

std::string channel_owner(const std::string& ch) {
  static const std::map<std::string, std::string> owners{
      {"IMU", "imu_acq"},         {"IMU_PPS", "imu_acq"},          {"IMU_TIMING", "imu_acq"}, {"STATUS_IMU_ACQ", "imu_acq"},
      {"GNSS_SOLUTION", "gnss_link"}, {"GNSS_PPS", "gnss_link"},   {"STATUS_GNSS_LINK", "gnss_link"},
      {"NAV", "fusion"},          {"NAV_INNOVATION", "fusion"},    {"STATUS_FUSION", "fusion"},
      {"STATUS_TSPI_PUB", "tspi_pub"}};
  const auto it = owners.find(ch);
  return it == owners.end() ? "" : it->second;
}
}  // namespace

TEST(Faults, GivenTheVehicleSystem_WhenEachServiceIsKilledAndBadInputArrives_ThenTspiResumesWithin2sAndNothingElseIsLost) {
  const fs::path dir = fs::temp_directory_path() / ("ldv_faults_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "sim");
  std::ofstream(dir / "scenario.yaml") << test::kShortDriveScenario;

  // Given a tactical-grade drive whose GPS time starts a little after now
  const double lead_s = 12.0;
  const double start_total_s = std::ceil(test::gps_total_seconds_now() + lead_s);
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.seed = 21;
  req.duration_s = kDriveDuration_s;
  req.scenario = (dir / "scenario.yaml").string();
  req.gnss_rate_hz = kGnssRate_hz;
  req.gps_week = static_cast<int>(start_total_s / kSecondsPerWeek);
  req.start_sow_s = start_total_s - req.gps_week * kSecondsPerWeek;
  if (req.start_sow_s + kDriveDuration_s + 5 > kSecondsPerWeek) GTEST_SKIP() << "too close to the end of the GPS week";
  sim::SimResult sim = sim::simulate(req);
  sim::write_outputs(sim, (dir / "sim").string());
  const double jump_gps_tod_s = inject_gga_jump(dir / "sim" / "gnss.nmea", kJumpAt_s, kJump_m);
  Truth truth;
  for (const auto& r : read_nav((dir / "sim" / "truth.nav").string())) truth.by_sow[r.sow_s] = r;
  double first_chunk_sow = 0;
  {
    std::ifstream in(dir / "sim" / "device_schedule.txt");
    for (std::string line; std::getline(in, line);)
      if (!line.empty() && line[0] != '#') {
        first_chunk_sow = std::stod(line);
        break;
      }
  }
  const double first_chunk_total_s = req.gps_week * kSecondsPerWeek + first_chunk_sow;
  const double start_delay_s = first_chunk_total_s - test::gps_total_seconds_now();
  ASSERT_GT(start_delay_s, 1.0) << "the simulation took longer than the lead time";

  // And the services configured as deploy/config, on the ptys of `ldv drive`
  const std::string imu_tty = (dir / "imu_tty").string(), gnss_tty = (dir / "gnss_tty").string();
  std::ofstream(dir / "imu_acq.yaml") << "bus_url: \"" << kBusUrl << "\"\ninput: {type: serial, serial: {device: " << imu_tty
                                      << ", baud: 460800}}\nprotocol: tsu\ntsu: {counter_hz: 10.0e6}\nsample_rate_hz: 200\n"
                                      << "pps: {source: device, label_refers: auto}\nfit_state_file: "
                                      << (dir / "pps_fit.yaml").string() << "\n";
  std::ofstream(dir / "gnss_link.yaml") << "bus_url: \"" << kBusUrl << "\"\ninput: {type: serial, serial: {device: " << gnss_tty
                                        << ", baud: 115200, reopen_min_s: 0.1}}\nprotocol: nmea\ngps_minus_utc_s: 18\n";
  std::ofstream(dir / "fusion.yaml") << "bus_url: \"" << kBusUrl << "\"\nkfgins_config: " << (dir / "sim" / "kfgins.yaml").string()
                                     << "\nhistory_s: 3.0\nstate_file: " << (dir / "fusion_state.yaml").string() << "\n";
  std::ofstream(dir / "tspi_pub.yaml") << "bus_url: \"" << kBusUrl << "\"\ntspi: {rate_hz: 20, group: 239.255.77.1, port: 7668, ttl: 1}\n";
  const std::map<std::string, std::vector<std::string>> args{
      {"imu_acq", {"--config", (dir / "imu_acq.yaml").string()}},
      {"gnss_link", {"--config", (dir / "gnss_link.yaml").string()}},
      {"fusion", {"--config", (dir / "fusion.yaml").string()}},
      {"tspi_pub", {"--config", (dir / "tspi_pub.yaml").string()}}};
  auto start = [&](const std::string& name) {
    return test::start_logged(kBin + "/" + name, args.at(name), (dir / (name + ".log")).string());
  };

  // When the logger, the devices and the services start
  const std::string log = (dir / "vehicle.lcmlog").string();
  // ldv_logger, not lcm-logger: LCM 1.3.1's lcm-logger keeps LCM's default 30-message queue and loses
  // messages when the host stalls it for a few tens of milliseconds (both were tried here).
  auto logger = test::start_logged(kBin + "/ldv_logger", {"--lcm-url", kBusUrl, log}, (dir / "logger.log").string());
  test::BusWatch w(kBusUrl, kTspiUrl);
  auto drive = test::start_logged(kBin + "/ldv",
                                  {"drive", (dir / "sim").string(), "--imu-link", imu_tty, "--gnss-link", gnss_tty,
                                   "--start-delay", std::to_string(start_delay_s - 0.1)},
                                  (dir / "drive.log").string());
  w.spin(0.3);
  std::map<std::string, std::unique_ptr<test::ChildProcess>> svc;
  for (const auto& [name, a] : args) svc[name] = start(name);
  const double drive_t0_steady = test::steady_s() + (first_chunk_total_s - test::gps_total_seconds_now());
  auto drive_time = [&] { return test::steady_s() - drive_t0_steady; };
  auto spin_until_drive_time = [&](double t) { w.spin(std::max(0.0, t - drive_time())); };

  // Then TSPI flows once the vehicle moves
  w.spin(kNavigatingBy_s + 2.0 - drive_time(), [&] { return !w.tspi.empty(); });
  ASSERT_FALSE(w.tspi.empty()) << "no TSPI by drive time " << drive_time() << " s (see " << dir << "/*.log)";
  std::printf("[ faults ] first TSPI at drive time %.2f s\n", w.tspi.front().rx_s - drive_t0_steady);

  // When each service is killed and restarted (200 ms later, or 2.5 s)
  struct Outcome {
    std::string name;
    double kill_s = 0.0, restart_s = 0.0;
    std::optional<double> tspi_after_restart_s;
    double max_tspi_gap_s = 0;
    double max_err_first_s = NAN, max_err_after_5s = NAN;
  };
  std::vector<Outcome> outcomes;
  bool fingerprints_sent = false;
  std::map<std::string, ldv_lcm::service_status_t> before_fingerprints;
  for (const auto& [name, at, restart_after_s] : kKills) {
    spin_until_drive_time(at);
    Outcome o;
    o.name = name;
    o.kill_s = test::steady_s();
    svc[name]->signal(SIGKILL);
    EXPECT_EQ(svc[name]->wait_exit(1.0), -SIGKILL);
    w.spin(restart_after_s);
    svc[name] = start(name);
    o.restart_s = test::steady_s();
    const size_t n_before = w.tspi.size();
    w.spin(5.0, [&] {
      for (size_t i = n_before; i < w.tspi.size(); ++i)
        if (w.tspi[i].rx_s > o.restart_s) return true;
      return false;
    });
    outcomes.push_back(o);
  }
  // And messages with wrong fingerprints arrive on the inputs of every service
  spin_until_drive_time(kFingerprintsAt_s);
  for (const char* ch : {"STATUS_IMU_ACQ", "STATUS_GNSS_LINK", "STATUS_FUSION", "STATUS_TSPI_PUB"})
    if (auto s = w.latest(ch)) before_fingerprints[ch] = *s;
  {
    ldv_lcm::pps_event_t wrong{};
    ldv_lcm::gnss_solution_t wrong_gnss{};
    for (int i = 0; i < 5; ++i) {
      w.vehicle.publish("IMU", wrong);
      w.vehicle.publish("GNSS_SOLUTION", wrong);
      w.vehicle.publish("NAV", wrong);
      w.vehicle.publish("GNSS_PPS", wrong_gnss);
      w.spin(0.05);
    }
    fingerprints_sent = true;
  }
  spin_until_drive_time(kEnd_s);
  w.spin(2.2);  // the next heartbeats

  for (auto& [name, p] : svc) p->signal(SIGTERM);
  for (auto& [name, p] : svc) EXPECT_EQ(p->wait_exit(5.0), 0) << name << " did not exit cleanly on SIGTERM";
  logger->signal(SIGTERM);
  EXPECT_EQ(logger->wait_exit(5.0), 0);
  drive->signal(SIGKILL);

  // Then TSPI came back within 2 s of every restart, accurate
  for (auto& o : outcomes) {
    double prev = o.kill_s - 1.0;
    for (const auto& t : w.tspi) {
      if (t.rx_s < o.kill_s - 1.0 || t.rx_s > o.restart_s + 8.0) continue;
      if (t.rx_s > prev) o.max_tspi_gap_s = std::max(o.max_tspi_gap_s, t.rx_s - prev);
      prev = t.rx_s;
      if (!o.tspi_after_restart_s && t.rx_s > o.restart_s) o.tspi_after_restart_s = t.rx_s - o.restart_s;
      const double err = horizontal_error_m(truth, t.m);
      if (t.rx_s > o.restart_s && t.rx_s < o.restart_s + *o.tspi_after_restart_s + 1.0 && std::isfinite(err))
        o.max_err_first_s = std::isnan(o.max_err_first_s) ? err : std::max(o.max_err_first_s, err);
      if (t.rx_s > o.restart_s + 5.0 && std::isfinite(err))
        o.max_err_after_5s = std::isnan(o.max_err_after_5s) ? err : std::max(o.max_err_after_5s, err);
    }
    std::printf(
        "[ kill -9 %-9s ] restart %.0f ms later; first TSPI %.3f s after the restart (%.3f s after the kill); "
        "longest TSPI gap %.3f s; horizontal error: first second %.3f m, from 5 s on %.3f m\n",
        o.name.c_str(), (o.restart_s - o.kill_s) * 1e3, o.tspi_after_restart_s.value_or(NAN),
        o.tspi_after_restart_s.value_or(NAN) + o.restart_s - o.kill_s, o.max_tspi_gap_s, o.max_err_first_s,
        o.max_err_after_5s);
    ASSERT_TRUE(o.tspi_after_restart_s) << o.name;
    EXPECT_LT(*o.tspi_after_restart_s, 2.0) << o.name;
    EXPECT_LT(o.max_err_first_s, 2.0) << o.name;
    // A gnss_link restart takes the PPS labels away for a moment (imu_acq holds over on its fit); an imu_acq
    // restart resumes on its saved fit (fit_state_file), so its stamps stay on GPS time throughout.
    EXPECT_LT(o.max_err_after_5s, o.name == "gnss_link" ? 0.5 : 0.3) << o.name;
  }

  // And TSPI's sequence reset only when tspi_pub restarted, with no gap otherwise
  int tspi_resets = 0, tspi_gaps = 0;
  for (size_t i = 1; i < w.tspi.size(); ++i) {
    if (w.tspi[i].m.seq <= w.tspi[i - 1].m.seq) ++tspi_resets;
    else if (w.tspi[i].m.seq != w.tspi[i - 1].m.seq + 1) ++tspi_gaps;
  }
  double sum2 = 0;
  int n = 0;
  for (const auto& t : w.tspi)
    if (const double e = horizontal_error_m(truth, t.m); std::isfinite(e) && t.rx_s - drive_t0_steady > kNavigatingBy_s) {
      sum2 += e * e;
      ++n;
    }
  std::printf("[ faults ] TSPI: %zu messages, %d resets, %d gaps, horizontal RMS vs truth %.3f m (%d compared)\n", w.tspi.size(),
              tspi_resets, tspi_gaps, std::sqrt(sum2 / std::max(n, 1)), n);
  EXPECT_EQ(tspi_resets, 1);
  EXPECT_EQ(tspi_gaps, 0);

  // And the 20 m jump went through gnss_link (below its gate) and fusion's gate rejected it
  int jump_innovations = 0, jump_accepted = 0;
  for (const auto& i : w.innovations)
    if (i.sensor == 1 && std::abs(std::fmod(i.gps_sow_s, 86400.0) - jump_gps_tod_s) < 1e-3) {
      ++jump_innovations;
      jump_accepted += i.accepted;
      std::printf("[ GNSS jump ] %.0f m north at GPS time of day %.1f s: innovation N %.2f m, NIS %.0f, accepted %d\n", kJump_m,
                  jump_gps_tod_s, i.innovation[0], i.nis, static_cast<int>(i.accepted));
    }
  EXPECT_EQ(jump_innovations, 1);
  EXPECT_EQ(jump_accepted, 0);
  double max_err_near_jump = 0;
  for (const auto& t : w.tspi)
    if (std::abs(std::fmod(t.m.gps_sow_s, 86400.0) - jump_gps_tod_s) < 2.0)
      if (const double e = horizontal_error_m(truth, t.m); std::isfinite(e)) max_err_near_jump = std::max(max_err_near_jump, e);
  std::printf("[ GNSS jump ] TSPI horizontal error within 2 s of the jump: max %.3f m\n", max_err_near_jump);
  EXPECT_LT(max_err_near_jump, 0.3);

  // And the wrong fingerprints were counted by every service, which kept running
  ASSERT_TRUE(fingerprints_sent);
  const std::map<std::string, int> expected_malformed{{"STATUS_IMU_ACQ", 5}, {"STATUS_FUSION", 10}, {"STATUS_TSPI_PUB", 5}};
  for (const auto& [ch, expect] : expected_malformed) {
    const auto after = w.latest(ch);
    ASSERT_TRUE(after && before_fingerprints.count(ch)) << ch;
    const int64_t d = after->malformed - before_fingerprints[ch].malformed;
    std::printf("[ fingerprints ] %s: malformed %lld -> %lld (+%lld), state %d, fault bits 0x%x\n", ch.c_str(),
                static_cast<long long>(before_fingerprints[ch].malformed), static_cast<long long>(after->malformed),
                static_cast<long long>(d), after->state, after->fault_bits);
    EXPECT_GE(d, expect) << ch;
    EXPECT_LE(d, expect + (ch == "STATUS_FUSION" ? 3 : 0)) << ch << " (fusion also counts innovation-gate rejections)";
  }
  // The jump's rejection was counted by the first fusion process (killed later, its counters with it).
  const double fusion_kill_s =
      std::find_if(outcomes.begin(), outcomes.end(), [](const Outcome& o) { return o.name == "fusion"; })->kill_s;
  int64_t fusion_rejections_before_kill = 0;
  for (const auto& st : w.status["STATUS_FUSION"])
    if (st.rx_s < fusion_kill_s)
      fusion_rejections_before_kill = std::max(fusion_rejections_before_kill, st.m.malformed);
  std::printf("[ GNSS jump ] fusion heartbeat before its kill: malformed %lld (innovation-gate rejections)\n",
              static_cast<long long>(fusion_rejections_before_kill));
  EXPECT_GE(fusion_rejections_before_kill, 1) << "the GNSS jump is counted";

  // And the logger's file has no gap on any channel; only the killed services' channels restarted
  const auto seqs = test::log_sequences(log);
  ASSERT_FALSE(seqs.empty());
  std::map<std::string, int> killed_count;
  for (const Kill& k : kKills) ++killed_count[k.service];
  for (const auto& [ch, c] : seqs) {
    const std::string owner = channel_owner(ch);
    std::printf("[ log ] %-16s %7lld messages, %lld gaps (%lld missing), %lld resets, %lld undecodable\n", ch.c_str(),
                static_cast<long long>(c.messages), static_cast<long long>(c.gaps), static_cast<long long>(c.missing),
                static_cast<long long>(c.resets), static_cast<long long>(c.undecodable));
    EXPECT_EQ(c.gaps, 0) << ch;
    if (owner.empty()) continue;
    if (ch == "IMU_TIMING" || ch == "IMU_PPS" || ch == "GNSS_PPS") EXPECT_LE(c.resets, killed_count[owner]) << ch;
    else EXPECT_EQ(c.resets, killed_count[owner]) << ch;
  }
  for (const char* ch : {"IMU", "GNSS_SOLUTION", "NAV", "GNSS_PPS"}) EXPECT_EQ(seqs.at(ch).undecodable, 5) << ch;
  if (!HasFailure()) fs::remove_all(dir);
}
