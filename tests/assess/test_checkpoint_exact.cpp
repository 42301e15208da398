// Exact checkpoints (issue 16): a checkpoint is a copy of the running NavFilter, so a filter restored from it
// continues exactly as the original on the same data, and a restart into a GNSS outage equals the
// uninterrupted run that has the same outage (what cutting the GNSS file gives). The model carries what the
// old checkpoint (a new filter built from options) lost: the GNSS position bias, the moving biases' split and
// ramp rates, the mechanisation's previous increment (coning/sculling), the snapshots and IMU history a late
// fix rewinds to, and fixes queued ahead of the IMU. Equal means to 1e-9 m in position at every IMU epoch and
// bit for bit in the effect states and covariance: both filters do the same arithmetic on the same numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "common/geo/earth_model.hpp"
#include "estimator/run/run_navigation.hpp"
#include "sim/simulator.hpp"
#include "toolbox/assess/filter_checkpoint.hpp"

using namespace ldv;
using namespace ldv::assess;

namespace {

constexpr double kPositionTolerance_m = 1e-9;
constexpr double kCheckpointAfter_s = 200.0;  // mid-run, moving, every estimate settled
constexpr double kOutage_s = 60.0;

// A tactical-grade drive whose IMU biases ramp (the paper's R term) and whose RTK has a slow error (the
// simulator's fixed-mode Gauss-Markov part), with a GNSS time offset: 5 Hz fixes with velocity.
const sim::SimResult& drive() {
  static const sim::SimResult s = [] {
    sim::SimRequest r;
    r.grade = "hg1700-typical";
    r.seed = 16;
    r.duration_s = 330.0;
    r.scenario = "drive";
    r.gnss_rate_hz = 5.0;
    r.gnss_velocity = true;
    // const, B, T, K, R: ramps of 2 deg/h/h and 0.5 m/s/h^2 on every axis
    r.effects = {"gyro_moving_bias=0.5,0.3,600,0.1,2", "accel_moving_bias=0.2,0.05,600,0.02,0.5", "time_offset=0.02"};
    return sim::simulate(r);
  }();
  return s;
}

// kfgins21 with the moving biases in place of the plain biases, the GNSS position bias and the time offset.
est::FilterOptions full_model(const sim::SimResult& s) {
  est::FilterOptions o = est::options_from_kfgins(s.kfgins);
  o.model = "kfgins21";
  o.drop = {"gyro_bias", "accel_bias"};
  o.add = {"gyro_moving_bias", "accel_moving_bias", "gnss_position_bias", "time_offset"};
  // Ramp-rate priors the size of the injected ramps, so the filter estimates them.
  o.gyro_moving_bias.ramp_rate_std = Vec3::Constant(2.0 * kDegToRad / 3600.0 / 3600.0);
  o.accel_moving_bias.ramp_rate_std = Vec3::Constant(0.5 / 3600.0 / 3600.0);
  return o;
}

// Started as run_navigation starts a given state (the simulator's truth at the start of the first increment),
// with the live service's 3 s of history for late fixes.
est::NavFilter started_filter(const sim::SimResult& s) {
  est::FilterOptions o = full_model(s);
  o.history_s = 3.0;
  est::NavFilter f(o);
  est::NavState x;
  x.t_s = s.imu.front().t_s - s.imu.front().dt_s;
  x.pos = *s.kfgins.init_pos;
  x.v_n_mps = *s.kfgins.init_vel_n_mps;
  x.q_b_n = quat_from_euler(*s.kfgins.init_rpy_rad);
  est::NavStd sd;
  sd.pos_ned_m = s.kfgins.init_pos_std_ned_m;
  sd.vel_n_mps = s.kfgins.init_vel_std_n_mps;
  sd.att_rad = s.kfgins.init_att_std_rad;
  f.initialize(x, sd);
  return f;
}

// The drive's inputs in one of two orders: live (each fix once the IMU has passed its availability, epoch +
// latency: the filter rewinds to a snapshot and re-processes its IMU history) or offline (each fix half a
// second before the IMU reaches it: it waits in the filter's queue and is applied exactly at its epoch).
struct Feeder {
  const sim::SimResult* s;
  bool live;
  size_t i = 0, g = 0;

  bool done() const { return i >= s->imu.size(); }
  double next_t_s() const { return s->imu[i].t_s; }
  void step(est::NavFilter& f) {
    const double t = s->imu[i].t_s;
    for (; g < s->gnss.size(); ++g) {
      const double available_s = live ? s->gnss[g].t_s + s->gnss_latency_s[g] : s->gnss[g].t_s - 0.5;
      if (available_s > t) break;
      f.add_gnss(s->gnss[g]);
    }
    f.add_imu(s->imu[i++]);
    f.take_innovations();
  }
};

Eigen::VectorXd effect_segment(const est::NavFilter& f, const std::string& block, int from, int n) {
  const est::StateBlock* b = f.layout().find(block);
  EXPECT_NE(b, nullptr) << block;
  return f.effect_state().segment(b->offset - est::kNavDim + from, n);
}

double max_abs_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() ? (a - b).cwiseAbs().maxCoeff() : INFINITY;
}

void continue_both_and_compare(bool live) {
  const sim::SimResult& s = drive();
  est::NavFilter original = started_filter(s);
  Feeder in{&s, live};
  const double t_checkpoint = s.imu.front().t_s + kCheckpointAfter_s;
  while (in.next_t_s() < t_checkpoint) in.step(original);

  // Given a running filter whose estimates include what a rebuilt filter cannot carry
  const Eigen::VectorXd gnss_bias_m = effect_segment(original, "gnss_position_bias", 0, 3);
  const Eigen::VectorXd gyro_ramp_rate = effect_segment(original, "gyro_moving_bias", 12, 3);
  const Eigen::VectorXd accel_ramp_rate = effect_segment(original, "accel_moving_bias", 12, 3);
  std::printf(
      "at the checkpoint: GNSS position bias [%.4f %.4f %.4f] m, gyro ramp rate %.3g deg/h/h, accel ramp rate "
      "%.3g m/s/h^2 (norms)\n",
      gnss_bias_m(0), gnss_bias_m(1), gnss_bias_m(2), gyro_ramp_rate.norm() * kRadToDeg * 3600.0 * 3600.0,
      accel_ramp_rate.norm() * 3600.0 * 3600.0);
  ASSERT_GT(gnss_bias_m.norm(), 1e-4);
  ASSERT_GT(gyro_ramp_rate.norm(), 0.0);
  ASSERT_GT(accel_ramp_rate.norm(), 0.0);

  // When a checkpoint is taken (every queued fix kept: GNSS continues) and a filter restored from it
  const FilterCheckpoint checkpoint = capture_checkpoint(original, std::numeric_limits<double>::infinity());
  est::NavFilter restored = restore_filter(checkpoint);
  Feeder in_restored = in;

  // Then both continue identically on the same IMU and GNSS data to the end of the run
  double max_pos_m = 0.0, max_vel_mps = 0.0, max_effect = 0.0;
  long epochs = 0;
  while (!in.done()) {
    in.step(original);
    in_restored.step(restored);
    ASSERT_EQ(original.state().t_s, restored.state().t_s);
    max_pos_m = std::max(max_pos_m, earth::ned_between(original.state().pos, restored.state().pos).norm());
    max_vel_mps = std::max(max_vel_mps, (original.state().v_n_mps - restored.state().v_n_mps).norm());
    max_effect = std::max(max_effect, max_abs_difference(original.effect_state(), restored.effect_state()));
    ++epochs;
  }
  std::printf(
      "%s fixes: %ld epochs after the checkpoint, max difference %.3g m position, %.3g m/s velocity, %.3g in an "
      "effect state, %.3g in the covariance at the end\n",
      live ? "late (live)" : "queued (offline)", epochs, max_pos_m, max_vel_mps, max_effect,
      max_abs_difference(original.covariance(), restored.covariance()));
  EXPECT_GT(epochs, 100L * 200L);
  EXPECT_LE(max_pos_m, kPositionTolerance_m);
  EXPECT_EQ(max_effect, 0.0);
  EXPECT_EQ(max_abs_difference(original.covariance(), restored.covariance()), 0.0);
  EXPECT_EQ(original.status(), restored.status());
  EXPECT_EQ(original.faults().late_dropped, 0);
  EXPECT_EQ(original.imu_noise_scale(), restored.imu_noise_scale());
  EXPECT_EQ(original.imu_noise_floor().gyro, restored.imu_noise_floor().gyro);
  EXPECT_EQ(original.imu_noise_floor().accel, restored.imu_noise_floor().accel);
}

}  // namespace

TEST(ExactCheckpoint, RestoredFilterContinuesAsTheOriginalWithLateFixes) { continue_both_and_compare(true); }

TEST(ExactCheckpoint, RestoredFilterContinuesAsTheOriginalWithQueuedFixes) { continue_both_and_compare(false); }

TEST(ExactCheckpoint, RestartIntoAnOutageEqualsTheUninterruptedRunWithThatOutage) {
  const sim::SimResult& s = drive();
  const est::FilterOptions fo = full_model(s);
  // Given an outage starting at a fix epoch mid-run (fixes after it are already queued in the running filter)
  const auto first_after = std::find_if(
      s.gnss.begin(), s.gnss.end(), [&](const GnssFix& g) { return g.t_s >= s.imu.front().t_s + kCheckpointAfter_s; });
  ASSERT_NE(first_after, s.gnss.end());
  const double start_s = first_after->t_s, stop_s = start_s + kOutage_s;

  // When the uninterrupted run (all fixes) is checkpointed at the outage start, as `ldv outage` does
  est::NavFilter uncut(fo);
  std::vector<FilterCheckpoint> checkpoint;
  std::optional<est::NavState> uncut_at_stop;
  est::RunCallbacks cb;
  cb.on_epoch = [&](const est::NavFilter& f) {
    if (checkpoint.empty() && f.state().t_s + 1e-9 >= start_s) checkpoint.push_back(capture_checkpoint(f, start_s));
    if (!uncut_at_stop && f.state().t_s + 1e-9 >= stop_s) uncut_at_stop = f.state();
  };
  est::run_navigation(s.imu, s.gnss, s.kfgins, uncut, cb);
  ASSERT_EQ(checkpoint.size(), 1u);
  ASSERT_TRUE(uncut_at_stop);
  const double t_checkpoint = checkpoint[0].filter.state().t_s;

  // and restarted from there on the IMU alone to the outage end
  std::vector<est::NavState> restart;
  est::NavFilter restored = restore_filter(checkpoint[0]);
  for (const ImuIncrement& m : s.imu)
    if (m.t_s > t_checkpoint + 1e-9 && m.t_s <= stop_s + 1e-9) {
      restored.add_imu(m);
      restart.push_back(restored.state());
    }

  // Then it equals, epoch for epoch, a run from the start with the outage's fixes removed
  std::vector<GnssFix> cut;
  for (const GnssFix& g : s.gnss)
    if (g.t_s <= start_s || g.t_s > stop_s) cut.push_back(g);
  KfGinsConfig cfg = s.kfgins;
  cfg.end_time_s = stop_s + 1e-9;
  est::NavFilter with_outage(fo);
  std::vector<est::NavState> reference;
  est::RunCallbacks rcb;
  rcb.on_epoch = [&](const est::NavFilter& f) {
    if (f.state().t_s > t_checkpoint + 1e-9) reference.push_back(f.state());
  };
  est::run_navigation(s.imu, cut, cfg, with_outage, rcb);
  ASSERT_EQ(restart.size(), reference.size());
  ASSERT_GT(restart.size(), static_cast<size_t>(kOutage_s * 199));
  double max_pos_m = 0.0;
  for (size_t k = 0; k < restart.size(); ++k) {
    ASSERT_EQ(restart[k].t_s, reference[k].t_s) << k;
    max_pos_m = std::max(max_pos_m, earth::ned_between(reference[k].pos, restart[k].pos).norm());
  }
  // And the outage matters: without its fixes the solution has drifted from the uncut one
  const double drift_m = earth::ned_between(uncut_at_stop->pos, restart.back().pos).norm();
  std::printf(
      "%.0f s outage from %.1f s: %zu epochs, restart minus re-run max %.3g m; drift from the uncut run at the end "
      "%.3f m\n",
      kOutage_s, start_s - s.imu.front().t_s, restart.size(), max_pos_m, drift_m);
  EXPECT_LE(max_pos_m, kPositionTolerance_m);
  EXPECT_EQ(with_outage.effect_state(), restored.effect_state());
  EXPECT_GT(drift_m, 0.01);
}

TEST(ExactCheckpoint, RestoredFilterDoesNotReportToTheOriginalsObserver) {
  // The observer is a raw pointer to an object of the original's owner (ldv diagnose): a restart must not call it.
  struct Counter : est::FilterObserver {
    long calls = 0;
    bool wants_matrices() const override { return true; }
    void on_update(const est::InnovationRecord&, const Eigen::MatrixXd&, const Eigen::MatrixXd&) override { ++calls; }
  } counter;
  const sim::SimResult& s = drive();
  est::NavFilter original = started_filter(s);
  original.set_observer(&counter);
  Feeder in{&s, false};
  while (in.next_t_s() < s.imu.front().t_s + 20.0) in.step(original);
  ASSERT_GT(counter.calls, 0);
  const long before = counter.calls;
  est::NavFilter restored = restore_filter(capture_checkpoint(original, std::numeric_limits<double>::infinity()));
  while (in.next_t_s() < s.imu.front().t_s + 40.0) in.step(restored);
  EXPECT_EQ(counter.calls, before);
}
