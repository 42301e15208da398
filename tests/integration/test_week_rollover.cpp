// The live chain across a GPS week rollover, through hostile messages and a bad warm-state file (issue 35): the
// real fusion and tspi_pub in a private network namespace, a simulated tactical drive published as imu_acq and
// gnss_link would (`ldv play`) from 45 s before the end of week 2300 into week 2301, fusion given a warm-state
// file whose roll is NaN, and the test itself publishing absurd but well-formed IMU and GNSS messages on the bus
// meanwhile. TSPI must keep coming into the new week, its times only going forward, close to the simulator's truth.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <ldv_lcm/service_status_t.hpp>
#include <ldv_lcm/tspi_v1_t.hpp>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "common/bus/bus.hpp"
#include "common/bus/message_conversions.hpp"
#include "common/formats/kfgins_config.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/geo/earth_model.hpp"
#include "common/time/gps_time.hpp"
#include "sim/simulator.hpp"
#include "tests/integration/bus_spin.hpp"
#include "tests/integration/child_process.hpp"

using namespace ldv;
namespace fs = std::filesystem;

namespace {
const std::string kBin = LDV_BIN_DIR;
const std::string kVehicleUrl = "udpm://239.255.76.67:7667?ttl=0";
constexpr int kWeek = 2300;

double continuous_s(const ldv_lcm::tspi_v1_t& t) { return (t.gps_week - kWeek) * kSecondsPerWeek + t.gps_sow_s; }
}  // namespace

TEST(WeekRollover, GivenHostileMessagesAndABadWarmState_ThenTspiKeepsComingIntoTheNewWeekOnTruth) {
  // Given: 90 s of a tactical drive with 5 Hz RTK, its files moved so the week ends 45 s in (KF-GINS files count
  // seconds of week on past 604800; `ldv play` publishes week 2301 from there), the start given from truth.
  const fs::path dir = fs::temp_directory_path() / ("ldv_week_rollover_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.seed = 11;
  req.duration_s = 90.0;
  req.scenario = "drive";
  req.gnss_rate_hz = 5.0;
  sim::SimResult sim = sim::simulate(req);
  sim::write_outputs(sim, dir.string());
  const double shift_s = (kSecondsPerWeek - 45.0) - sim.imu.front().t_s;
  std::vector<ImuIncrement> imu = sim.imu;
  for (ImuIncrement& s : imu) s.t_s += shift_s;
  std::vector<GnssFix> gnss = sim.gnss;
  for (GnssFix& g : gnss) g.t_s += shift_s;
  write_kfgins_imu((dir / "imu.txt").string(), imu);
  write_kfgins_gnss((dir / "gnss.txt").string(), gnss, false);
  KfGinsConfig kcfg = load_kfgins_config((dir / "kfgins.yaml").string());
  kcfg.start_time_s += shift_s;
  kcfg.end_time_s = -1.0;
  save_kfgins_config(kcfg, (dir / "kfgins.yaml").string());
  std::map<long, sim::TruthSample> truth;
  for (const auto& t : sim.truth) truth[std::lround((t.t_s + shift_s) * 1000)] = t;

  // A warm-state file saved a second ago whose roll is NaN: fusion must refuse it and start from the given state.
  const fs::path state = dir / "fusion_state.yaml";
  {
    std::ofstream s(state);
    s.precision(15);
    timespec now{};
    clock_gettime(CLOCK_REALTIME, &now);
    s << "saved_host_time_s: " << now.tv_sec - 1 << "\nt_s: 604750\nlat_rad: 0.5\nlon_rad: 2.0\nh_m: 20\n"
      << "v_n_mps: [0, 0, 0]\nrpy_rad: [.nan, 0, 1]\natt_std_rad: [0.01, 0.01, 0.1]\n";
  }
  const fs::path fusion_cfg = dir / "fusion.yaml";
  std::ofstream(fusion_cfg) << "bus_url: \"" << kVehicleUrl << "\"\nkfgins_config: " << (dir / "kfgins.yaml").string()
                            << "\nstate_file: " << state.string() << "\nwarm_start_max_age_s: 30\n";
  const fs::path tspi_cfg = dir / "tspi_pub.yaml";
  std::ofstream(tspi_cfg) << "bus_url: \"" << kVehicleUrl << "\"\ntspi:\n  rate_hz: 20\n  group: 239.255.77.1\n"
                          << "  port: 7668\n  ttl: 1\n";

  Bus vehicle(kVehicleUrl);
  std::set<std::string> up;
  std::optional<ldv_lcm::service_status_t> fusion_status;
  vehicle.subscribe<ldv_lcm::service_status_t>("STATUS_.*",
                                               [&](const ldv_lcm::service_status_t& m, const std::string& ch) {
                                                 up.insert(ch);
                                                 if (ch == "STATUS_FUSION") fusion_status = m;
                                               });
  const std::string fusion_log = (dir / "fusion.log").string();
  test::ChildProcess fusion(kBin + "/fusion", {"--config", fusion_cfg.string()}, "", fusion_log);
  test::ChildProcess tspi(kBin + "/tspi_pub", {"--config", tspi_cfg.string()});
  Bus remote("udpm://239.255.77.1:7668?ttl=1");
  std::vector<ldv_lcm::tspi_v1_t> got;
  remote.subscribe<ldv_lcm::tspi_v1_t>("TSPI",
                                       [&](const ldv_lcm::tspi_v1_t& t, const std::string&) { got.push_back(t); });
  ASSERT_TRUE(test::spin_until(
      vehicle, [&] { return up.size() >= 2; }, 30.0))
      << "no heartbeats from fusion and tspi_pub";

  // When the drive plays at 3x real time while the test publishes a hostile message every 0.5 s of data time,
  // stamped just ahead of the newest TSPI: absurd IMU increments, a GNSS velocity of 1e6 m/s at the right place,
  // a fix 1e300 m high, a time of week past the week's end, a fix a kilometre away.
  long hostile = 0;
  double next_hostile_s = 0.0;
  {
    test::ChildProcess play(kBin + "/ldv", {"play", dir.string(), "--url", kVehicleUrl, "--speed", "3",
                                            "--gnss-latency", "0.12", "--week", std::to_string(kWeek)});
    while (play.wait_exit(0.01) == 1000) {
      while (remote.handle(0) > 0) {
      }
      vehicle.handle(0);
      if (got.empty() || continuous_s(got.back()) < next_hostile_s) continue;
      const double t = continuous_s(got.back()) + 0.013;
      next_hostile_s = t + 0.5;
      const GpsTime at{kWeek + static_cast<int>(t / kSecondsPerWeek), std::fmod(t, kSecondsPerWeek)};
      const auto near = truth.lower_bound(std::lround(t * 1000));
      if (near == truth.end()) continue;
      ImuIncrement bad_imu;
      bad_imu.t_s = at.sow_s;
      bad_imu.dt_s = 0.005;
      GnssFix bad_fix;
      bad_fix.t_s = at.sow_s;
      bad_fix.pos = near->second.pos;
      bad_fix.pos_std_ned_m = Vec3(0.01, 0.01, 0.02);
      switch (hostile++ % 5) {
        case 0:
          bad_imu.dvel_b_mps = Vec3(1e30, 0, 0);
          vehicle.publish("IMU", message_from_imu(bad_imu, at.week, 900000 + hostile));
          break;
        case 1:
          bad_imu.dtheta_b_rad = Vec3(1000.0, 0, 0);
          vehicle.publish("IMU", message_from_imu(bad_imu, at.week, 900000 + hostile));
          break;
        case 2:
          bad_fix.has_velocity = true;
          bad_fix.vel_n_mps = Vec3(1e6, 0, 0);
          bad_fix.vel_std_n_mps = Vec3::Constant(0.01);
          vehicle.publish("GNSS_SOLUTION", message_from_gnss(bad_fix, at.week, 900000 + hostile));
          break;
        case 3:
          bad_fix.pos.h_m = 1e300;
          vehicle.publish("GNSS_SOLUTION", message_from_gnss(bad_fix, at.week, 900000 + hostile));
          break;
        case 4: {
          bad_imu.t_s = at.sow_s + 1e6;  // not a seconds of week
          vehicle.publish("IMU", message_from_imu(bad_imu, at.week, 900000 + hostile));
          bad_fix.pos = earth::offset_ned(bad_fix.pos, Vec3(1000.0, 0, 0));
          vehicle.publish("GNSS_SOLUTION", message_from_gnss(bad_fix, at.week, 900000 + hostile));
          break;
        }
      }
    }
  }
  const double last_epoch_s = imu.back().t_s - 0.06;
  test::spin_until(
      remote, [&] { return !got.empty() && continuous_s(got.back()) >= last_epoch_s; }, 60.0);
  test::spin_until(
      vehicle, [&] { return fusion_status && fusion_status->malformed > 0; }, 5.0);
  for (auto* p : {&tspi, &fusion}) p->signal(SIGTERM);
  EXPECT_EQ(fusion.wait_exit(5), 0);
  EXPECT_EQ(tspi.wait_exit(5), 0);

  // Then: the bad warm state was refused by name and the given start used
  std::ifstream log_in(fusion_log);
  const std::string log_text{std::istreambuf_iterator<char>(log_in), std::istreambuf_iterator<char>()};
  EXPECT_NE(log_text.find("not used (rpy_rad"), std::string::npos) << log_text;
  // TSPI ran into week 2301 to the end of the drive, forward only, without a gap, on the truth
  ASSERT_GT(got.size(), 20u * 80u);
  EXPECT_GT(hostile, 50) << "hostile messages published";
  ASSERT_TRUE(fusion_status.has_value());
  EXPECT_GE(fusion_status->malformed, hostile / 2) << "the hostile messages are counted as refused";
  long in_new_week = 0;
  double sum_h2 = 0.0, max_speed = 0.0;
  int compared = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    const double t = continuous_s(got[i]);
    in_new_week += got[i].gps_week == kWeek + 1;
    ASSERT_GE(got[i].gps_sow_s, 0.0);
    ASSERT_LT(got[i].gps_sow_s, kSecondsPerWeek);
    if (i > 0) {
      ASSERT_GT(t, continuous_s(got[i - 1])) << "TSPI went back at " << i;
      ASSERT_LT(t - continuous_s(got[i - 1]), 0.06) << std::fixed << "a TSPI gap after " << continuous_s(got[i - 1]);
    }
    max_speed = std::max(max_speed, std::sqrt(got[i].vel_ned_mps[0] * got[i].vel_ned_mps[0] +
                                              got[i].vel_ned_mps[1] * got[i].vel_ned_mps[1]));
    const auto it = truth.find(std::lround(t * 1000));
    if (it == truth.end() || t < continuous_s(got.front()) + 10.0) continue;
    const Vec3 d =
        earth::ned_between(it->second.pos, {got[i].lat_deg * kDegToRad, got[i].lon_deg * kDegToRad, got[i].height_m});
    sum_h2 += d.head<2>().squaredNorm();
    ++compared;
  }
  ASSERT_GT(compared, 1000);
  const double rms_m = std::sqrt(sum_h2 / compared);
  std::printf(
      "TSPI across the rollover: %zu messages, %ld in week %d, %ld hostile messages published (fusion "
      "refused %lld), max speed %.1f m/s, horizontal RMS vs truth %.3f m\n",
      got.size(), in_new_week, kWeek + 1, hostile, static_cast<long long>(fusion_status->malformed), max_speed, rms_m);
  EXPECT_GT(in_new_week, 20 * 40);
  EXPECT_LT(max_speed, 60.0);
  EXPECT_LT(rms_m, 0.10);
  fs::remove_all(dir);
}
