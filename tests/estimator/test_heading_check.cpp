// The heading check (estimator/run/heading_check.hpp) against closed forms: velocity changes turned by a known
// angle give that angle; a GNSS outlier at constant velocity gives none; a standstill gives none. And on a
// simulated drive with GNSS outliers the session never takes them for a failed heading.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/geo/earth_model.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/heading_check.hpp"
#include "estimator/run/run_navigation.hpp"
#include "sim/simulator.hpp"

namespace ldv::est {
namespace {

// A vehicle on a horizontal circle of radius r at speed v (a steady turn: the velocity turns at v / r) from
// t = 0, with fixes every 1 s and the IMU (100 Hz) seeing its velocity changes turned by `imu_turn_rad`
// (a heading wrong by that much); `jump_at_s`: one fix displaced 2 m north. The check's verdict after each fix.
std::vector<std::optional<double>> circle(double imu_turn_rad, double jump_at_s = -1.0, double v = 10.0,
                                          double r = 50.0) {
  std::vector<std::optional<double>> verdicts;
  HeadingCheck check(20.0);
  const Geodetic origin{0.6, -2.0, 100.0};
  const double w = v / r, dt = 0.01;
  auto vel = [&](double t) { return Eigen::Vector2d(-v * std::sin(w * t), v * std::cos(w * t)); };
  const Eigen::Rotation2Dd turn(imu_turn_rad);
  for (int k = 0; k <= 3000; ++k) {
    const double t = k * dt;
    if (k % 100 == 0) {
      GnssFix f;
      f.t_s = t;
      Vec3 ned(r * std::cos(w * t) - r, r * std::sin(w * t), 0.0);
      if (std::abs(t - jump_at_s) < 1e-9) ned.x() += 2.0;
      f.pos = earth::offset_ned(origin, ned);
      f.pos_std_ned_m = Vec3(0.01, 0.01, 0.02);
      check.add_fix(f);
      verdicts.push_back(check.heading_misfit_rad());
    }
    const Eigen::Vector2d dv = turn * (vel(t + dt) - vel(t));
    check.add_imu(Vec3(dv.x(), dv.y(), -9.8 * dt));
  }
  return verdicts;
}

bool never_concluded(const std::vector<std::optional<double>>& verdicts) {
  return std::none_of(verdicts.begin(), verdicts.end(), [](const auto& v) { return v.has_value(); });
}

TEST(HeadingCheck, GivenVelocityChangesTurnedByAKnownAngle_ThenThatAngleIsReturned) {
  for (const double deg : {0.0, 20.0, -45.0, 135.0, 180.0}) {
    const std::optional<double> misfit = circle(deg * kDegToRad).back();
    ASSERT_TRUE(misfit.has_value()) << deg;
    EXPECT_NEAR(std::remainder(*misfit - deg * kDegToRad, 2 * kPi) * kRadToDeg, 0.0, 1.0) << deg;
  }
}

TEST(HeadingCheck, GivenAStraightRunWithAGnssOutlier_ThenNothingIsConcluded) {
  // A circle of radius 1e7 m: straight at 10 m/s; a 2 m jump makes 2-4 m/s velocity changes the IMU never had.
  EXPECT_TRUE(never_concluded(circle(0.0, 15.0, 10.0, 1e7)));
  EXPECT_TRUE(never_concluded(circle(0.0, -1.0, 0.0, 50.0))) << "standing still";
  // In a turn the outlier is left out and the turn still tells the angle.
  const std::optional<double> misfit = circle(30.0 * kDegToRad, 15.0).back();
  ASSERT_TRUE(misfit.has_value());
  EXPECT_NEAR(*misfit * kRadToDeg, 30.0, 2.0);
}

TEST(HeadingCheck, GivenADriveWithGnssOutliers_WhenTheAlignmentIsRight_ThenItIsNeverRedone) {
  sim::SimRequest req;
  req.grade = "3dm-gx2-typical";
  req.scenario = "drive";
  req.duration_s = 400.0;  // to the last stop, after 30 s at 25 m/s
  req.gnss_rate_hz = 4.0;
  req.seed = 1;
  req.vehicle.gnss_outlier_rate = 0.01;
  const sim::SimResult sim = sim::simulate(req);
  KfGinsConfig cfg = sim.kfgins;
  cfg.init_pos.reset();
  cfg.init_vel_n_mps.reset();
  cfg.init_rpy_rad.reset();
  NavFilter filter(options_from_kfgins(cfg));
  const RunSummary sum = run_navigation(sim.imu, sim.gnss, cfg, filter, {});
  EXPECT_EQ(sum.initialisation.find("aligned again"), std::string::npos) << sum.initialisation;
}

}  // namespace
}  // namespace ldv::est
