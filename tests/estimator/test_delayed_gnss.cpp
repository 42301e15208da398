// Given the same drive, when every GNSS fix reaches the filter 0.3 s after its epoch (as live RTK
// solutions do) instead of before, then the filter re-processes its IMU history and ends in the same
// state as with on-time fixes.
#include <gtest/gtest.h>

#include "common/geo/earth_model.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"
#include "sim/simulator.hpp"

namespace ldv::est {
namespace {

TEST(DelayedGnss, LateFixesGiveTheOnTimeAnswer) {
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.duration_s = 120.0;
  req.gnss_rate_hz = 5.0;
  req.scenario = "drive";
  const sim::SimResult sim = sim::simulate(req);
  FilterOptions o = options_from_kfgins(sim.kfgins);
  o.history_s = 2.0;

  NavState s0;
  s0.t_s = sim.truth.front().t_s;
  s0.pos = sim.truth.front().pos;
  s0.v_n_mps = sim.truth.front().vel_n_mps;
  s0.q_b_n = quat_from_euler(sim.truth.front().rpy_rad);
  NavStd sd;
  const double latency_s = 0.3;
  size_t g_on = 0, g_late = 0;
  // a: each fix handed over before the IMU reaches it; b: each fix 0.3 s after its epoch.
  NavFilter a(o), b(o);
  a.initialize(s0, sd);
  b.initialize(s0, sd);
  const double t_stop = sim.imu.back().t_s - 1.0;  // fixes after this are not given to either
  g_on = g_late = 0;
  for (const ImuIncrement& inc : sim.imu) {
    for (; g_on < sim.gnss.size() && sim.gnss[g_on].t_s <= inc.t_s && sim.gnss[g_on].t_s < t_stop; ++g_on)
      a.add_gnss(sim.gnss[g_on]);
    a.add_imu(inc);
    b.add_imu(inc);
    for (; g_late < sim.gnss.size() && sim.gnss[g_late].t_s + latency_s <= inc.t_s && sim.gnss[g_late].t_s < t_stop;
         ++g_late)
      b.add_gnss(sim.gnss[g_late]);
  }
  ASSERT_EQ(g_on, g_late);
  const Vec3 dr = earth::ned_between(a.state().pos, b.state().pos);
  const Vec3 dv = a.state().v_n_mps - b.state().v_n_mps;
  const double dphi = rotvec_from_quat(a.state().q_b_n.inverse() * b.state().q_b_n).norm();
  std::printf("late vs on-time after %zu fixes: |dr| %.2e m, |dv| %.2e m/s, |dphi| %.2e rad\n", g_on, dr.norm(), dv.norm(), dphi);
  EXPECT_LT(dr.norm(), 1e-6);
  EXPECT_LT(dv.norm(), 1e-8);
  EXPECT_LT(dphi, 1e-10);
  EXPECT_LT((a.covariance() - b.covariance()).norm(), 1e-9 * a.covariance().norm());
  EXPECT_EQ(b.faults().late_dropped, 0);
  // And fixes older than the history are dropped, flagged, never crash.
  GnssFix old = sim.gnss.front();
  b.add_gnss(old);
  EXPECT_TRUE(b.status() & kStatusLateDropped);
  EXPECT_EQ(b.faults().late_dropped, 1);
}

}  // namespace
}  // namespace ldv::est
