// Given perfect IMU increments from the simulator's exact truth integrator on a manoeuvring drive,
// when the strapdown mechanisation runs free-inertial for 10 minutes from the true initial state,
// then horizontal drift < 0.5 m and heading drift < 0.002 deg.
#include <gtest/gtest.h>

#include "common/geo/earth_model.hpp"
#include "estimator/ins/mechanization.hpp"
#include "sim/scenario.hpp"
#include "sim/truth_integrator.hpp"

namespace ldv::est {
namespace {

NavState from_truth(const sim::TruthSample& t) {
  NavState s;
  s.t_s = t.t_s;
  s.pos = t.pos;
  s.v_n_mps = t.vel_n_mps;
  s.q_b_n = quat_from_euler(t.rpy_rad);
  return s;
}

struct Drift {
  double horizontal_m, vertical_m, heading_deg, level_deg;
};

Drift free_inertial(const std::string& scenario, double duration_s, double rate_hz) {
  const auto motion = sim::compile_scenario(sim::load_scenario(scenario), duration_s);
  sim::TruthOptions o;
  o.t0_sow_s = 100000.0;
  o.dt_s = 1.0 / rate_hz;
  o.intervals = static_cast<size_t>(duration_s * rate_hz);
  const sim::TruthRun run = sim::integrate_truth(motion, o);
  NavState s = from_truth(run.truth.front());
  Mechanization mech;
  mech.reset(s);
  for (const auto& inc : run.increments) mech.step(s, inc);
  const sim::TruthSample& end = run.truth.back();
  const Vec3 dr = earth::ned_between(end.pos, s.pos);
  const Mat3 dC = s.C_b_n() * C_b_n_from_euler(end.rpy_rad).transpose();  // (I - [phi x])
  const Vec3 phi = -rotvec_from_quat(Quat(dC));
  EXPECT_NEAR(s.t_s, end.t_s, 1e-6);
  return {dr.head<2>().norm(), std::abs(dr.z()), std::abs(phi.z()) * kRadToDeg, phi.head<2>().norm() * kRadToDeg};
}

TEST(FreeInertial, TenMinutesPerfectSensorsOnFigureEights) {
  const Drift d = free_inertial("figure8", 600.0, 200.0);
  std::printf("free-inertial 600 s figure8 200 Hz: horizontal %.4f m, vertical %.4f m, heading %.6f deg, level %.6f deg\n",
              d.horizontal_m, d.vertical_m, d.heading_deg, d.level_deg);
  EXPECT_LT(d.horizontal_m, 0.5);
  EXPECT_LT(d.heading_deg, 0.002);
}

TEST(FreeInertial, TenMinutesPerfectSensorsOnTurnsAndStops) {
  const Drift d = free_inertial("turns", 600.0, 200.0);
  std::printf("free-inertial 600 s turns 200 Hz: horizontal %.4f m, vertical %.4f m, heading %.6f deg, level %.6f deg\n",
              d.horizontal_m, d.vertical_m, d.heading_deg, d.level_deg);
  EXPECT_LT(d.horizontal_m, 0.5);
  EXPECT_LT(d.heading_deg, 0.002);
}

}  // namespace
}  // namespace ldv::est

namespace ldv::est {
// Issue 35, item 26: a drive across the antimeridian was written at longitude 180.003 deg. Longitude stays in
// (-180, 180] and the track stays continuous across it (200 m east in 10 s at 20 m/s).
TEST(FreeInertial, GivenADriveEastAcrossTheAntimeridian_ThenLongitudeWrapsAndTheTrackIsContinuous) {
  NavState s;
  s.t_s = 1000.0;
  s.pos = {0.0, 179.9995 * kDegToRad, 10.0};
  s.v_n_mps = Vec3(0.0, 20.0, 0.0);
  const Geodetic start = s.pos;
  Mechanization mech;
  mech.reset(s);
  const double g = earth::gravity_n(s.pos.lat_rad, s.pos.h_m).z();
  for (int k = 1; k <= 1000; ++k) {
    ImuIncrement inc;
    inc.t_s = 1000.0 + 0.01 * k;
    inc.dt_s = 0.01;
    inc.dvel_b_mps = Vec3(0.0, 0.0, -g * 0.01);
    mech.step(s, inc);
    ASSERT_GT(s.pos.lon_rad, -kPi);
    ASSERT_LE(s.pos.lon_rad, kPi);
  }
  EXPECT_LT(s.pos.lon_rad, 0.0) << "past 180 deg: on the western side";
  const Vec3 moved = earth::ned_between(start, s.pos);
  EXPECT_NEAR(moved.y(), 200.0, 5.0);
  EXPECT_NEAR(moved.x(), 0.0, 5.0);
}
}  // namespace ldv::est

namespace ldv::est {
// Issue 46, item 1: at 89.9995 deg (55 m from the North Pole) ldv nav wrote a file of one time (the gravity
// gradient was taken beyond 90 deg: NaN). Driving north over the pole, the track goes on down the far meridian:
// 200 m in 10 s at 20 m/s from 55.5 m short of the pole ends 144.5 m past it, at longitude + 180 deg, heading south.
TEST(FreeInertial, GivenADriveNorthOverThePole_ThenItContinuesDownTheFarMeridian) {
  const double lat0 = 89.9995 * kDegToRad, lon0 = 10.0 * kDegToRad, h = 10.0, speed = 20.0;
  NavState s;
  s.t_s = 1000.0;
  s.pos = {lat0, lon0, h};
  s.v_n_mps = Vec3(speed, 0.0, 0.0);  // level, heading north: body = n
  const earth::Radii r0 = earth::radii(lat0);
  const double to_pole_m = (kHalfPi - lat0) * (r0.meridian_m + h);
  Mechanization mech;
  mech.reset(s);
  int crossings = 0;
  for (int k = 1; k <= 1000; ++k) {
    ImuIncrement inc;
    inc.t_s = 1000.0 + 0.01 * k;
    inc.dt_s = 0.01;
    // what a level vehicle driving straight along its meridian senses: the n frame's rotation, gravity, Coriolis,
    // in body axes (body = n before the pole, n turned 180 deg about down after it)
    const Mat3 C_n_b = s.C_b_n().transpose();
    const Vec3 rate_n = earth::omega_ie_n(s.pos.lat_rad) + earth::omega_en_n(s.pos.lat_rad, h, s.v_n_mps);
    inc.dtheta_b_rad = C_n_b * rate_n * 0.01;
    const Vec3 coriolis_n =
        (2.0 * earth::omega_ie_n(s.pos.lat_rad) + earth::omega_en_n(s.pos.lat_rad, h, s.v_n_mps)).cross(s.v_n_mps);
    inc.dvel_b_mps = C_n_b * (coriolis_n - earth::gravity_n(s.pos.lat_rad, h)) * 0.01;
    crossings += mech.step(s, inc).crossed_pole;
    ASSERT_TRUE(std::isfinite(s.pos.lat_rad) && std::isfinite(s.pos.lon_rad) && s.v_n_mps.allFinite());
    ASSERT_LE(s.pos.lat_rad, kHalfPi);
  }
  EXPECT_EQ(crossings, 1);
  const double past_pole_m = (kHalfPi - s.pos.lat_rad) * (earth::radii(s.pos.lat_rad).meridian_m + h);
  EXPECT_NEAR(past_pole_m, 200.0 - to_pole_m, 0.5);
  EXPECT_NEAR(std::remainder(s.pos.lon_rad - (lon0 + kPi), 2 * kPi), 0.0, 1e-3);
  EXPECT_NEAR(s.v_n_mps.x(), -speed, 0.05) << "heading south on the far side";
  EXPECT_NEAR(s.v_n_mps.y(), 0.0, 0.05);
  EXPECT_NEAR(s.pos.h_m, h, 0.05);
}
}  // namespace ldv::est
