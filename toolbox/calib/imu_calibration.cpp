#include "toolbox/calib/imu_calibration.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <iomanip>
#include <sstream>

#include "common/io/input_error.hpp"

namespace ldv::calib {

Mat3 non_orthogonality_matrix(const Vec3& m) {
  Mat3 n;
  n << 0.0, m.z(), m.y(),  //
      m.z(), 0.0, m.x(),   //
      m.y(), m.x(), 0.0;
  return n;
}

Mat3 TriadCalibration::C_b_s() const {
  // frame_rotation_rad rotates the body axes onto the sensor axes: C_s_b = Rot(theta), so C_b_s = Rot^T.
  return quat_from_rotvec(frame_rotation_rad).toRotationMatrix().transpose();
}

Mat3 TriadCalibration::sensor_matrix() const {
  const Mat3 S = Mat3::Identity() + Mat3(scale.asDiagonal()) + non_orthogonality_matrix(misalignment_rad);
  return S * C_b_s();
}

Vec3 TriadCalibration::correct(const Vec3& measured) const {
  return sensor_matrix().partialPivLu().solve(measured - bias);
}

ImuRates apply_calibration(const ImuCalibration& cal, const ImuRates& raw) {
  return {cal.accel.correct(raw.f_b_mps2), cal.gyro.correct(raw.w_b_rad_s)};
}

ImuIncrement apply_calibration(const ImuCalibration& cal, const ImuIncrement& raw) {
  ImuIncrement out = raw;
  out.dvel_b_mps = cal.accel.sensor_matrix().partialPivLu().solve(raw.dvel_b_mps - cal.accel.bias * raw.dt_s);
  out.dtheta_b_rad = cal.gyro.sensor_matrix().partialPivLu().solve(raw.dtheta_b_rad - cal.gyro.bias * raw.dt_s);
  return out;
}

namespace {

constexpr double kPpm = 1e-6;

Vec3 read_vec3(const YAML::Node& parent, const std::string& key, const std::string& path, bool required,
               double unit = 1.0) {
  const YAML::Node n = parent[key];
  if (!n) {
    if (required) throw InputError(path, 0, "missing key '" + key + "' (a list of 3 numbers)");
    return Vec3::Zero();
  }
  if (!n.IsSequence() || n.size() != 3) throw InputError(path, n.Mark().line + 1, "'" + key + "': expected [x, y, z]");
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    try {
      v[i] = n[i].as<double>() * unit;
    } catch (const YAML::Exception&) {
      throw InputError(path, n.Mark().line + 1, "'" + key + "': element " + std::to_string(i) + " is not a number");
    }
    if (!std::isfinite(v[i])) throw InputError(path, n.Mark().line + 1, "'" + key + "': non-finite value");
  }
  return v;
}

TriadCalibration read_triad(const YAML::Node& node, const std::string& bias_key, const std::string& path) {
  TriadCalibration t;
  t.bias = read_vec3(node, bias_key, path, true);
  t.scale = read_vec3(node, "scale_ppm", path, true, kPpm);
  t.misalignment_rad = read_vec3(node, "misalignment_rad", path, true);
  t.frame_rotation_rad = read_vec3(node, "frame_rotation_rad", path, false);
  t.bias_sigma = read_vec3(node, bias_key + "_sigma", path, false);
  t.scale_sigma = read_vec3(node, "scale_ppm_sigma", path, false, kPpm);
  t.misalignment_sigma_rad = read_vec3(node, "misalignment_rad_sigma", path, false);
  t.frame_rotation_sigma_rad = read_vec3(node, "frame_rotation_rad_sigma", path, false);
  return t;
}

std::string flow(const Vec3& v, double unit = 1.0) {
  std::ostringstream s;
  s << std::setprecision(17) << "[" << v.x() / unit << ", " << v.y() / unit << ", " << v.z() / unit << "]";
  return s.str();
}

void write_triad(std::ostream& out, const char* name, const TriadCalibration& t, const std::string& bias_key) {
  out << name << ":\n";
  out << "  " << bias_key << ": " << flow(t.bias) << "\n";
  out << "  scale_ppm: " << flow(t.scale, kPpm) << "\n";
  out << "  misalignment_rad: " << flow(t.misalignment_rad) << "\n";
  out << "  frame_rotation_rad: " << flow(t.frame_rotation_rad) << "\n";
  out << "  " << bias_key << "_sigma: " << flow(t.bias_sigma) << "\n";
  out << "  scale_ppm_sigma: " << flow(t.scale_sigma, kPpm) << "\n";
  out << "  misalignment_rad_sigma: " << flow(t.misalignment_sigma_rad) << "\n";
  out << "  frame_rotation_rad_sigma: " << flow(t.frame_rotation_sigma_rad) << "\n";
}

}  // namespace

ImuCalibration load_calibration(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(path, 0, "cannot open calibration file");
  } catch (const YAML::Exception& e) {
    throw InputError(path, e.mark.line + 1, "not valid YAML: " + e.msg);
  }
  if (!root.IsMap() || !root["format"] || root["format"].as<std::string>() != "ldv_imu_calibration_v1")
    throw InputError(path, 0, "expected 'format: ldv_imu_calibration_v1'");
  if (!root["accel"] || !root["gyro"]) throw InputError(path, 0, "expected sections 'accel' and 'gyro'");
  ImuCalibration cal;
  cal.accel = read_triad(root["accel"], "bias_mps2", path);
  cal.gyro = read_triad(root["gyro"], "bias_rad_s", path);
  if (root["description"]) cal.description = root["description"].as<std::string>();
  return cal;
}

void save_calibration(const std::string& path, const ImuCalibration& cal) {
  std::ofstream out(path);
  if (!out) throw InputError(path, 0, "cannot open calibration file for writing");
  out << "# ldvnav IMU calibration (toolbox/calib/README.md; model of docs/effects.md):\n"
         "#   f_meas = (I + diag(accel.scale) + N(accel.misalignment)) f_b + accel.bias\n"
         "#   w_meas = (I + diag(gyro.scale) + N(gyro.misalignment)) C_b_g w_b + gyro.bias\n"
         "#   N(m) = [[0, m_z, m_y], [m_z, 0, m_x], [m_y, m_x, 0]]; C_b_g = Rot(gyro.frame_rotation)^T\n"
         "# Measurements are SI after the device's nominal conversion; correct with M^-1 (meas - bias).\n";
  out << "format: ldv_imu_calibration_v1\n";
  std::string quoted;  // YAML double-quoted scalar
  for (char c : cal.description) {
    if (c == '"' || c == '\\') quoted += '\\';
    if (c != '\n') quoted += c;
  }
  out << "description: \"" << quoted << "\"\n";
  write_triad(out, "accel", cal.accel, "bias_mps2");
  write_triad(out, "gyro", cal.gyro, "bias_rad_s");
  if (!out) throw InputError(path, 0, "write failed");
}

}  // namespace ldv::calib
