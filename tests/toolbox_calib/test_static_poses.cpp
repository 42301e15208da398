// The static-interval detector on a simulated log whose pose boundaries are known.
#include <gtest/gtest.h>

#include "simulated_imu.hpp"
#include "toolbox/calib/static_poses.hpp"

namespace ldv::calib {
namespace {

TEST(StaticPoses, GivenSimulatedPosesThenEachIsFoundInsideItsTrueInterval) {
  testing::SimulatedSensor sensor{testing::truth_for_grade(false)};
  const testing::SimulatedLogSpec spec;
  const auto sim = testing::simulate_log(sensor, spec, 2);
  StaticDetectorOptions opt;
  opt.init_static_s = spec.init_static_s;
  opt.threshold_multiplier = 3.0;
  const StaticDetection det = detect_static_poses(sim.log, opt);
  ASSERT_EQ(det.poses.size(), sim.pose_samples.size());
  // Slack: the last samples of a constant-rate rotation barely move gravity, so a window that holds a few
  // of them can already be quiet.
  const size_t half_window = 50, slack = 10;
  for (size_t k = 0; k < det.poses.size(); ++k) {
    const auto [b, e] = sim.pose_samples[k];
    // A window centred on a sample is quiet only once it holds no motion: the pose shrinks by half a window.
    EXPECT_GE(det.poses[k].begin + slack, b + (k == 0 ? 0 : half_window)) << k;
    EXPECT_LE(det.poses[k].end, e - half_window + slack) << k;
    EXPECT_GT(det.poses[k].samples(), (e - b) - 2 * half_window - 2 * slack) << k;
  }
}

TEST(StaticPoses, PoseCovarianceIsTheSampleCovarianceOverN) {
  ImuLog log;
  log.dt_s = 0.01;
  for (int i = 0; i < 4; ++i) {
    log.t_s.push_back(i * 0.01);
    log.f_mps2.push_back(Vec3(i, 0.0, 10.0 + (i % 2)));
  }
  const Pose p = make_pose(log, 0, 4);
  EXPECT_NEAR(p.f_mean_mps2.x(), 1.5, 1e-12);
  EXPECT_NEAR(p.f_mean_cov(0, 0), (1.25 / 3.0 * 4.0) / 4.0, 1e-12);  // var of 0..3 (n-1) over n
  EXPECT_NEAR(p.f_mean_cov(2, 2), (1.0 / 3.0) / 4.0, 1e-12);
}

}  // namespace
}  // namespace ldv::calib
