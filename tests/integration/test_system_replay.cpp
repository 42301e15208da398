// The vehicle pipeline on a real bus in a private network namespace: a simulated drive published
// as imu_acq/gnss_link would (`ldv play`, GNSS 120 ms late), the real fusion and tspi_pub binaries,
// ldv_logger recording (as deployed; lcm-logger's 30-message queue loses messages on a loaded host, and
// a log with a hole cannot replay to the live result). Then: TSPI rate and sequence, TSPI accuracy against the simulator's truth,
// and the recorded log replayed through the same estimator code gives the same TSPI.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>

#include <ldv_lcm/service_status_t.hpp>
#include <ldv_lcm/tspi_v1_t.hpp>

#include "common/bus/bus.hpp"
#include "common/formats/kfgins_config.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/geo/earth_model.hpp"
#include "estimator/run/alignment_options_from.hpp"
#include "estimator/run/run_navigation.hpp"
#include "services/fusion/log_replay.hpp"
#include "sim/simulator.hpp"
#include "tests/integration/bus_spin.hpp"
#include "tests/integration/child_process.hpp"

using namespace ldv;
namespace fs = std::filesystem;

namespace {
const std::string kBin = LDV_BIN_DIR;
const std::string kVehicleUrl = "udpm://239.255.76.67:7667?ttl=0";

std::map<long, NavRecord> by_millisecond(const std::vector<NavRecord>& recs) {
  std::map<long, NavRecord> m;
  for (const auto& r : recs) m[std::lround(r.sow_s * 1000)] = r;
  return m;
}
}  // namespace

TEST(SystemReplay, LiveTspiIsAccurateGapFreeAndEqualsTheLogReplay) {
  // Given a 130 s tactical-grade drive with 5 Hz RTK: 60 s static (a 1 deg/h gyro cannot gyrocompass to
  // better than ~4 deg, so the heading comes from the GNSS course once the vehicle moves), then driving
  const fs::path dir = fs::temp_directory_path() / "ldv_system_replay";
  fs::remove_all(dir);
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.seed = 7;
  req.duration_s = 130.0;
  req.scenario = "drive";
  req.gnss_rate_hz = 5.0;
  sim::SimResult sim = sim::simulate(req);
  sim::write_outputs(sim, dir.string());
  const auto truth = by_millisecond(read_nav((dir / "truth.nav").string()));

  // When the services run and the drive is played at 4x real time
  const std::string log = (dir / "run.lcmlog").string();
  const std::string tspi_cfg = (dir / "tspi_pub.yaml").string();
  std::ofstream(tspi_cfg) << "bus_url: \"" << kVehicleUrl << "\"\ntspi:\n  rate_hz: 20\n  group: 239.255.77.1\n"
                          << "  port: 7668\n  ttl: 1\n";
  auto vehicle = std::make_unique<Bus>(kVehicleUrl);  // only to see the processes come up
  std::set<std::string> up;
  vehicle->subscribe<ldv_lcm::service_status_t>("STATUS_.*", [&](const ldv_lcm::service_status_t&, const std::string& ch) { up.insert(ch); });
  test::ChildProcess logger(kBin + "/ldv_logger", {"--lcm-url", kVehicleUrl, log});
  test::ChildProcess fusion(kBin + "/fusion", {"--bus-url", kVehicleUrl, "--kfgins-config", (dir / "kfgins.yaml").string()});
  test::ChildProcess tspi(kBin + "/tspi_pub", {"--config", tspi_cfg});
  Bus remote("udpm://239.255.77.1:7668?ttl=1");
  std::vector<ldv_lcm::tspi_v1_t> got;
  remote.subscribe<ldv_lcm::tspi_v1_t>("TSPI", [&](const ldv_lcm::tspi_v1_t& t, const std::string&) { got.push_back(t); });
  // Play only once every process listens (its first heartbeat follows its subscriptions): a service
  // that misses the first samples the logger has would not match the log's replay.
  ASSERT_TRUE(test::spin_until(*vehicle, [&] { return up.size() >= 3; }, 30.0))
      << "heartbeats within 30 s: " << up.size() << " of STATUS_FUSION, STATUS_TSPI_PUB, STATUS_LOGGER";
  vehicle.reset();
  {
    test::ChildProcess play(kBin + "/ldv", {"play", dir.string(), "--url", kVehicleUrl, "--speed", "4", "--gnss-latency", "0.12"});
    while (play.wait_exit(0.02) == 1000)
      while (remote.handle(0) > 0) {
      }
  }
  // Until TSPI reaches the end of the drive (a loaded machine delays it; it does not end it early).
  const double last_epoch_s = sim.imu.back().t_s - 0.06;
  test::spin_until(remote, [&] { return !got.empty() && got.back().gps_sow_s >= last_epoch_s; }, 60.0);
  test::spin_until(remote, [] { return false; }, 0.2);  // nothing may follow; a straggler would show as a gap
  for (auto* p : {&tspi, &fusion, &logger}) p->signal(SIGTERM);
  EXPECT_EQ(fusion.wait_exit(5), 0);
  EXPECT_EQ(tspi.wait_exit(5), 0);
  logger.wait_exit(5);

  // Then TSPI flowed at 20 Hz from alignment (at the first motion, t = 62 s) to the end, without a gap
  ASSERT_GT(got.size(), 20u * 60u) << "expected TSPI for the 67 s of driving";
  for (size_t i = 1; i < got.size(); ++i) {
    ASSERT_EQ(got[i].seq, got[i - 1].seq + 1);
    if (i == 1) continue;  // the first TSPI is the first NAV after alignment, mid-slot
    ASSERT_NEAR(got[i].gps_sow_s - got[i - 1].gps_sow_s, 0.05, 0.0026) << std::fixed << got[i - 1].gps_sow_s << " -> " << got[i].gps_sow_s << " at " << i;
  }
  // And it is accurate against the truth once converged (10 s after the first TSPI)
  double sum_h2 = 0;
  int n = 0;
  for (const auto& t : got) {
    if (t.gps_sow_s < got.front().gps_sow_s + 10.0) continue;
    const auto it = truth.find(std::lround(t.gps_sow_s * 1000));
    ASSERT_NE(it, truth.end());
    const Vec3 d = earth::ned_between(it->second.pos, {t.lat_deg * kDegToRad, t.lon_deg * kDegToRad, t.height_m});
    sum_h2 += d.head<2>().squaredNorm();
    ++n;
  }
  const double horizontal_rms_m = std::sqrt(sum_h2 / n);
  std::printf("live TSPI: %zu messages, horizontal RMS vs truth %.3f m\n", got.size(), horizontal_rms_m);
  EXPECT_LT(horizontal_rms_m, 0.10);

  // And the recorded log, replayed through the same estimator code, gives the same TSPI
  const KfGinsConfig kcfg = load_kfgins_config((dir / "kfgins.yaml").string());
  est::FilterOptions fo = est::options_from_kfgins(kcfg);
  fo.history_s = 3.0;
  FusionEngine engine(live_session_options(kcfg, fo));  // as the service runs it
  std::map<long, FusionOutput> replay;
  replay_fusion_log(log, engine, [&](const FusionOutput& o) { replay[std::lround(o.state.t_s * 1000)] = o; });
  double max_diff_m = 0;
  int compared = 0;
  for (const auto& t : got) {
    const auto it = replay.find(std::lround(t.gps_sow_s * 1000));
    ASSERT_NE(it, replay.end()) << "TSPI epoch " << t.gps_sow_s << " missing from the replay";
    const Vec3 d = earth::ned_between(it->second.state.pos, {t.lat_deg * kDegToRad, t.lon_deg * kDegToRad, t.height_m});
    max_diff_m = std::max(max_diff_m, d.norm());
    ++compared;
  }
  std::printf("replay of the log vs live TSPI: %d epochs, max difference %.6f m\n", compared, max_diff_m);
  EXPECT_LT(max_diff_m, 1e-3);
}
