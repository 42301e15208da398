// Each injected effect changes the data exactly as its definition in docs/effects.md says:
// a run with the effect minus the same run without it, compared with the physics of the effect.
#include <gtest/gtest.h>

#include "sim/imu_error_model.hpp"
#include "sim_test_helpers.hpp"

using namespace ldv;
using namespace ldv::sim;
using namespace ldv::sim::test;

namespace {
constexpr double kDegPerH = kDegToRad / 3600.0;

SimResult run_with(const std::vector<std::string>& effects, const std::string& scenario = "drive",
                   double duration_s = 200.0) {
  SimRequest r = perfect_request(scenario, duration_s, 100.0);
  r.effects = effects;
  return simulate(r);
}
const SimResult& baseline() {
  static const SimResult b = run_with({});
  return b;
}
// Largest norm over all samples of (measured difference - expected difference).
template <class F>
double worst(const SimResult& with, F expected_minus_actual) {
  double w = 0;
  for (size_t k = 0; k < with.imu.size(); ++k) w = std::max(w, expected_minus_actual(k).norm());
  return w;
}
}  // namespace

TEST(SimEffects, GyroAndAccelBiasAddBiasTimesDt) {
  const SimResult r = run_with({"gyro_bias=5,-3,8", "accel_bias=2,-1.5,3"});
  const Vec3 bg = Vec3(5, -3, 8) * kDegPerH, ba = Vec3(2, -1.5, 3) * 9.80665e-3;
  const auto& b = baseline();
  EXPECT_LT(worst(r, [&](size_t k) { return Vec3(r.imu[k].dtheta_b_rad - b.imu[k].dtheta_b_rad - bg * 0.01); }), 1e-16);
  EXPECT_LT(worst(r, [&](size_t k) { return Vec3(r.imu[k].dvel_b_mps - b.imu[k].dvel_b_mps - ba * 0.01); }), 1e-15);
  EXPECT_LT((Vec3(r.injected_effects.at("gyro_bias").data()) - bg).norm(), 1e-18);
}

TEST(SimEffects, ScaleFactorMultipliesTheTrueIncrement) {
  const SimResult r = run_with({"gyro_scale=300,-200,500", "accel_scale=100,400,-250"});
  const Vec3 sg = Vec3(300, -200, 500) * 1e-6, sa = Vec3(100, 400, -250) * 1e-6;
  const auto& b = baseline();
  EXPECT_LT(worst(r, [&](size_t k) {
              return Vec3(r.imu[k].dtheta_b_rad - b.imu[k].dtheta_b_rad - sg.cwiseProduct(b.imu[k].dtheta_b_rad));
            }),
            1e-17);
  EXPECT_LT(worst(r, [&](size_t k) {
              return Vec3(r.imu[k].dvel_b_mps - b.imu[k].dvel_b_mps - sa.cwiseProduct(b.imu[k].dvel_b_mps));
            }),
            1e-15);
}

TEST(SimEffects, MisalignmentCouplesAxesThroughTheSymmetricMatrix) {
  const SimResult r = run_with({"gyro_misalignment=100,-60,80", "accel_misalignment=-50,30,70"});
  const double as = kDegToRad / 3600;
  // docs/effects.md: N(m) = [[0, m_z, m_y], [m_z, 0, m_x], [m_y, m_x, 0]], written out here.
  auto N = [](const Vec3& m) {
    Mat3 n;
    n << 0, m.z(), m.y(), m.z(), 0, m.x(), m.y(), m.x(), 0;
    return n;
  };
  const Mat3 Ng = N(Vec3(100, -60, 80) * as), Na = N(Vec3(-50, 30, 70) * as);
  const auto& b = baseline();
  EXPECT_LT(worst(r, [&](size_t k) { return Vec3(r.imu[k].dtheta_b_rad - b.imu[k].dtheta_b_rad - Ng * b.imu[k].dtheta_b_rad); }),
            1e-17);
  EXPECT_LT(worst(r, [&](size_t k) { return Vec3(r.imu[k].dvel_b_mps - b.imu[k].dvel_b_mps - Na * b.imu[k].dvel_b_mps); }),
            1e-15);
  // A large specific force on z leaks into x and y as m_y f_z and m_x f_z.
  EXPECT_GT(std::abs(r.imu[0].dvel_b_mps.x() - b.imu[0].dvel_b_mps.x()), 1e-6);
}

TEST(SimEffects, GSensitivityAddsGyroBiasProportionalToSpecificForce) {
  const SimResult r = run_with({"g_sensitivity=2,-1,1.5"});
  const Vec3 G = Vec3(2, -1, 1.5) * kDegPerH / 9.80665;
  const auto& b = baseline();
  EXPECT_LT(worst(r, [&](size_t k) {
              return Vec3(r.imu[k].dtheta_b_rad - b.imu[k].dtheta_b_rad - G.cwiseProduct(b.imu[k].dvel_b_mps));
            }),
            1e-18);
  // Standing still the z gyro sees G_z * (-g) per second.
  EXPECT_NEAR((r.imu[10].dtheta_b_rad.z() - b.imu[10].dtheta_b_rad.z()) / 0.01, -1.5 * kDegPerH, 0.01 * kDegPerH);
}

TEST(SimEffects, NonlinearScaleAddsKTimesSquaredSpecificForce) {
  const SimResult r = run_with({"accel_nonlinear_scale=50,-30,40"});
  const Vec3 k2 = Vec3(50, -30, 40) * 1e-6 / 9.80665;
  const auto& b = baseline();
  // int f^2 dt = dv^2/dt + dt var(f) over the sample; with jerk j, var(f) = (j dt)^2 / 12 (< 3e-4 m^2/s^4
  // here), so the difference stays below k * 3e-6 = 2e-11.
  EXPECT_LT(worst(r, [&](size_t k) {
              return Vec3(r.imu[k].dvel_b_mps - b.imu[k].dvel_b_mps - k2.cwiseProduct(b.imu[k].dvel_b_mps.cwiseAbs2()) / 0.01);
            }),
            2e-11);
}

TEST(SimEffects, GravityAnomalyChangesOnlyTheAccelerometersByMinusCnbDeltaG) {
  const SimResult r = run_with({"gravity_anomaly=25,-15,40"});  // constant, mGal
  const Vec3 dg = Vec3(25, -15, 40) * 1e-5;
  const auto& b = baseline();
  EXPECT_LT(worst(r, [&](size_t k) { return Vec3(r.imu[k].dtheta_b_rad - b.imu[k].dtheta_b_rad); }), 0.0 + 1e-20);
  // True gravity is normal + anomaly, so the accelerometers sense -C_n_b dg more (attitude at mid-interval).
  EXPECT_LT(worst(r, [&](size_t k) {
              const Mat3 C0 = C_b_n_from_euler(b.truth[k].rpy_rad), C1 = C_b_n_from_euler(b.truth[k + 1].rpy_rad);
              const Mat3 C_n_b = (0.5 * (C0 + C1)).transpose();
              return Vec3(r.imu[k].dvel_b_mps - b.imu[k].dvel_b_mps + C_n_b * dg * 0.01);
            }),
            1e-10);
}

TEST(SimEffects, LeverArmPutsTheGnssAtTheAntenna) {
  // Given a 0.5, -0.3, -1.2 m lever arm and no noise
  const SimResult r = run_with({"lever_arm=0.5,-0.3,-1.2"});
  const Vec3 l(0.5, -0.3, -1.2);
  ASSERT_GT(r.gnss.size(), 100u);
  for (const GnssFix& g : r.gnss) {
    const size_t k = static_cast<size_t>(std::lround((g.t_s - r.truth.front().t_s) * 100.0));
    const TruthSample& t = r.truth[k];
    ASSERT_NEAR(t.t_s, g.t_s, 1e-9);
    // Then GNSS position - truth IMU position = C_b_n l (exact ECEF geometry, text-free).
    EXPECT_LT((exact_ned(t.pos, g.pos) - C_b_n_from_euler(t.rpy_rad) * l).norm(), 1e-5);
  }
  // Hidden: the KF-GINS config does not know it.
  EXPECT_EQ(r.kfgins.antenna_lever_b_m, Vec3::Zero());
}

TEST(SimEffects, DeclaredLeverArmIsWrittenIntoTheConfig) {
  SimRequest q = perfect_request("drive", 100.0);
  q.declared_effects = {"lever_arm=0.5,-0.3,-1.2"};
  const SimResult r = simulate(q);
  EXPECT_LT((r.kfgins.antenna_lever_b_m - Vec3(0.5, -0.3, -1.2)).norm(), 1e-12);
  EXPECT_EQ(r.injected_effects.at("lever_arm").size(), 3u);
}

TEST(SimEffects, TimeOffsetTagsTheImuEarlierAndKeepsTheFixesOnGpsTime) {
  // Given a 50 ms time offset (GNSS tag minus IMU tag): the fix labelled t was taken at IMU time t - 0.05 s.
  // The GNSS tags are GPS time, the truth's scale: each fix is the truth at its label ...
  const SimResult r = run_with({"time_offset=0.05"});
  const auto& b = baseline();
  for (const GnssFix& g : r.gnss) {
    const size_t k = static_cast<size_t>(std::lround((g.t_s - r.truth.front().t_s) * 100.0));
    EXPECT_LT(exact_ned(r.truth[k].pos, g.pos).norm(), 1e-6);
  }
  // ... and each IMU sample is the same increment, tagged 0.05 s before its true time.
  ASSERT_EQ(r.imu.size(), b.imu.size());
  for (size_t k = 0; k < r.imu.size(); ++k) {
    ASSERT_NEAR(r.imu[k].t_s, b.imu[k].t_s - 0.05, 1e-9);
    ASSERT_EQ(r.imu[k].dvel_b_mps, b.imu[k].dvel_b_mps);
  }
}

TEST(SimEffects, MovingBiasWithoutNoiseIsItsConstantPlusRamp) {
  // With noise off only the deterministic parts of the moving bias stay (constant + ramp R t).
  const SimResult r = run_with({"gyro_moving_bias=0.5,0.3,600,0.1,0.05"});
  const auto& b = baseline();
  for (size_t k : {0ul, 5000ul, 19999ul}) {
    const double t_mid = (k + 0.5) * 0.01;
    const double expected = (0.5 * kDegPerH + 0.05 * kDegPerH / 3600.0 * t_mid) * 0.01;
    EXPECT_NEAR(r.imu[k].dtheta_b_rad.x() - b.imu[k].dtheta_b_rad.x(), expected, 1e-18);
  }
}

TEST(SimEffects, BadEffectSpecificationsNameTheEffectAndTheExpectation) {
  auto err = [](const std::string& spec) {
    SimRequest q = perfect_request("static", 10.0);
    q.effects = {spec};
    return input_error_of([&] { simulate(q); });
  };
  EXPECT_NE(err("lever_arm=1,2").find("lever_arm': expected 3 comma-separated values [m,m,m], found 2"), std::string::npos)
      << err("lever_arm=1,2");
  EXPECT_NE(err("gyro_bias=1,x,3").find("value 2 'x' is not a number"), std::string::npos);
  EXPECT_NE(err("gyro_bais").find("unknown effect 'gyro_bais'"), std::string::npos);
  EXPECT_NE(err("time_offset=0.1,0.2").find("expected 1 comma-separated values [s]"), std::string::npos);
}

// Issue 46 (6): a 1e9 m lever arm simulated a drive with latitudes of 8742 deg; sizes no sensor or installation
// shows are refused, naming the effect, the value and the bound, while the largest real ones still simulate.
TEST(SimEffects, SizesNoPhysicalSensorShowsAreRefusedByEffectAndValue) {
  auto err = [](const std::string& spec) {
    SimRequest q = perfect_request("static", 10.0);
    q.effects = {spec};
    return input_error_of([&] { simulate(q); });
  };
  const std::string lever = err("lever_arm=1e9,0,0");
  EXPECT_NE(lever.find("effect 'lever_arm': value 1 ("), std::string::npos) << lever;
  EXPECT_NE(lever.find("expected |value| <= 100"), std::string::npos) << lever;
  EXPECT_NE(err("gyro_bias=0,0,-1e7").find("value 3"), std::string::npos);
  EXPECT_NE(err("time_offset=3600").find("effect 'time_offset'"), std::string::npos);
  EXPECT_NE(err("accel_moving_bias=0.2,0.05,1e12,0.02,0.02").find("value 3"), std::string::npos);
  EXPECT_EQ(err("lever_arm=40,-2,-15"), "");     // a ship's mast: a real size
  EXPECT_EQ(err("accel_bias=200,-100,50"), "");  // a poor consumer MEMS
}
