// The odometer over the bus (issue 16): a drive's IMU, GNSS and wheel speeds recorded as fusion receives them
// (wheel_speed_t on WHEEL_SPEED) and replayed through fusion's engine with `--aid odometer`
// gives the solution `ldv nav` computes from the files (the same navigation session), and wheel speeds flagged
// slipping or invalid are left out without counting as bad input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <map>

#include "common/bus/message_conversions.hpp"
#include "common/geo/earth_model.hpp"
#include "estimator/run/run_navigation.hpp"
#include "estimator/update/odometer.hpp"
#include "services/fusion/log_replay.hpp"
#include "sim/simulator.hpp"
#include "tests/services_boundary/hostile_log.hpp"

using namespace ldv;
namespace fs = std::filesystem;

using ldv::testing::write_log_event;

TEST(WheelSpeedReplay, GivenAnOdometerOnTheBus_WhenTheLogIsReplayedWithTheOdometerAid_ThenItEqualsTheFileRun) {
  sim::SimRequest req;
  req.grade = "3dm-gx2-typical";
  req.scenario = "drive";
  req.duration_s = 120.0;
  req.gnss_rate_hz = 5.0;
  req.seed = 7;
  req.vehicle.odometer = true;
  const sim::SimResult sim = sim::simulate(req);
  ASSERT_GT(sim.odometer.size(), 1000u);
  const int week = 2300;

  // The log in the order the file run hands the readings over (fixes and wheel speeds half a second ahead of
  // the IMU; late ones are the filter's rewind, tested in tests/estimator/test_nav_session.cpp), so every
  // epoch compares; every 50th wheel message flagged slipping (with a speed 5 m/s off: it must not be used).
  const fs::path log_path = fs::temp_directory_path() / ("ldv_wheel_replay_" + std::to_string(::getpid()) + ".lcmlog");
  long slipping = 0;
  {
    lcm::LogFile log(log_path.string(), "w");
    ASSERT_TRUE(log.good());
    size_t g = 0, o = 0;
    int64_t seq = 0;
    for (const ImuIncrement& inc : sim.imu) {
      for (; g < sim.gnss.size() && sim.gnss[g].t_s <= inc.t_s + 0.5; ++g)
        write_log_event(log, "GNSS_SOLUTION", message_from_gnss(sim.gnss[g], week, static_cast<int64_t>(g)), inc.t_s);
      for (; o < sim.odometer.size() && sim.odometer[o].t_s <= inc.t_s + 0.5; ++o) {
        ldv_lcm::wheel_speed_t m = message_from_odometer(sim.odometer[o].t_s, sim.odometer[o].speed_mps, week, seq);
        if (o % 50 == 49) {
          m.speed_mps[0] += 5.0;
          m.status |= kWheelStatusSlipping;
          ++slipping;
        }
        write_log_event(log, "WHEEL_SPEED", m, inc.t_s);
      }
      write_log_event(log, "IMU", message_from_imu(inc, week, seq++), inc.t_s);
    }
  }

  KfGinsConfig cfg = sim.kfgins;
  est::FilterOptions fo = est::options_from_kfgins(cfg);
  fo.aids.enabled = {"odometer"};
  fo.aids.odometer_std_mps = 0.05;

  // The file run: the odometer readings that were not flagged, as `ldv nav --aid odometer --odometer odo.txt`.
  std::vector<est::ObservationPtr> readings;
  for (size_t o = 0; o < sim.odometer.size(); ++o)
    if (o % 50 != 49)
      readings.push_back(std::make_shared<est::OdometerObservation>(sim.odometer[o].t_s, sim.odometer[o].speed_mps));
  est::NavFilter file_filter(fo);
  std::map<long, est::NavState> file_run;
  est::RunCallbacks cb;
  cb.on_epoch = [&](const est::NavFilter& f) { file_run[std::lround(f.state().t_s * 1e4)] = f.state(); };
  const est::RunSummary file_sum = est::run_navigation(sim.imu, sim.gnss, cfg, file_filter, cb, nullptr, &readings);
  EXPECT_GT(file_sum.other_observations, 1000);

  // The replay: fusion's engine (history_s as deployed) over the log.
  fo.history_s = 3.0;
  est::SessionOptions so = est::session_options_from(cfg, fo);
  so.imu_noise_floor = file_sum.imu_noise_floor;  // measured over the file offline (none live)
  FusionEngine engine(so);
  ASSERT_TRUE(engine.wants_odometer());
  std::map<long, est::NavState> replay;
  const LogReplaySummary sum = replay_fusion_log(log_path.string(), engine, [&](const FusionOutput& out) {
    replay[std::lround(out.state.t_s * 1e4)] = out.state;
  });
  fs::remove(log_path);
  EXPECT_EQ(sum.wheel_messages, static_cast<long>(sim.odometer.size()) - slipping);
  EXPECT_EQ(sum.malformed, 0) << "a slipping wheel is expected input, not bad input";

  ASSERT_EQ(replay.size(), file_run.size());
  double max_dr_m = 0.0;
  for (const auto& [key, a] : file_run) {
    const auto it = replay.find(key);
    ASSERT_NE(it, replay.end());
    max_dr_m = std::max(max_dr_m, earth::ned_between(a.pos, it->second.pos).norm());
  }
  std::printf("wheel speeds over the bus vs odo.txt: %zu epochs, max position difference %.3g m\n", replay.size(),
              max_dr_m);
  // Not to the bit: a fix's std goes through the message as a variance (sqrt of a square).
  EXPECT_LT(max_dr_m, 1e-6);
}

TEST(WheelSpeedMessage, GivenWheelsOfEachLayout_ThenTheOdometerSpeedIsTheRearAxleCentres) {
  ldv_lcm::wheel_speed_t m = message_from_odometer(100.0, 12.5, 2300, 0);
  EXPECT_DOUBLE_EQ(*odometer_speed_from_message(m), 12.5);
  m.num_wheels = 4;
  m.wheel_id = {1, 2, 3, 4};
  m.speed_mps = {13.0, 12.0, 10.0, 11.0};  // a left turn: the rear axle centre moves at the rear wheels' mean
  m.counts = {0, 0, 0, 0};
  EXPECT_DOUBLE_EQ(*odometer_speed_from_message(m), 10.5);
  m.status = 0;  // speeds not flagged valid
  EXPECT_FALSE(odometer_speed_from_message(m));
  m.status = kWheelStatusSpeedsValid;
  m.speed_mps[2] = std::nan("");
  EXPECT_FALSE(is_valid(m));
  m.speed_mps[2] = 10.0;
  m.num_wheels = 5;  // arrays of 4
  EXPECT_FALSE(is_valid(m));
}
