// Scenarios: the built-ins cover the manoeuvres they promise, YAML files are read strictly, and
// every bad input names the file, the line, the field and what was expected.
#include <gtest/gtest.h>

#include "sim/scenario.hpp"
#include "sim_test_helpers.hpp"

using namespace ldv;
using namespace ldv::sim;
using namespace ldv::sim::test;

TEST(SimScenarios, EveryBuiltInCompilesAndRuns) {
  for (const std::string& name : builtin_scenario_names()) {
    const SimResult r = simulate(perfect_request(name, 120.0, 50.0));
    EXPECT_EQ(r.imu.size(), 6000u) << name;
    for (const auto& t : r.truth) ASSERT_TRUE(t.f_b_mps2.allFinite() && t.omega_ib_b_rad_s.allFinite()) << name;
  }
}

TEST(SimScenarios, TheDefaultDriveUsesEveryManoeuvre) {
  // Given one loop of the drive
  const SimResult r = simulate(perfect_request("drive", 900.0, 20.0));
  double min_speed = 1e9, max_speed = -1e9, min_yaw_rate = 0, max_yaw_rate = 0, min_pitch = 0, max_pitch = 0;
  double max_roll = 0, static_s = 0;
  for (const TruthSample& t : r.truth) {
    const Mat3 C = C_b_n_from_euler(t.rpy_rad);
    const double forward = (C.transpose() * t.vel_n_mps).x();
    min_speed = std::min(min_speed, forward);
    max_speed = std::max(max_speed, forward);
    const double yaw_rate = t.omega_ib_b_rad_s.z();
    min_yaw_rate = std::min(min_yaw_rate, yaw_rate);
    max_yaw_rate = std::max(max_yaw_rate, yaw_rate);
    min_pitch = std::min(min_pitch, t.rpy_rad.y());
    max_pitch = std::max(max_pitch, t.rpy_rad.y());
    max_roll = std::max(max_roll, std::abs(t.rpy_rad.x()));
    if (t.vel_n_mps.norm() < 1e-12) static_s += 0.05;
  }
  // Then it stands, reverses, drives up to 25 m/s, turns both ways, climbs and descends, and banks.
  EXPECT_GT(static_s, 60.0);
  EXPECT_LT(min_speed, -2.0);
  EXPECT_GT(max_speed, 24.9);
  EXPECT_LT(min_yaw_rate, -0.2);
  EXPECT_GT(max_yaw_rate, 0.2);
  EXPECT_LT(min_pitch, -3.9 * kDegToRad);
  EXPECT_GT(max_pitch, 4.9 * kDegToRad);
  EXPECT_GT(max_roll, 2.4 * kDegToRad);
}

TEST(SimScenarios, AirborneProfileBanksIntoItsTurns) {
  const SimResult r = simulate(perfect_request("airborne", 300.0, 50.0));
  // A coordinated turn banks by atan(v * yaw_rate / g0) at every instant: no side force, up to the
  // difference between normal gravity and g0 and the Coriolis terms (< 0.05 m/s^2 at 60 m/s).
  double max_side = 0, max_centripetal = 0, max_bank = 0;
  for (const TruthSample& t : r.truth) {
    max_side = std::max(max_side, std::abs(t.f_b_mps2.y()));
    max_centripetal = std::max(max_centripetal, t.vel_n_mps.norm() * std::abs(t.omega_ib_b_rad_s.z()));
    max_bank = std::max(max_bank, std::abs(t.rpy_rad.x()));
  }
  EXPECT_GT(max_centripetal, 5.0);
  EXPECT_LT(max_side, 0.05);
  EXPECT_GT(max_bank, 30 * kDegToRad);
  EXPECT_GT(r.truth.front().pos.h_m, 999.0);
}

TEST(SimScenarios, UserFileIsReadAndItsSegmentsFlown) {
  const std::string file = write_text("user.yaml", R"(name: user
start: {lat_deg: 10, lon_deg: 20, h_m: 5, yaw_deg: 90}
segments:
  - {type: static, duration_s: 2}
  - {type: accelerate, to_speed_mps: 10, duration_s: 4}
  - {type: straight, duration_s: 10}
)");
  const SimResult r = simulate(perfect_request(file, 16.0, 100.0));
  // Heading east at 10 m/s: 2 s static, 20 m while accelerating (mean 5 m/s over 4 s), 100 m straight.
  const Vec3 d = exact_ned(r.truth.front().pos, r.truth.back().pos);
  EXPECT_NEAR(d.y(), 120.0, 1e-3);
  EXPECT_NEAR(d.x(), 0.0, 2e-3);
  EXPECT_NEAR(r.truth.back().vel_n_mps.y(), 10.0, 1e-12);
}

namespace {
std::string scenario_error(const std::string& name, const std::string& text, double duration = 60.0) {
  const std::string file = write_text(name, text);
  return input_error_of([&] { simulate(perfect_request(file, duration)); });
}
}  // namespace

TEST(SimScenarios, BadFilesNameFileLineFieldAndExpectation) {
  const std::string header = "start: {yaw_deg: 0}\nsegments:\n";
  std::string e = scenario_error("bad1.yaml", header + "  - {type: turn, angle_deg: ninety, duration_s: 5}\n");
  EXPECT_NE(e.find("bad1.yaml:3"), std::string::npos) << e;
  EXPECT_NE(e.find("field 'angle_deg': expected a heading change [deg]"), std::string::npos) << e;
  EXPECT_NE(e.find("found 'ninety'"), std::string::npos) << e;

  e = scenario_error("bad2.yaml", header + "  - {type: straight}\n");
  EXPECT_NE(e.find("bad2.yaml:3"), std::string::npos) << e;
  EXPECT_NE(e.find("segments segment 1 (straight): field 'duration_s': expected a positive number [s] (the field is missing)"),
            std::string::npos)
      << e;

  e = scenario_error("bad3.yaml", header + "  - {type: static, duration_s: 5}\n  - {type: trun, duration_s: 5}\n");
  EXPECT_NE(e.find("bad3.yaml:4"), std::string::npos) << e;
  EXPECT_NE(e.find("found 'trun'"), std::string::npos) << e;

  e = scenario_error("bad4.yaml", header + "  - {type: turn, angle_deg: 90, duration_s: 5, bank: 3}\n");
  EXPECT_NE(e.find("unknown field 'bank' (allowed: angle_deg, bank_deg, coordinated, duration_s, type)"), std::string::npos) << e;

  e = scenario_error("bad5.yaml", "start: {lat_deg: 95}\nsegments:\n  - {type: static, duration_s: 5}\n");
  EXPECT_NE(e.find("bad5.yaml:1"), std::string::npos) << e;
  EXPECT_NE(e.find("start: field 'lat_deg': expected a number [deg] in [-89, 89], found 95"), std::string::npos) << e;

  e = scenario_error("bad6.yaml", "segments: [ {type: static, duration_s: 5 }\n");
  EXPECT_NE(e.find("YAML syntax error"), std::string::npos) << e;

  e = scenario_error("bad7.yaml", header + "  - {type: accelerate, to_speed_mps: 5, duration_s: 5}\n  - {type: static, duration_s: 5}\n");
  EXPECT_NE(e.find("bad7.yaml:4: segment 'static': the vehicle moves at 5"), std::string::npos) << e;

  e = scenario_error("bad8.yaml", header + "  - {type: circle, radius_m: 20}\n");
  EXPECT_NE(e.find("radius_m needs a moving vehicle"), std::string::npos) << e;

  e = input_error_of([] { simulate(perfect_request("/nonexistent/scenario.yaml", 10)); });
  EXPECT_NE(e.find("/nonexistent/scenario.yaml: scenario: expected a built-in name (accelerate"), std::string::npos) << e;
}

TEST(SimScenarios, BadRequestOptionsNameTheOption) {
  auto err = [](const std::function<void(SimRequest&)>& change) {
    SimRequest q = perfect_request("static", 10.0);
    change(q);
    return input_error_of([&] { simulate(q); });
  };
  EXPECT_NE(err([](auto& q) { q.grade = "hg1800"; }).find("--grade: unknown IMU grade 'hg1800'"), std::string::npos);
  EXPECT_NE(err([](auto& q) { q.duration_s = -1; }).find("--duration: expected a positive number of seconds"), std::string::npos);
  EXPECT_NE(err([](auto& q) { q.imu_rate_hz = 0; }).find("--imu-rate"), std::string::npos);
  EXPECT_NE(err([](auto& q) { q.gnss_rate_hz = 100; }).find("--gnss-rate"), std::string::npos);
  EXPECT_NE(err([](auto& q) { q.outages = {{5, -1}}; }).find("--outages: expected START:LENGTH"), std::string::npos);
  EXPECT_NE(err([](auto& q) { q.gnss_mode = "rtk"; }).find("--gnss-mode: unknown GNSS solution type 'rtk'"), std::string::npos);
  EXPECT_NE(err([](auto& q) { q.start_sow_s = 604790; }).find("--start-sow"), std::string::npos);
}

TEST(SimScenarios, SameSeedSameDataOtherSeedOtherData) {
  auto run = [](uint64_t seed) {
    SimRequest q;
    q.grade = "hg1900-typical";
    q.scenario = "figure8";
    q.duration_s = 60;
    q.seed = seed;
    q.effects = {"gravity_anomaly", "moving_bias"};
    return simulate(q);
  };
  const SimResult a = run(7), b = run(7), c = run(8);
  ASSERT_EQ(a.imu.size(), b.imu.size());
  for (size_t k = 0; k < a.imu.size(); ++k) {
    ASSERT_EQ(a.imu[k].dtheta_b_rad, b.imu[k].dtheta_b_rad);
    ASSERT_EQ(a.imu[k].dvel_b_mps, b.imu[k].dvel_b_mps);
  }
  for (size_t k = 0; k < a.gnss.size(); ++k) ASSERT_EQ(a.gnss[k].pos.lat_rad, b.gnss[k].pos.lat_rad);
  EXPECT_NE(a.imu[100].dtheta_b_rad, c.imu[100].dtheta_b_rad);
  EXPECT_NE(a.injected_effects.at("gyro_bias"), c.injected_effects.at("gyro_bias"));
}

TEST(SimScenarios, OutagesRemoveTheScheduledFixes) {
  SimRequest q = perfect_request("drive", 300.0);
  q.outages = {{100.0, 30.0}, {200.0, 10.0}};
  const SimResult r = simulate(q);
  EXPECT_EQ(r.gnss.size(), 301u - 40u);
  for (const GnssFix& g : r.gnss) {
    const double t = g.t_s - q.start_sow_s;
    EXPECT_FALSE(t >= 100 && t < 130) << t;
    EXPECT_FALSE(t >= 200 && t < 210) << t;
  }
}
