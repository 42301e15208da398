// Bad input: a clear message naming the file and line, never NaN output.
#include <gtest/gtest.h>

#include <fstream>

#include "common/io/input_error.hpp"
#include "real_data.hpp"
#include "common/formats/imu_calibration.hpp"
#include "toolbox/calib/static_calibration.hpp"

namespace ldv::calib {
namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// Expects an InputError whose message contains every fragment.
template <class F>
void expect_input_error(F&& f, std::initializer_list<const char*> fragments) {
  try {
    f();
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    for (const char* s : fragments) EXPECT_NE(std::string(e.what()).find(s), std::string::npos) << e.what();
  }
}

// Issue 13: a device as input is refused at once (it once read forever); a write error is reported, not "written".
TEST(CalibBadInput, DevicesAreRefusedAndAFullDiskIsAnError) {
  expect_input_error([] { read_csv_log("/dev/zero", {}); }, {"/dev/zero", "character device"});
  expect_input_error([] { load_calibration("/dev/zero"); }, {"/dev/zero", "character device"});
  const std::string endless = write_temp("endless.csv", "Fs,100\n" + std::string(100000, '7'));
  expect_input_error([&] { read_csv_log(endless, {}); }, {"endless.csv:2", "line longer than"});
  ImuCalibration cal;
  cal.description = "test";
  expect_input_error([&] { save_calibration("/dev/full", cal); }, {"/dev/full", "failed"});
}

TEST(CalibBadInput, MissingFileIsNamed) {
  expect_input_error([] { read_csv_log("/nonexistent/poses.csv", {}); }, {"/nonexistent/poses.csv", "cannot open"});
  expect_input_error([] { read_xyz_pair("/nonexistent/acc.txt", "", {}); }, {"/nonexistent/acc.txt"});
}

TEST(CalibBadInput, NonNumericAndNanFieldsNameFileAndLine) {
  const std::string text = "Fs,100\nax,ay,az,gx,gy,gz\n1,2,3,4,5,6\n1,2,abc,4,5,6\n";
  const std::string p = write_temp("bad_text.csv", text);
  expect_input_error([&] { read_csv_log(p, {}); }, {"bad_text.csv:4", "column 3", "abc"});
  const std::string q = write_temp("bad_nan.csv", "Fs,100\nax,ay,az,gx,gy,gz\n1,2,3,4,5,6\n1,2,nan,4,5,6\n");
  expect_input_error([&] { read_csv_log(q, {}); }, {"bad_nan.csv:4"});
}

TEST(CalibBadInput, WrongColumnCountAndMismatchedGyroFile) {
  const std::string p = write_temp("bad_cols.csv", "Fs,100\nax,ay,az,gx,gy,gz\n1,2,3,4,5,6\n1,2,3,4,5\n");
  expect_input_error([&] { read_csv_log(p, {}); }, {"bad_cols.csv:4", "expected 6 columns"});
  std::string acc, gyro;
  for (int i = 0; i < 20; ++i) {
    acc += std::to_string(i * 0.01) + " 1 2 3\n";
    gyro += std::to_string(i * 0.01 + (i == 7 ? 0.5 : 0.0)) + " 1 2 3\n";
  }
  const std::string a = write_temp("acc.txt", acc), g = write_temp("gyro.txt", gyro);
  expect_input_error([&] { read_xyz_pair(a, g, {}); }, {"gyro.txt:8", "does not match"});
}

TEST(CalibBadInput, NoColumnNamesAndUnknownUnits) {
  const std::string p = write_temp("no_names.csv", "1,2,3\n4,5,6\n");
  expect_input_error([&] { read_csv_log(p, {}); }, {"no_names.csv:1", "--columns"});
  expect_input_error([] { accel_si_per_unit("furlongs"); }, {"furlongs"});
  expect_input_error([] { gyro_si_per_unit("rpm"); }, {"rpm"});
}

TEST(CalibBadInput, ConstantAccelerometerAndTooShortLogAreRefusedWithAReason) {
  ImuLog log;
  log.dt_s = 0.01;
  log.source = "constant.csv";
  for (int i = 0; i < 5000; ++i) {
    log.t_s.push_back(i * 0.01);
    log.f_mps2.push_back(Vec3(0, 0, 9.8));
  }
  StaticCalibrationOptions opt;
  opt.detector.init_static_s = 10.0;
  expect_input_error([&] { calibrate_static(log, opt); }, {"constant.csv", "constant"});
  opt.detector.init_static_s = 100.0;  // longer than the 50 s log
  expect_input_error([&] { calibrate_static(log, opt); }, {"constant.csv", "does not fit"});
}

TEST(CalibBadInput, StaticLogWithOnePoseGivesRankDeficiencyNotNumbers) {
  ImuLogOptions o;
  o.accel = {16384, 0.0, 9.80665};
  o.gyro = {131, 0.0, kDegToRad};
  const ImuLog log = read_csv_log(testing::shared_data("calib/mpu6050/static_test.csv"), o);
  StaticCalibrationOptions opt;
  opt.detector.init_static_s = 10.0;
  opt.detector.threshold_multiplier = 5.0;
  const StaticCalibrationResult r = calibrate_static(log, opt);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.accel.refusal.find("rank deficient"), std::string::npos) << r.accel.refusal;
  EXPECT_TRUE(r.gravity_residual_after_mps2.empty());
}

}  // namespace
}  // namespace ldv::calib
