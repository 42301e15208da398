#include "sim/imu_grade.hpp"

#include <cmath>

#include "common/io/input_error.hpp"

namespace ldv::sim {
namespace {
// Engineering units -> SI, converted once here.
constexpr double kDegPerH = kDegToRad / 3600.0;            // deg/h -> rad/s
constexpr double kDegPerSqrtH = kDegToRad / 60.0;          // deg/sqrt(h) -> rad/sqrt(s)
constexpr double kDegPerHPerSqrtH = kDegPerH / 60.0;       // deg/h/sqrt(h) -> rad/s/sqrt(s)
constexpr double kDegPerHPerH = kDegPerH / 3600.0;         // deg/h/h -> rad/s^2
constexpr double kMg = 9.80665e-3;                         // mg -> m/s^2
constexpr double kMpsPerSqrtH = 1.0 / 60.0;                // m/s/sqrt(h) -> m/s/sqrt(s)
constexpr double kMpsPerHPerSqrtH = 1.0 / 3600.0 / 60.0;   // m/s/h/sqrt(h) -> m/s^2/sqrt(s)
constexpr double kMpsPerHH = 1.0 / 3600.0 / 3600.0;        // m/s/h^2 -> m/s^3
constexpr double kArcsec = kDegToRad / 3600.0;
constexpr double kPpm = 1e-6;

Vec3 c(double v) { return Vec3::Constant(v); }

ImuGrade hg1700() {
  ImuGrade g;
  g.name = "hg1700";
  g.source =
      "Honeywell HG1700-AG58 datasheet (gyro bias 1 deg/h, ARW 0.125 deg/sqrt(h), scale 150 ppm; accel bias 1 mg, "
      "VRW 0.0296 m/s/sqrt(h), scale 300 ppm); in-run B, K, R, Q: typical ring-laser tactical-grade values";
  g.gyro.white_N = c(0.125 * kDegPerSqrtH);
  g.gyro.quantization_Q = c(1.2e-6 / std::sqrt(12.0));  // angle LSB ~1.2e-6 rad
  g.gyro.instability_B = c(0.3 * kDegPerH);
  g.gyro.instability_T_s = c(1800.0);
  g.gyro.rate_rw_K = c(0.05 * kDegPerHPerSqrtH);
  g.gyro.ramp_R = Vec3(0.02, -0.015, 0.01) * kDegPerHPerH;
  g.gyro.turn_on_bias_std = c(1.0 * kDegPerH);
  g.gyro.scale_std = c(150 * kPpm);
  g.accel.white_N = c(0.0296 * kMpsPerSqrtH);
  g.accel.quantization_Q = c(1.9e-5 / std::sqrt(12.0));  // velocity LSB ~1.9e-5 m/s
  g.accel.instability_B = c(0.05 * kMg);
  g.accel.instability_T_s = c(1800.0);
  g.accel.rate_rw_K = c(0.02 * kMpsPerHPerSqrtH);
  g.accel.ramp_R = Vec3(0.01, -0.01, 0.02) * kMpsPerHH;
  g.accel.turn_on_bias_std = c(1.0 * kMg);
  g.accel.scale_std = c(300 * kPpm);
  return g;
}

ImuGrade hg1900() {
  ImuGrade g;
  g.name = "hg1900";
  g.source =
      "Honeywell HG1900 (MEMS gyro, tactical) datasheet-level values: gyro bias 2 deg/h, ARW 0.09 deg/sqrt(h), "
      "scale 150 ppm; accel bias 1 mg, VRW 0.05 m/s/sqrt(h), scale 300 ppm; in-run terms typical for the class";
  g.gyro.white_N = c(0.09 * kDegPerSqrtH);
  g.gyro.quantization_Q = c(1.2e-6 / std::sqrt(12.0));
  g.gyro.instability_B = c(0.6 * kDegPerH);
  g.gyro.instability_T_s = c(1000.0);
  g.gyro.rate_rw_K = c(0.1 * kDegPerHPerSqrtH);
  g.gyro.ramp_R = Vec3(0.05, -0.03, 0.04) * kDegPerHPerH;
  g.gyro.turn_on_bias_std = c(2.0 * kDegPerH);
  g.gyro.scale_std = c(150 * kPpm);
  g.accel.white_N = c(0.05 * kMpsPerSqrtH);
  g.accel.quantization_Q = c(1.9e-5 / std::sqrt(12.0));  // velocity LSB ~1.9e-5 m/s
  g.accel.instability_B = c(0.1 * kMg);
  g.accel.instability_T_s = c(1000.0);
  g.accel.rate_rw_K = c(0.04 * kMpsPerHPerSqrtH);
  g.accel.ramp_R = Vec3(0.02, -0.02, 0.03) * kMpsPerHH;
  g.accel.turn_on_bias_std = c(1.0 * kMg);
  g.accel.scale_std = c(300 * kPpm);
  return g;
}

ImuGrade gx2() {
  ImuGrade g;
  g.name = "3dm-gx2";
  g.source =
      "MicroStrain 3DM-GX2 datasheet-level values (consumer MEMS): gyro in-run bias instability 18 deg/h "
      "(0.005 deg/s), ARW 0.05 deg/sqrt(s) = 3 deg/sqrt(h), turn-on bias 0.2 deg/s, scale 0.5 %; accel bias "
      "10 mg, in-run 0.2 mg, VRW 0.1 m/s/sqrt(h), scale 0.5 %";
  g.gyro.white_N = c(3.0 * kDegPerSqrtH);
  g.gyro.quantization_Q = c(0.1 * kArcsec);  // 16-bit rate ADC integrated over a sample
  g.gyro.instability_B = c(18.0 * kDegPerH);
  g.gyro.instability_T_s = c(300.0);
  g.gyro.rate_rw_K = c(5.0 * kDegPerHPerSqrtH);
  g.gyro.ramp_R = Vec3(2.0, -1.5, 1.0) * kDegPerHPerH;
  g.gyro.turn_on_bias_std = c(0.2 * 3600.0 * kDegPerH);
  g.gyro.scale_std = c(5000 * kPpm);
  g.accel.white_N = c(0.1 * kMpsPerSqrtH);
  g.accel.quantization_Q = c(5e-5);
  g.accel.instability_B = c(0.2 * kMg);
  g.accel.instability_T_s = c(300.0);
  g.accel.rate_rw_K = c(0.3 * kMpsPerHPerSqrtH);
  g.accel.ramp_R = Vec3(0.5, -0.3, 0.4) * kMpsPerHH;
  g.accel.turn_on_bias_std = c(10.0 * kMg);
  g.accel.scale_std = c(5000 * kPpm);
  return g;
}
}  // namespace

std::vector<std::string> imu_grade_names() { return {"perfect", "hg1700", "hg1900", "3dm-gx2"}; }

ImuGrade imu_grade(const std::string& name) {
  if (name == "perfect") {
    ImuGrade g;
    g.name = "perfect";
    g.source = "no sensor errors";
    return g;
  }
  if (name == "hg1700") return hg1700();
  if (name == "hg1900") return hg1900();
  if (name == "3dm-gx2" || name == "3dmgx2" || name == "gx2") return gx2();
  throw InputError("--grade", 0, "unknown IMU grade '" + name + "': expected one of perfect, hg1700, hg1900, 3dm-gx2");
}

}  // namespace ldv::sim
