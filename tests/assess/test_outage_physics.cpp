// Outage drift physics against independent truth: free-inertial segments started from the simulator's
// true state (a checkpoint made from truth, nothing estimated), run by the same segment code `ldv outage`
// uses. A perfect IMU does not drift; a constant accelerometer bias b drifts 1/2 b t^2; a gyro bias w
// tilts the platform and drifts 1/6 g w t^3 (both minus the Schuler term, < 0.1 % here).
#include <gtest/gtest.h>

#include "sim_drive.hpp"
#include "toolbox/assess/filter_checkpoint.hpp"
#include "toolbox/assess/outage_run.hpp"

using namespace ldv;
using namespace ldv::assess;

namespace {

// A filter at the true state at t_start (no estimated errors, no ZUPT), as a checkpoint.
FilterCheckpoint checkpoint_at_truth(const sim::SimResult& s, double t_start_s) {
  est::FilterOptions o;
  o.model = "ins15";
  o.zupt.enabled = false;
  const NavSeries series = test::truth_series(s);
  const NavSample truth = *series.at(t_start_s);
  est::NavFilter f(o);
  f.initialize(est::NavState{truth.t_s, truth.pos, truth.vel_n_mps, truth.q_b_n}, est::NavStd{});
  return capture_checkpoint(f, truth.t_s);  // nothing queued: a fresh filter
}

OutageResult free_inertial(const sim::SimResult& s, double start_s, double length_s) {
  const double t0 = s.imu.front().t_s;
  const OutageWindow w{length_s, t0 + start_s, true};
  const NavSeries truth = test::truth_series(s);
  return run_outage_segment(checkpoint_at_truth(s, w.start_s), w, s.imu, truth, {});
}

}  // namespace

TEST(OutagePhysics, PerfectImuDoesNotDrift) {
  const auto& s = test::sim_drive("perfect", 500.0, "drive", {}, false);
  const OutageResult r = free_inertial(s, 100.0, 300.0);
  EXPECT_NEAR(r.t_end_s - r.window.start_s, 300.0, 0.01);
  EXPECT_LT(r.end_drift.pos_ned_m.norm(), 0.02);
  EXPECT_LT(r.end_drift.vel_ned_mps.norm(), 1e-4);
  EXPECT_LT(r.end_drift.att_phi_n_rad.norm() * kRadToDeg, 1e-5);
  EXPECT_GT(r.curve.size(), 290u);
}

TEST(OutagePhysics, AccelerometerBiasDriftsHalfBTSquared) {
  // 1 mg on the forward axis of a vehicle standing still (levelled, heading 30 deg).
  const auto& s = test::sim_drive("perfect", 200.0, "static", {"accel_bias=1,0,0"}, false);
  const double b = 1e-3 * 9.80665, t = 60.0;
  const OutageResult r = free_inertial(s, 20.0, t);
  const double expect = 0.5 * b * t * t;  // 17.7 m
  EXPECT_NEAR(r.end_drift.pos_ned_m.head<2>().norm(), expect, 0.02 * expect);
  // Along the heading (30 deg): north and east in the ratio cos/sin.
  EXPECT_NEAR(std::atan2(r.end_drift.pos_ned_m.y(), r.end_drift.pos_ned_m.x()) * kRadToDeg, 30.0, 1.0);
  EXPECT_NEAR(r.end_drift.vel_ned_mps.head<2>().norm(), b * t, 0.02 * b * t);
}

TEST(OutagePhysics, GyroBiasDriftsOneSixthGWTCubed) {
  // 10 deg/h on the roll axis: the platform tilts w t, gravity leaks in sideways.
  const auto& s = test::sim_drive("perfect", 200.0, "static", {"gyro_bias=10,0,0"}, false);
  const double w = 10.0 * kDegToRad / 3600.0, t = 90.0, g = 9.80;
  const OutageResult r = free_inertial(s, 20.0, t);
  const double expect = g * w * t * t * t / 6.0;  // 59 m
  EXPECT_NEAR(r.end_drift.pos_ned_m.head<2>().norm(), expect, 0.03 * expect);
  EXPECT_NEAR(std::abs(r.end_drift.rpy_rad.x()), w * t, 0.02 * w * t);  // roll error w t
}
