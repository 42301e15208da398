#pragma once
// A recorded IMU log for calibration, in SI after the device's nominal conversion, read from the formats
// people calibrate with: separate accel/gyro files (`t x y z`, imu_tk style), one CSV with metadata header
// lines (`Fs,100`, `Initialization time,36.5`, then `ax,ay,az,gx,gy,gz`), or KF-GINS increments.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/math/rotation.hpp"

namespace ldv::calib {

struct ImuLog {
  std::vector<double> t_s;
  std::vector<Vec3> f_mps2;   // specific force, sensor axes
  std::vector<Vec3> w_rad_s;  // angular rate, sensor axes (empty when no gyro data)
  double dt_s = 0.0;          // nominal sample interval
  std::optional<double> init_static_s;  // initial static period given by the file header, if any
  std::string source;         // file name(s), for messages
  size_t size() const { return f_mps2.size(); }
  bool has_gyro() const { return !w_rad_s.empty(); }
};

// Nominal conversion of one triad: si = (raw - offset_counts) / counts_per_unit * si_per_unit.
struct TriadUnits {
  double counts_per_unit = 1.0;  // 1 when the file already holds the unit
  double offset_counts = 0.0;    // zero-rate / zero-g output removed before scaling (e.g. 32768)
  double si_per_unit = 1.0;      // m/s^2 per g = 9.80665, rad/s per deg/s = pi/180, ...
  double to_si(double raw) const { return (raw - offset_counts) / counts_per_unit * si_per_unit; }
};

// Parses a unit name: accel "m/s^2" | "g"; gyro "rad/s" | "deg/s" | "deg/h". Throws InputError otherwise.
double accel_si_per_unit(const std::string& unit);
double gyro_si_per_unit(const std::string& unit);

struct ImuLogOptions {
  TriadUnits accel, gyro;
  std::optional<double> rate_hz;  // overrides the time column / header
  // Column names per position for CSV (t, ax, ay, az, gx, gy, gz, or '-' to skip); empty: from the header.
  std::vector<std::string> columns;
};

// `t x y z` files (whitespace or comma); the two files must hold the same time stamps.
ImuLog read_xyz_pair(const std::string& accel_path, const std::string& gyro_path, const ImuLogOptions& opt);
// CSV with optional `key,value` metadata lines and a column-name line before the numbers.
ImuLog read_csv_log(const std::string& path, const ImuLogOptions& opt);
// KF-GINS imu.txt increments, turned into rates (already SI; units options are ignored).
ImuLog read_kfgins_log(const std::string& path);

}  // namespace ldv::calib
