#include "common/formats/imu_calibration.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include "common/io/input_error.hpp"
#include "common/io/output_file.hpp"
#include "common/io/text_file_lines.hpp"

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

// Far outside any real sensor's calibration (ldv calib static's physical ranges are 20 % and 0.2 rad): a
// value past these is a unit mistake (a fraction written as ppm, degrees as radians) or a broken solve.
constexpr double kMaxScale = 0.5, kMaxAngleRad = 0.5;
constexpr double kNoLimit = std::numeric_limits<double>::infinity();

struct Vec3Key {
  std::string key;
  bool required = false;
  double unit = 1.0;          // file value * unit = SI
  double max_abs = kNoLimit;  // SI
  bool sigma = false;         // must be >= 0
};

Vec3 read_vec3(const YAML::Node& parent, const std::string& section, const Vec3Key& k, const std::string& path) {
  const std::string name = section + "." + k.key;
  const YAML::Node n = parent[k.key];
  if (!n) {
    if (k.required) throw InputError(path, 0, "missing key '" + name + "' (a list of 3 numbers)");
    return Vec3::Zero();
  }
  const long line = n.Mark().line + 1;
  if (!n.IsSequence() || n.size() != 3) throw InputError(path, line, "'" + name + "': expected [x, y, z]");
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    try {
      v[i] = n[i].as<double>() * k.unit;
    } catch (const YAML::Exception&) {
      throw InputError(path, line, "'" + name + "': element " + std::to_string(i + 1) + " is not a number");
    }
    if (!std::isfinite(v[i])) throw InputError(path, line, "'" + name + "': non-finite value");
    if (k.sigma && v[i] < 0) throw InputError(path, line, "'" + name + "': a sigma cannot be negative");
    if (std::abs(v[i]) > k.max_abs) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "element %d is %g, beyond any sensor's calibration (limit +-%g): wrong unit?", i + 1,
                    v[i] / k.unit, k.max_abs / k.unit);
      throw InputError(path, line, "'" + name + "': " + msg);
    }
  }
  return v;
}

TriadCalibration read_triad(const YAML::Node& node, const std::string& section, const std::string& bias_key,
                            const std::string& path) {
  if (!node.IsMap()) throw InputError(path, node.Mark().line + 1, "'" + section + "': expected a section of keys");
  const auto read = [&](const Vec3Key& k) { return read_vec3(node, section, k, path); };
  TriadCalibration t;
  t.bias = read({bias_key, true});
  t.scale = read({"scale_ppm", true, kPpm, kMaxScale});
  t.misalignment_rad = read({"misalignment_rad", true, 1.0, kMaxAngleRad});
  t.frame_rotation_rad = read({"frame_rotation_rad", false, 1.0, kMaxAngleRad});
  t.bias_sigma = read({bias_key + "_sigma", false, 1.0, kNoLimit, true});
  t.scale_sigma = read({"scale_ppm_sigma", false, kPpm, kNoLimit, true});
  t.misalignment_sigma_rad = read({"misalignment_rad_sigma", false, 1.0, kNoLimit, true});
  t.frame_rotation_sigma_rad = read({"frame_rotation_rad_sigma", false, 1.0, kNoLimit, true});
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
    root = YAML::Load(read_small_text_file(path));  // bounded: /dev/zero or a huge file is refused
  } catch (const YAML::BadFile&) {
    throw InputError(path, 0, "cannot open calibration file");
  } catch (const YAML::Exception& e) {
    throw InputError(path, e.mark.line + 1, "not valid YAML: " + e.msg);
  }
  if (!root.IsMap() || !root["format"] || !root["format"].IsScalar() ||
      root["format"].as<std::string>() != "ldv_imu_calibration_v1")
    throw InputError(path, 0, "key 'format': expected 'format: ldv_imu_calibration_v1'");
  if (!root["accel"] || !root["gyro"]) throw InputError(path, 0, "expected sections 'accel' and 'gyro'");
  ImuCalibration cal;
  cal.accel = read_triad(root["accel"], "accel", "bias_mps2", path);
  cal.gyro = read_triad(root["gyro"], "gyro", "bias_rad_s", path);
  if (const YAML::Node d = root["description"]) {
    if (!d.IsScalar()) throw InputError(path, d.Mark().line + 1, "'description': expected one line of text");
    cal.description = d.as<std::string>();
  }
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
  close_checked(out, path);  // a full disk shows at the flush, not at the << above
}


}  // namespace ldv::calib
