// Real MPU-6050 log (tomisuarez2/ImuCalibration, ../shared/data/calib/mpu6050): compared with the data
// owner's own result (a peer's answer, not truth), and the 90-degree rotation check of the gyro calibration.
#include <gtest/gtest.h>

#include <cstdio>

#include "common/io/text_table.hpp"
#include "real_data.hpp"
#include "toolbox/calib/gyro_rotation_model.hpp"
#include "toolbox/calib/static_calibration.hpp"

namespace ldv::calib {
namespace {

using testing::axis_non_orthogonality_rad;
using testing::row_gains;
using testing::shared_data;

constexpr double kG0 = 9.80665;           // the peer fitted to standard gravity: so do we, to compare
constexpr double kAccCountsPerG = 16384;  // +-2 g range
constexpr double kGyroCountsPerDegS = 131;  // +-250 deg/s range

ImuLogOptions mpu_units() {
  ImuLogOptions o;
  o.accel = {kAccCountsPerG, 0.0, kG0};
  o.gyro = {kGyroCountsPerDegS, 0.0, kDegToRad};
  return o;
}

const StaticCalibrationResult& mpu_run() {
  static const StaticCalibrationResult r = [] {
    const ImuLog log = read_csv_log(shared_data("calib/mpu6050/calibration_poses.csv"), mpu_units());
    StaticCalibrationOptions opt;
    opt.gravity_mps2 = kG0;
    opt.gyro_full_scale_rad_s = 250.0 * kDegToRad;  // the gyro clips in three of the hand rotations
    return calibrate_static(log, opt);
  }();
  return r;
}

std::vector<double> read_column(const std::string& path) {
  std::vector<double> v;
  read_numeric_table(path, 1, 1, [&](long, const std::vector<double>& row) { v.push_back(row[0]); });
  return v;
}

TEST(RealMpu6050, AccelerometerAgreesWithTheDataOwnersCalibration) {
  const StaticCalibrationResult& r = mpu_run();
  ASSERT_TRUE(r.ok()) << r.accel.refusal;
  EXPECT_EQ(r.detection.poses.size(), 10u);  // the data owner found 10 intervals too
  // Peer model (Tedaldi): f = T K (raw + b), T = [[1, -a0, a1], [0, 1, -a2], [0, 0, 1]], K = diag(k) [m/s^2 per count].
  const std::vector<double> p = read_column(shared_data("calib/mpu6050/their_params_acc.csv"));
  ASSERT_EQ(p.size(), 9u);
  Mat3 T;
  T << 1, -p[0], p[1], 0, 1, -p[2], 0, 0, 1;
  const Mat3 peer_counts_per_si = (T * Vec3(p[3], p[4], p[5]).asDiagonal()).inverse();
  const Vec3 peer_offset_counts = -Vec3(p[6], p[7], p[8]);
  const double counts_per_si = kAccCountsPerG / kG0;
  const Mat3 ours_counts_per_si = counts_per_si * r.calibration.accel.sensor_matrix();
  const Vec3 ours_offset_counts = counts_per_si * r.calibration.accel.bias;
  const Vec3 g_ours = row_gains(ours_counts_per_si), g_peer = row_gains(peer_counts_per_si);
  const Vec3 n_ours = axis_non_orthogonality_rad(ours_counts_per_si), n_peer = axis_non_orthogonality_rad(peer_counts_per_si);
  const Vec3 scale_sigma = r.calibration.accel.scale_sigma;
  for (int i = 0; i < 3; ++i) {
    std::printf("accel axis %d: gain %.1f vs peer %.1f counts/(m/s^2) (%.3f %%, our sigma %.3f %%); offset %.1f vs %.1f "
                "counts; non-orthogonality %.2f vs %.2f mrad\n",
                i, g_ours[i], g_peer[i], 100 * (g_ours[i] / g_peer[i] - 1), 100 * scale_sigma[i], ours_offset_counts[i],
                peer_offset_counts[i], 1e3 * n_ours[i], 1e3 * n_peer[i]);
    // Same data, same gravity, two least-squares fits: they may differ by our own uncertainty (3 sigma, with a
    // floor of 0.1 %) but not by the +-3 % sensitivity tolerance of the chip's datasheet.
    EXPECT_NEAR(g_ours[i] / g_peer[i], 1.0, std::max(3.0 * scale_sigma[i], 1e-3));
    EXPECT_NEAR(ours_offset_counts[i], peer_offset_counts[i], std::max(3.0 * counts_per_si * r.calibration.accel.bias_sigma[i], 10.0));
  }
}

TEST(RealMpu6050, GyroComparedWithTheDataOwnersCalibration) {
  const StaticCalibrationResult& r = mpu_run();
  ASSERT_EQ(r.gyro_method_used, GyroMethod::kRotation);
  EXPECT_FALSE(r.gyro_earth_rate.solved);  // MEMS: Earth rate refused
  EXPECT_GE(r.clipped_transitions.size(), 2u);
  // Peer: w = T K (raw - b), T = [[1, -m0, m1], [m2, 1, -m3], [-m4, m5, 1]], K [rad/s per count], b [counts].
  const std::vector<double> p = read_column(shared_data("calib/mpu6050/their_params_gyro.csv"));
  ASSERT_EQ(p.size(), 12u);
  Mat3 T;
  T << 1, -p[0], p[1], p[2], 1, -p[3], -p[4], p[5], 1;
  const Mat3 peer_counts_per_si = (T * Vec3(p[6], p[7], p[8]).asDiagonal()).inverse();
  const double counts_per_si = kGyroCountsPerDegS / kDegToRad;
  const Mat3 ours = counts_per_si * r.calibration.gyro.sensor_matrix();
  const Vec3 g_ours = row_gains(ours), g_peer = row_gains(peer_counts_per_si);
  const Vec3 n_ours = axis_non_orthogonality_rad(ours), n_peer = axis_non_orthogonality_rad(peer_counts_per_si);
  for (int i = 0; i < 3; ++i) {
    std::printf("gyro axis %d: gain %.1f vs peer %.1f counts/(rad/s) (%.2f %%, our sigma %.2f %%); bias %.1f vs %.1f "
                "counts; non-orthogonality %.2f vs %.2f mrad\n",
                i, g_ours[i], g_peer[i], 100 * (g_ours[i] / g_peer[i] - 1), 100 * r.calibration.gyro.scale_sigma[i],
                counts_per_si * r.calibration.gyro.bias[i], p[9 + i], 1e3 * n_ours[i], 1e3 * n_peer[i]);
    // Physically justified: the datasheet's sensitivity tolerance is +-3 %, so each answer must lie within
    // 3 % of nominal (ours with its 3 sigma); the peer's fit also used the rotations where the gyro clipped.
    EXPECT_LT(std::abs(r.calibration.gyro.scale[i]), 0.03 + 3.0 * r.calibration.gyro.scale_sigma[i]);
    EXPECT_NEAR(counts_per_si * r.calibration.gyro.bias[i], p[9 + i], 30.0);  // turn-on bias, same log
  }
}

TEST(RealMpu6050, IntegratingTheCalibratedGyroOverTheNinetyDegreeRotationGivesNinetyDegrees) {
  const StaticCalibrationResult& cal = mpu_run();
  ASSERT_EQ(cal.gyro_method_used, GyroMethod::kRotation);
  const ImuLog log = read_csv_log(shared_data("calib/mpu6050/rotation_90deg_x.csv"), mpu_units());
  StaticDetectorOptions det;
  det.init_static_s = 10.0;  // the log starts with ~16 s at rest
  det.threshold_multiplier = 5.0;
  const StaticDetection d = detect_static_poses(log, det);
  ASSERT_EQ(d.poses.size(), 2u);
  const Pose& a = d.poses.front();
  const Pose& b = d.poses.back();
  // The turn-on bias is re-measured at rest before and after, as a user of a MEMS calibration must.
  const Mat3 C = integrate_attitude(log, a.end - 1, b.begin, cal.calibration.gyro, a.w_mean_rad_s, b.w_mean_rad_s);
  const Vec3 rotvec = rotvec_from_quat(Quat(C));
  TriadCalibration nominal;
  const Vec3 rotvec_nominal =
      rotvec_from_quat(Quat(integrate_attitude(log, a.end - 1, b.begin, nominal, a.w_mean_rad_s, b.w_mean_rad_s)));
  // Independent witness: the calibrated accelerometers' tilt change between the two rests.
  const Vec3 u0 = cal.calibration.accel.correct(a.f_mean_mps2).normalized();
  const Vec3 u1 = cal.calibration.accel.correct(b.f_mean_mps2).normalized();
  const double tilt_deg = std::acos(u0.dot(u1)) * kRadToDeg;
  const double angle_deg = rotvec.norm() * kRadToDeg;
  const double sigma_deg = angle_deg * cal.calibration.gyro.scale_sigma.maxCoeff();
  std::printf("90-degree check: calibrated gyro %.2f deg (about x: %.2f deg, sigma from scale %.2f deg), nominal "
              "conversion %.2f deg, accelerometer tilt change %.2f deg, motion %.1f s\n",
              angle_deg, rotvec.x() * kRadToDeg, sigma_deg, rotvec_nominal.norm() * kRadToDeg, tilt_deg,
              b.t_begin_s - a.t_end_s);
  EXPECT_GT(std::abs(rotvec.x()), 0.95 * rotvec.norm());  // a rotation about x
  // Tolerance from the calibration's own uncertainty: with the clipped rotations left out, six transitions
  // pin the x scale to a few percent only (sigma_deg), and the rotation itself is a hand-made "90 degrees"
  // (the accelerometers saw the actual tilt change): 3 sigma + 1 deg for the hand, against both.
  const double tolerance_deg = 3.0 * sigma_deg + 1.0;
  EXPECT_NEAR(angle_deg, tilt_deg, tolerance_deg);
  EXPECT_NEAR(angle_deg, 90.0, tolerance_deg);
  EXPECT_LT(sigma_deg, 5.0);  // the check must still mean something
}

}  // namespace
}  // namespace ldv::calib
