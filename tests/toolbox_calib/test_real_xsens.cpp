// Real Xsens MTi multi-position log (imu_tk test data, ../shared/data/calib/xsens_tedaldi) against the
// vendor's own calibration of the unit: scale within 2 %, non-orthogonality within 0.01 rad.
#include <gtest/gtest.h>

#include <cstdio>

#include "real_data.hpp"
#include "toolbox/calib/static_calibration.hpp"

namespace ldv::calib {
namespace {

using testing::axis_non_orthogonality_rad;
using testing::row_gains;

// Nominal conversion we give the tool (round numbers, not the vendor's): counts per SI unit, 16-bit offset.
constexpr double kAccCountsPerMps2 = 400.0, kGyroCountsPerRadS = 5000.0, kOffsetCounts = 32768.0;

struct XsensRun {
  ImuLog log;
  StaticCalibrationResult result;
};

const XsensRun& xsens_run() {
  static const XsensRun run = [] {
    XsensRun r;
    ImuLogOptions o;
    o.accel = {kAccCountsPerMps2, kOffsetCounts, 1.0};
    o.gyro = {kGyroCountsPerRadS, kOffsetCounts, 1.0};
    r.log = read_xyz_pair(testing::shared_data("calib/xsens_tedaldi/xsens_acc.txt"),
                          testing::shared_data("calib/xsens_tedaldi/xsens_gyro.txt"), o);
    StaticCalibrationOptions opt;
    opt.detector.init_static_s = 50.0;  // the data set's initialisation period (imu_tk: 5000 samples)
    opt.lat_rad = 45.41 * kDegToRad;    // Padova
    opt.h_m = 12.0;
    r.result = calibrate_static(r.log, opt);
    return r;
  }();
  return run;
}

// Vendor reference (data README): gains in counts per SI unit and misalignment matrices whose rows are the
// sensitive directions (they include the triad's rotation in the housing).
const Vec3 kVendorAccGain(415, 413, 415), kVendorGyroGain(4778, 4758, 4766);
Mat3 vendor_acc_misalignment() {
  Mat3 m;
  m << 1.00, 0.00, -0.01, 0.01, 1.00, 0.01, 0.02, 0.01, 1.00;
  return m;
}
Mat3 vendor_gyro_misalignment() {
  Mat3 m;
  m << 1.00, -0.01, -0.02, 0.00, 1.00, 0.04, -0.01, 0.01, 1.00;
  return m;
}

TEST(RealXsens, AccelerometerScaleWithinTwoPercentAndNonOrthogonalityWithinTenMilliradOfVendor) {
  const StaticCalibrationResult& r = xsens_run().result;
  ASSERT_TRUE(r.ok()) << r.accel.refusal;
  EXPECT_GE(r.detection.poses.size(), 30u);
  const Mat3 M = r.calibration.accel.sensor_matrix();
  const Vec3 gain = row_gains(M) * kAccCountsPerMps2;
  const Vec3 nonorth = axis_non_orthogonality_rad(M);
  const Vec3 vendor_nonorth = axis_non_orthogonality_rad(vendor_acc_misalignment());
  for (int i = 0; i < 3; ++i) {
    std::printf("accel axis %d: gain %.2f counts/(m/s^2) vendor %.0f (%.3f %%); non-orthogonality %.4f rad vendor %.4f\n",
                i, gain[i], kVendorAccGain[i], 100 * (gain[i] / kVendorAccGain[i] - 1), nonorth[i], vendor_nonorth[i]);
    EXPECT_NEAR(gain[i] / kVendorAccGain[i], 1.0, 0.02);
    EXPECT_NEAR(nonorth[i], vendor_nonorth[i], 0.01);
  }
  // The vendor's misalignment is quoted to 0.01: non-orthogonality is the sum of two such entries.
  double ss = 0.0;
  for (double v : r.gravity_residual_after_mps2) ss += v * v;
  const double rms_after = std::sqrt(ss / r.gravity_residual_after_mps2.size());
  std::printf("gravity magnitude residual after calibration: rms %.3g m/s^2 over %zu poses; sigma0 %.2f\n",
              rms_after, r.gravity_residual_after_mps2.size(), r.accel.result.sigma0);
  EXPECT_LT(rms_after, 3e-3);  // 0.3 mg: the Xsens' 16-bit resolution is 2.4 mm/s^2 per count
}

TEST(RealXsens, GyroEarthRateSolveRefusedAndRotationMethodMatchesVendor) {
  const StaticCalibrationResult& r = xsens_run().result;
  ASSERT_TRUE(r.ok());
  // A MEMS gyro cannot resolve 15 deg/h: the Earth-rate adjustment must refuse, not answer.
  EXPECT_TRUE(r.gyro_earth_rate.attempted);
  EXPECT_FALSE(r.gyro_earth_rate.solved);
  ASSERT_EQ(r.gyro_method_used, GyroMethod::kRotation) << r.gyro_rotation.refusal;
  const Mat3 M = r.calibration.gyro.sensor_matrix();
  const Vec3 gain = row_gains(M) * kGyroCountsPerRadS;
  const Vec3 nonorth = axis_non_orthogonality_rad(M);
  const Vec3 vendor_nonorth = axis_non_orthogonality_rad(vendor_gyro_misalignment());
  for (int i = 0; i < 3; ++i) {
    std::printf("gyro axis %d: gain %.1f counts/(rad/s) vendor %.0f (%.3f %%); non-orthogonality %.4f rad vendor %.4f\n",
                i, gain[i], kVendorGyroGain[i], 100 * (gain[i] / kVendorGyroGain[i] - 1), nonorth[i], vendor_nonorth[i]);
    EXPECT_NEAR(gain[i] / kVendorGyroGain[i], 1.0, 0.02);
    EXPECT_NEAR(nonorth[i], vendor_nonorth[i], 0.01);
  }
  double ss = 0.0;
  for (double v : r.rotation_residual_rad) ss += v * v;
  std::printf("gravity direction after integrating the calibrated gyro: rms %.3f deg over %zu transitions\n",
              std::sqrt(ss / r.rotation_residual_rad.size()) * kRadToDeg, r.rotation_residual_rad.size());
}

}  // namespace
}  // namespace ldv::calib
