// The calibration file and the library API that ldv nav / imu_acq use.
#include <gtest/gtest.h>

#include "common/formats/kfgins_config.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/io/input_error.hpp"
#include "simulated_imu.hpp"
#include "common/formats/imu_calibration.hpp"

namespace ldv::calib {
namespace {

TEST(CalibrationFile, SaveLoadRoundTripKeepsEveryValue) {
  ImuCalibration c = testing::truth_for_grade(false);
  c.accel.scale_sigma = Vec3(1e-5, 2e-5, 3e-5);
  c.description = "round \"trip\"";
  const std::string path = ::testing::TempDir() + "/cal_roundtrip.yaml";
  save_calibration(path, c);
  const ImuCalibration l = load_calibration(path);
  EXPECT_LT((l.accel.sensor_matrix() - c.accel.sensor_matrix()).norm(), 1e-9);
  EXPECT_LT((l.gyro.sensor_matrix() - c.gyro.sensor_matrix()).norm(), 1e-9);
  EXPECT_LT((l.gyro.bias - c.gyro.bias).norm(), 1e-12);
  EXPECT_LT((l.accel.scale_sigma - c.accel.scale_sigma).norm(), 1e-12);
}

TEST(CalibrationFile, ApplyCalibrationInvertsTheSensorModelForRatesAndIncrements) {
  const ImuCalibration c = testing::truth_for_grade(false);
  const Vec3 f_b(0.3, -1.2, -9.7), w_b(0.2, -0.1, 0.4);
  const ImuRates raw{c.accel.sensor_matrix() * f_b + c.accel.bias, c.gyro.sensor_matrix() * w_b + c.gyro.bias};
  const ImuRates out = apply_calibration(c, raw);
  EXPECT_LT((out.f_b_mps2 - f_b).norm(), 1e-12);
  EXPECT_LT((out.w_b_rad_s - w_b).norm(), 1e-12);
  ImuIncrement inc;
  inc.dt_s = 0.005;
  inc.dvel_b_mps = raw.f_b_mps2 * inc.dt_s;
  inc.dtheta_b_rad = raw.w_b_rad_s * inc.dt_s;
  const ImuIncrement ci = apply_calibration(c, inc);
  EXPECT_LT((ci.dvel_b_mps - f_b * inc.dt_s).norm(), 1e-14);
  EXPECT_LT((ci.dtheta_b_rad - w_b * inc.dt_s).norm(), 1e-14);
}

TEST(CalibrationFile, GivenMissingKeyThenInputErrorNamesFileAndKey) {
  const std::string path = ::testing::TempDir() + "/cal_bad.yaml";
  std::ofstream(path) << "format: ldv_imu_calibration_v1\naccel:\n  bias_mps2: [0, 0, 0]\n  scale_ppm: [0, 0, 0]\n"
                         "  misalignment_rad: [0, 0, 0]\ngyro:\n  scale_ppm: [0, 0, 0]\n";
  try {
    load_calibration(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cal_bad.yaml"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("bias_rad_s"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_calibration(::testing::TempDir() + "/does_not_exist.yaml"), InputError);
}

TEST(CalibrationFile, GivenValuesNoSensorHas_ThenInputErrorNamesLineAndKey) {
  const std::string path = ::testing::TempDir() + "/cal_units.yaml";
  const auto refused_at = [&](const std::string& accel_extra, const std::string& where) {
    std::ofstream(path) << "format: ldv_imu_calibration_v1\ngyro:\n  bias_rad_s: [0, 0, 0]\n  scale_ppm: [0, 0, 0]\n"
                           "  misalignment_rad: [0, 0, 0]\naccel:\n  bias_mps2: [0, 0, 0]\n  scale_ppm: [0, 0, 0]\n"
                           "  misalignment_rad: [0, 0, 0]\n"
                        << accel_extra;
    try {
      load_calibration(path);
      ADD_FAILURE() << "accepted " << accel_extra;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
    }
  };
  refused_at("  frame_rotation_rad: [0, 0, 30]\n", "cal_units.yaml:10: 'accel.frame_rotation_rad': element 3 is 30");
  refused_at("  bias_mps2_sigma: [0.1, -0.1, 0.1]\n", "cal_units.yaml:10: 'accel.bias_mps2_sigma'");
  refused_at("  scale_ppm_sigma: [1, 2]\n", "cal_units.yaml:10: 'accel.scale_ppm_sigma': expected [x, y, z]");
}

TEST(CalibrationFile, GivenARelativePathInAConfig_ThenItIsFoundFromTheWorkingDirectoryElseBesideTheConfig) {
  const std::string dir = ::testing::TempDir() + "/cal_resolve";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/imu_cal.yaml") << "x";
  EXPECT_EQ(resolve_data_path("imu_cal.yaml", dir + "/kfgins.yaml"),
            (std::filesystem::path(dir) / "imu_cal.yaml").lexically_normal().string());
  EXPECT_EQ(resolve_data_path("/abs/cal.yaml", dir + "/kfgins.yaml"), "/abs/cal.yaml");
  EXPECT_EQ(resolve_data_path("nowhere.yaml", dir + "/kfgins.yaml"), "nowhere.yaml");  // the error names it as given
}

}  // namespace
}  // namespace ldv::calib
