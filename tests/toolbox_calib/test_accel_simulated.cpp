// Accelerometer gravity-magnitude adjustment against simulated truth: every parameter within 3 sigma,
// sigmas consistent over seeds (NEES inside the chi-square band), sigma0 near 1.
#include <gtest/gtest.h>

#include "simulated_imu.hpp"
#include "toolbox/calib/accel_gravity_model.hpp"
#include "toolbox/calib/static_calibration.hpp"

namespace ldv::calib {
namespace {

using testing::SimulatedLogSpec;
using testing::SimulatedSensor;

VectorXd accel_truth(const ImuCalibration& t) {
  VectorXd x(9);
  x << t.accel.bias, t.accel.scale, t.accel.misalignment_rad;
  return x;
}

std::vector<Pose> known_poses(const testing::SimulatedLog& sim) {
  std::vector<Pose> poses;
  for (auto [b, e] : sim.pose_samples) poses.push_back(make_pose(sim.log, b, e));
  return poses;
}

TEST(AccelSimulated, GivenKnownSensorWhenAdjustedThenEveryParameterWithinThreeSigma) {
  SimulatedSensor sensor{testing::truth_for_grade(false)};
  const SimulatedLogSpec spec;
  const auto sim = testing::simulate_log(sensor, spec, 7);
  const double g = earth::gravity_n(spec.lat_rad, spec.h_m).norm();
  const AccelGravityModel model(g);
  const auto poses = known_poses(sim);
  const GaussHelmertResult r = solve_gauss_helmert(model, AccelGravityModel::blocks(poses),
                                                   AccelGravityModel::initial_guess(poses, g));
  ASSERT_TRUE(r.converged);
  EXPECT_FALSE(r.observability.rank_deficient);
  const VectorXd err = r.x - accel_truth(sensor.truth);
  for (int i = 0; i < 9; ++i) EXPECT_LT(std::abs(err[i]), 3.0 * r.sigma()[i]) << model.param_names()[i];
}

TEST(AccelSimulated, GivenManySeedsWhenAdjustedThenNeesInsideChiSquareBand) {
  SimulatedSensor sensor{testing::truth_for_grade(false)};
  const SimulatedLogSpec spec;
  const double g = earth::gravity_n(spec.lat_rad, spec.h_m).norm();
  const AccelGravityModel model(g);
  const int seeds = 30;
  double nees_sum = 0.0, s0sq_sum = 0.0;
  for (int seed = 0; seed < seeds; ++seed) {
    const auto sim = testing::simulate_log(sensor, spec, 100 + seed);
    const auto poses = known_poses(sim);
    const GaussHelmertResult r = solve_gauss_helmert(model, AccelGravityModel::blocks(poses),
                                                     AccelGravityModel::initial_guess(poses, g));
    const VectorXd err = r.x - accel_truth(sensor.truth);
    nees_sum += err.dot(r.cov_x_apriori.ldlt().solve(err));
    s0sq_sum += r.sigma0 * r.sigma0;
  }
  // Sum of 30 NEES with 9 dof is chi-square(270): two-sided 99 % band [212, 335].
  EXPECT_GT(nees_sum, 212.0);
  EXPECT_LT(nees_sum, 335.0);
  // sigma0^2 averages to 1 when the pose covariances are right (15 redundancy x 30 seeds: +-0.2 is > 3 sigma).
  EXPECT_NEAR(s0sq_sum / seeds, 1.0, 0.2);
}

TEST(AccelSimulated, GivenFullLogWhenCalibratedThenDetectorFindsEveryPoseAndCorrectionRestoresGravity) {
  SimulatedSensor sensor{testing::truth_for_grade(false)};
  const SimulatedLogSpec spec;
  const auto sim = testing::simulate_log(sensor, spec, 11);
  StaticCalibrationOptions opt;
  opt.lat_rad = spec.lat_rad;
  opt.h_m = spec.h_m;
  opt.gyro_method = GyroMethod::kNone;
  const StaticCalibrationResult r = calibrate_static(sim.log, opt);
  ASSERT_TRUE(r.ok()) << r.accel.refusal;
  EXPECT_EQ(r.detection.poses.size(), static_cast<size_t>(spec.poses));
  const VectorXd err = r.accel.result.x - accel_truth(sensor.truth);
  for (int i = 0; i < 9; ++i) EXPECT_LT(std::abs(err[i]), 3.0 * r.accel.result.sigma()[i]) << i;
  // Applying the calibration to a fresh noiseless sample returns the true specific force.
  const Vec3 f_b(1.0, -2.0, -9.5);
  const ImuRates corrected = apply_calibration(
      r.calibration, ImuRates{sensor.truth.accel.sensor_matrix() * f_b + sensor.truth.accel.bias, Vec3::Zero()});
  EXPECT_LT((corrected.f_b_mps2 - f_b).norm(), 5e-3);
}

TEST(AccelSimulated, GivenTooFewPosesWhenCalibratedThenRankDeficiencyIsReportedNotAnswered) {
  SimulatedSensor sensor{testing::truth_for_grade(false)};
  SimulatedLogSpec spec;
  spec.poses = 6;  // 6 conditions for 9 unknowns
  const auto sim = testing::simulate_log(sensor, spec, 3);
  StaticCalibrationOptions opt;
  opt.detector.threshold_multiplier = 3.0;
  opt.gyro_method = GyroMethod::kNone;
  const StaticCalibrationResult r = calibrate_static(sim.log, opt);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.accel.refusal.find("rank deficient"), std::string::npos) << r.accel.refusal;
  EXPECT_TRUE(r.accel.undamped_observability.rank_deficient);
  EXPECT_GE(r.accel.undamped_observability.weak_directions.size(), 3u);
  EXPECT_EQ(r.calibration.accel.scale, Vec3::Zero());  // nothing produced
}

TEST(AccelSimulated, GivenDampingSweepThenResidualGrowsEigenvalueFallsAndWellPosedProblemKeepsEvSmall) {
  SimulatedSensor sensor{testing::truth_for_grade(false)};
  const SimulatedLogSpec spec;
  const auto sim = testing::simulate_log(sensor, spec, 5);
  const double g = earth::gravity_n(spec.lat_rad, spec.h_m).norm();
  const AccelGravityModel model(g);
  const auto poses = known_poses(sim);
  const DampingSweep sw = sweep_damping(model, AccelGravityModel::blocks(poses),
                                        AccelGravityModel::initial_guess(poses, g), default_ev_grid());
  ASSERT_EQ(sw.points.size(), default_ev_grid().size());
  EXPECT_LT(sw.points.back().max_cov_eigenvalue, sw.points.front().max_cov_eigenvalue);
  EXPECT_GT(sw.points.back().rms_misclosure, sw.points.front().rms_misclosure);
  EXPECT_LE(sw.best().ev, 1e-3);  // well determined: damping only adds bias
}

}  // namespace
}  // namespace ldv::calib
