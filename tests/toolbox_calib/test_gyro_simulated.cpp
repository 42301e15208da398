// Gyro calibration against simulated truth: Earth-rate adjustment for a tactical-grade gyro, rotation
// integration for a MEMS gyro, and a MEMS Earth-rate solve that must be refused as unobservable.
#include <gtest/gtest.h>

#include "simulated_imu.hpp"
#include "toolbox/calib/gyro_earth_rate_model.hpp"
#include "toolbox/calib/gyro_rotation_model.hpp"
#include "toolbox/calib/static_calibration.hpp"

namespace ldv::calib {
namespace {

using testing::SimulatedLogSpec;
using testing::SimulatedSensor;

SimulatedSensor tactical_sensor() {
  SimulatedSensor s{testing::truth_for_grade(true)};
  s.accel_noise_mps2 = 2e-3;
  s.gyro_noise_rad_s = 0.05 * kDegToRad / 60.0 / std::sqrt(0.01);  // ARW 0.05 deg/sqrt(h) at 100 Hz
  return s;
}

SimulatedLogSpec long_poses() {
  SimulatedLogSpec spec;
  spec.poses = 24;
  spec.pose_s = 30.0;
  return spec;
}

VectorXd gyro_truth12(const ImuCalibration& t) {
  VectorXd x(12);
  x << t.gyro.bias, t.gyro.scale, t.gyro.misalignment_rad, t.gyro.frame_rotation_rad;
  return x;
}

std::vector<Pose> gyro_known_poses(const testing::SimulatedLog& sim) {
  std::vector<Pose> poses;
  for (auto [b, e] : sim.pose_samples) poses.push_back(make_pose(sim.log, b, e));
  return poses;
}

TEST(GyroEarthRate, GivenTacticalGyroWhenCalibratedThenTwelveParametersWithinThreeSigma) {
  const SimulatedSensor sensor = tactical_sensor();
  const SimulatedLogSpec spec = long_poses();
  const auto sim = testing::simulate_log(sensor, spec, 21);
  StaticCalibrationOptions opt;
  opt.lat_rad = spec.lat_rad;
  opt.h_m = spec.h_m;
  const StaticCalibrationResult r = calibrate_static(sim.log, opt);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r.gyro_method_used, GyroMethod::kEarthRate) << r.gyro_earth_rate.refusal;
  const VectorXd err = r.gyro_earth_rate.result.x - gyro_truth12(sensor.truth);
  const VectorXd sigma = r.gyro_earth_rate.result.sigma();
  for (int i = 0; i < 12; ++i)
    EXPECT_LT(std::abs(err[i]), 3.0 * sigma[i]) << r.gyro_earth_rate.param_names[i] << " sigma " << sigma[i];
  // The bias is the part Earth rate pins down best: well under 1 deg/h here.
  EXPECT_LT(sigma.head<3>().maxCoeff(), 1.0 * kDegToRad / 3600.0);
}

TEST(GyroEarthRate, GivenSeveralSeedsThenNeesInsideChiSquareBand) {
  const SimulatedSensor sensor = tactical_sensor();
  const SimulatedLogSpec spec = long_poses();
  double nees_sum = 0.0;
  const int seeds = 8;
  for (int seed = 0; seed < seeds; ++seed) {
    const auto sim = testing::simulate_log(sensor, spec, 300 + seed);
    const auto poses = gyro_known_poses(sim);
    // The accelerometer calibration is taken as known, as the pipeline takes its own estimate.
    const GyroEarthRateModel model(sensor.truth.accel, spec.lat_rad, spec.h_m);
    const GaussHelmertResult r =
        solve_gauss_helmert(model, GyroEarthRateModel::blocks(poses), GyroEarthRateModel::initial_guess(poses));
    ASSERT_TRUE(r.converged);
    const VectorXd err = r.x - gyro_truth12(sensor.truth);
    nees_sum += err.dot(r.cov_x_apriori.ldlt().solve(err));
  }
  // chi-square(96): two-sided 99 % band [64.1, 133.5].
  EXPECT_GT(nees_sum, 64.1);
  EXPECT_LT(nees_sum, 133.5);
}

TEST(GyroEarthRate, GivenMemsGyroWhenEarthRateSolveRequestedThenFlaggedUnobservableNotAnswered) {
  SimulatedSensor sensor{testing::truth_for_grade(false)};
  sensor.gyro_noise_rad_s = 0.005 * kDegToRad / std::sqrt(0.01);  // 0.005 deg/s/sqrt(Hz), a good MEMS
  const SimulatedLogSpec spec;
  const auto sim = testing::simulate_log(sensor, spec, 4);
  StaticCalibrationOptions opt;
  opt.gyro_method = GyroMethod::kEarthRate;
  const StaticCalibrationResult r = calibrate_static(sim.log, opt);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r.gyro_earth_rate.attempted);
  EXPECT_FALSE(r.gyro_earth_rate.solved);
  EXPECT_TRUE(r.gyro_earth_rate.undamped_observability.unresolved);
  EXPECT_NE(r.gyro_earth_rate.refusal.find("not observable"), std::string::npos) << r.gyro_earth_rate.refusal;
  EXPECT_EQ(r.gyro_method_used, GyroMethod::kNone);
  EXPECT_EQ(r.calibration.gyro.scale, Vec3::Zero());
}

TEST(GyroRotation, GivenMemsGyroWhenAutoThenRotationMethodRecoversScaleMisalignmentAndRotation) {
  SimulatedSensor sensor{testing::truth_for_grade(false)};
  sensor.gyro_noise_rad_s = 0.005 * kDegToRad / std::sqrt(0.01);
  SimulatedLogSpec spec;
  spec.poses = 16;
  const auto sim = testing::simulate_log(sensor, spec, 8);
  StaticCalibrationOptions opt;
  opt.lat_rad = spec.lat_rad;
  opt.h_m = spec.h_m;
  opt.ev = 0.0;
  const StaticCalibrationResult r = calibrate_static(sim.log, opt);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r.gyro_method_used, GyroMethod::kRotation);
  EXPECT_FALSE(r.gyro_earth_rate.solved);  // auto tried Earth rate first and refused it
  const Adjustment& a = r.gyro_rotation;
  VectorXd truth(9);
  truth << sensor.truth.gyro.scale, sensor.truth.gyro.misalignment_rad, sensor.truth.gyro.frame_rotation_rad;
  const VectorXd err = a.result.x - truth;
  for (int i = 0; i < 9; ++i) EXPECT_LT(std::abs(err[i]), 3.0 * a.result.sigma()[i]) << a.param_names[i];
  EXPECT_LT(a.result.sigma().head<3>().maxCoeff(), 2e-3);  // scale to better than 0.2 %
  EXPECT_NEAR(a.result.sigma0, 1.0, 0.5);
}

TEST(GyroRotation, GivenSeveralSeedsThenNeesInsideChiSquareBand) {
  SimulatedSensor sensor{testing::truth_for_grade(false)};
  sensor.gyro_noise_rad_s = 0.005 * kDegToRad / std::sqrt(0.01);
  SimulatedLogSpec spec;
  spec.poses = 16;
  VectorXd truth(9);
  truth << sensor.truth.gyro.scale, sensor.truth.gyro.misalignment_rad, sensor.truth.gyro.frame_rotation_rad;
  double nees_sum = 0.0;
  const int seeds = 8;
  for (int seed = 0; seed < seeds; ++seed) {
    const auto sim = testing::simulate_log(sensor, spec, 500 + seed);
    const auto poses = gyro_known_poses(sim);
    const GyroRotationModel model(sim.log, poses, sensor.truth.accel, find_clipped_samples(sim.log));
    const GaussHelmertResult r = solve_gauss_helmert(model, model.blocks(), VectorXd::Zero(9));
    ASSERT_TRUE(r.converged);
    const VectorXd err = r.x - truth;
    nees_sum += err.dot(r.cov_x_apriori.ldlt().solve(err));
  }
  // chi-square(72): two-sided 99 % band [44.8, 106.4].
  EXPECT_GT(nees_sum, 44.8);
  EXPECT_LT(nees_sum, 106.4);
}

// Exact cube poses (axis up and down, level on a table): gravity has two zero components in the body, and the
// misclosure's tangent basis, chosen anew at every evaluation from the smallest component, switched between the
// tied axes with the noise; the adjustment straddling the switch did not converge in 50 iterations (3 of 3 seeds
// of the paper's HG1700 on `ldv sim`'s multiposition poses rounded to exact). The basis axis is now chosen once
// per transition.
TEST(GyroRotation, GivenExactCubePosesThenTheRotationMethodConvergesAndRecoversTheTruth) {
  SimulatedSensor sensor{testing::truth_for_grade(true)};
  sensor.gyro_noise_rad_s = 1e-4;
  SimulatedLogSpec spec;
  // The pose with body axis `down_b` pointing down (NED), turned by yaw: the six axis poses (two gravity
  // components exactly 0) and the eight cube corners.
  const auto pose = [](const Vec3& down_b, double yaw_deg) {
    return Mat3(Eigen::AngleAxisd(yaw_deg * kDegToRad, Vec3::UnitZ()) *
                Quat::FromTwoVectors(down_b.normalized(), Vec3::UnitZ()));
  };
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {1.0, -1.0}) spec.orientations.push_back(pose(sign * Vec3::Unit(axis), 60.0 * axis + 30.0 * sign));
  for (int corner = 0; corner < 8; ++corner)
    spec.orientations.push_back(
        pose(Vec3(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1), 45.0 * corner));
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    const auto sim = testing::simulate_log(sensor, spec, seed);
    StaticCalibrationOptions opt;
    opt.lat_rad = spec.lat_rad;
    opt.h_m = spec.h_m;
    opt.ev = 0.0;
    opt.gyro_method = GyroMethod::kRotation;
    const StaticCalibrationResult r = calibrate_static(sim.log, opt);
    ASSERT_TRUE(r.ok()) << "seed " << seed;
    const Adjustment& a = r.gyro_rotation;
    ASSERT_TRUE(a.result.converged) << "seed " << seed;
    EXPECT_LT(a.result.iterations, 10) << "seed " << seed;
    for (int i = 0; i < 3; ++i)
      EXPECT_LT(std::abs(a.result.x[i] - sensor.truth.gyro.scale[i]), 3.0 * a.result.sigma()[i])
          << a.param_names[i] << " seed " << seed;
  }
}

}  // namespace
}  // namespace ldv::calib
