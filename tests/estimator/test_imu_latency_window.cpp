// The IMU latency found live (estimator/calibrate/imu_latency_window.hpp, SessionOptions::imu_latency_window):
// the fusion service has no file to search before it starts, so the session looks for the lag over a sliding
// window while it navigates and takes it out of the IMU stamps from then on. Against simulated truth, fed as
// live (each fix arriving after its solution latency, from a datasheet config with no initial state):
//  - an IMU 240 ms late is found within 3 sigma of the truth within the first minutes of driving;
//  - once found, the horizontal error is that of the same drive without latency (within 1.5x), while the
//    session that leaves the lag in is several times worse;
//  - without latency, no lag is ever taken out;
//  - fixes arriving later do not change the decisions (a replayed log decides as the service did).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/geo/earth_model.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"
#include "sim/simulator.hpp"

namespace ldv::est {
namespace {

sim::SimResult window_drive(const std::string& grade, double latency_s, std::uint64_t seed) {
  sim::SimRequest r;
  r.grade = grade;
  r.seed = seed;
  r.duration_s = 500.0;
  r.scenario = "drive";  // 10 m/s turns, up to 25 m/s straights
  r.gnss_rate_hz = 4.0;
  if (latency_s > 0) r.vehicle.imu_latency_s = latency_s;
  return sim::simulate(r);
}

struct LiveRun {
  std::vector<ImuLatencyDecision> decisions;
  double horiz_rms_after_m = 0.0;  // against truth, from `after_s` on
  long dropped_retimed = 0;
};

// Truth position at time t (the nearest truth sample moved by its velocity: the samples are 5 ms apart).
Geodetic truth_pos_at(const sim::SimResult& sim, double t_s) {
  auto it = std::lower_bound(sim.truth.begin(), sim.truth.end(), t_s,
                             [](const sim::TruthSample& s, double t) { return s.t_s < t; });
  if (it == sim.truth.end()) --it;
  if (it != sim.truth.begin() && std::abs(std::prev(it)->t_s - t_s) < std::abs(it->t_s - t_s)) --it;
  return earth::offset_ned(it->pos, it->vel_n_mps * (t_s - it->t_s));
}

LiveRun run_live(const sim::SimResult& sim, bool look_for_latency, double after_s, double extra_gnss_delay_s = 0.0) {
  KfGinsConfig cfg = sim.kfgins;  // noise from the datasheet (the grade); the data are aligned
  cfg.init_pos.reset();
  cfg.init_vel_n_mps.reset();
  cfg.init_rpy_rad.reset();
  FilterOptions fo = options_from_kfgins(cfg);
  fo.history_s = 3.0;  // as the fusion service: late fixes re-process the IMU history
  SessionOptions so = session_options_from(cfg, fo);
  if (look_for_latency) so.imu_latency_window = ImuLatencyWindowOptions{};
  NavFilter filter(fo);
  double sum_sq = 0.0;
  long n = 0;
  NavSession session(so, filter, [&](const NavFilter& f, int) {
    const double t = f.state().t_s;
    if (t < sim.truth.front().t_s + after_s || std::lround(t * 200.0) % 20 != 0) return;  // 10 Hz
    sum_sq += earth::ned_between(truth_pos_at(sim, t), f.state().pos).head<2>().squaredNorm();
    ++n;
  });
  size_t g = 0;
  for (const ImuIncrement& inc : sim.imu) {
    for (; g < sim.gnss.size() && sim.gnss[g].t_s + sim.gnss_latency_s[g] + extra_gnss_delay_s <= inc.t_s; ++g)
      session.add_gnss(sim.gnss[g], inc.t_s);
    session.add_imu(inc, 2300, inc.t_s);
  }
  session.finish();
  LiveRun out;
  if (session.imu_latency_window()) out.decisions = session.imu_latency_window()->decisions();
  out.dropped_retimed = session.imu_samples_dropped_retimed();
  out.horiz_rms_after_m = n > 0 ? std::sqrt(sum_sq / n) : 1e9;
  return out;
}

TEST(ImuLatencyWindow, GivenAnImu240msLate_WhenNavigatingLive_ThenTheLagIsFoundAndCostsNothingOnceTakenOut) {
  for (const char* grade : {"hg1700-typical", "3dm-gx2-typical"}) {
    const double lag_s = 0.24;
    const sim::SimResult late = window_drive(grade, lag_s, 3);
    const sim::SimResult on_time = window_drive(grade, 0.0, 3);  // the same drive and sensor errors, stamped on time
    const LiveRun live = run_live(late, true, 0.0);
    ASSERT_FALSE(live.decisions.empty()) << grade << ": no lag found";
    const ImuLatencyDecision& first = live.decisions.front();
    std::printf(
        "%s: lag %.1f +- %.1f ms decided at %.0f s into the drive (%d turning intervals); %zu decision(s), "
        "the last %.1f +- %.1f ms; %ld samples dropped by the re-timing\n",
        grade, 1e3 * first.lag_s, 1e3 * first.sigma_s, first.from_imu_t_s - late.truth.front().t_s,
        first.turning_intervals, live.decisions.size(), 1e3 * live.decisions.back().lag_s,
        1e3 * live.decisions.back().sigma_s, live.dropped_retimed);
    EXPECT_LT(std::abs(first.lag_s - lag_s), 3.0 * first.sigma_s) << grade;
    EXPECT_LT(std::abs(live.decisions.back().lag_s - lag_s), 3.0 * live.decisions.back().sigma_s) << grade;
    EXPECT_LT(first.from_imu_t_s - late.truth.front().t_s, 200.0) << grade << ": found late";
    EXPECT_NEAR(static_cast<double>(live.dropped_retimed), lag_s * 200.0, 2.0) << "samples re-timed into the past";

    // From 60 s after the decision on: as good as the IMU on time, and far better than the lag left in.
    const double after_s = first.from_imu_t_s - late.truth.front().t_s + 60.0;
    const double rms_found = run_live(late, true, after_s).horiz_rms_after_m;
    const double rms_on_time = run_live(on_time, true, after_s).horiz_rms_after_m;
    const double rms_left_in = run_live(late, false, after_s).horiz_rms_after_m;
    std::printf("%s: horizontal RMS from %.0f s: %.3f m found and taken out, %.3f m on time, %.3f m left in\n", grade,
                after_s, rms_found, rms_on_time, rms_left_in);
    EXPECT_LT(rms_found, 1.5 * rms_on_time) << grade;
    EXPECT_GT(rms_left_in, 2.0 * rms_found) << grade << ": the lag should matter on this drive";
  }
}

// The search runs on a worker thread and its answer is taken at a point fixed in data time: however late the
// fixes arrive (up to the 2 s that point waits), the decisions are the same, so a log replays as it ran live.
TEST(ImuLatencyWindow, GivenFixesArrivingLater_ThenTheDecisionsAreTheSame) {
  const sim::SimResult late = window_drive("3dm-gx2-typical", 0.24, 3);
  const LiveRun prompt = run_live(late, true, 0.0);
  const LiveRun delayed = run_live(late, true, 0.0, 1.5);
  ASSERT_FALSE(prompt.decisions.empty());
  ASSERT_EQ(prompt.decisions.size(), delayed.decisions.size());
  for (size_t i = 0; i < prompt.decisions.size(); ++i) {
    EXPECT_EQ(prompt.decisions[i].lag_s, delayed.decisions[i].lag_s);
    EXPECT_EQ(prompt.decisions[i].from_imu_t_s, delayed.decisions[i].from_imu_t_s);
  }
}

TEST(ImuLatencyWindow, GivenAnImuOnTime_WhenNavigatingLive_ThenNoLagIsTakenOut) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const LiveRun live = run_live(window_drive("3dm-gx2-typical", 0.0, seed), true, 0.0);
    for (const ImuLatencyDecision& d : live.decisions)
      ADD_FAILURE() << "seed " << seed << ": a lag of " << 1e3 * d.lag_s << " +- " << 1e3 * d.sigma_s
                    << " ms taken out";
    EXPECT_EQ(live.dropped_retimed, 0);
  }
}

}  // namespace
}  // namespace ldv::est
