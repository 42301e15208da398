#pragma once
// KF-GINS YAML configuration, read as KF-GINS reads it (same keys, same engineering units), converted
// to SI once here. Optional keys stay optional: no initpos/initvel/initatt means "align from the data".
// ldvnav-specific settings live under an `ldv:` section that KF-GINS ignores.
#include <cmath>
#include <optional>
#include <string>

#include <yaml-cpp/yaml.h>

#include "common/geo/geodetic.hpp"
#include "common/math/rotation.hpp"

namespace ldv {

struct KfGinsImuNoise {
  Vec3 arw_rad_per_sqrt_s = Vec3::Zero();       // yaml: arw [deg/sqrt(h)]
  Vec3 vrw_mps_per_sqrt_s = Vec3::Zero();       // yaml: vrw [m/s/sqrt(h)]
  Vec3 gyro_bias_std_rad_s = Vec3::Zero();      // yaml: gbstd [deg/h]
  Vec3 accel_bias_std_mps2 = Vec3::Zero();      // yaml: abstd [mGal]
  Vec3 gyro_scale_std = Vec3::Zero();           // yaml: gsstd [ppm]
  Vec3 accel_scale_std = Vec3::Zero();          // yaml: asstd [ppm]
  double corr_time_s = 3600.0;                  // yaml: corrtime [h]
};

// KF-GINS models the in-run bias as one Gauss-Markov process (gbstd/abstd, corrtime). A sensor with a
// Gauss-Markov sigma B and a rate random walk K: the single process whose variance after the correlation
// time T matches, B^2 + K^2 T / 2 (what `ldv sim` and `ldv allan --noise-config` both write).
inline double kfgins_single_bias_std(double gm_sigma, double rate_rw_K, double corr_time_s) {
  return std::sqrt(gm_sigma * gm_sigma + rate_rw_K * rate_rw_K * 0.5 * corr_time_s);
}

struct KfGinsConfig {
  std::string config_path;  // the file this came from (for messages)
  std::string imu_path, gnss_path, output_path;
  int imu_data_columns = 7;
  double imu_rate_hz = 200.0;
  double start_time_s = 0.0;
  double end_time_s = -1.0;  // -1: to the end of the IMU file

  std::optional<Geodetic> init_pos;
  std::optional<Vec3> init_vel_n_mps;
  std::optional<Vec3> init_rpy_rad;

  Vec3 init_gyro_bias_rad_s = Vec3::Zero();
  Vec3 init_accel_bias_mps2 = Vec3::Zero();
  Vec3 init_gyro_scale = Vec3::Zero();
  Vec3 init_accel_scale = Vec3::Zero();

  Vec3 init_pos_std_ned_m = Vec3::Constant(1.0);
  Vec3 init_vel_std_n_mps = Vec3::Constant(0.1);
  Vec3 init_att_std_rad = Vec3::Constant(1.0 * kDegToRad);
  std::optional<Vec3> init_gyro_bias_std_rad_s, init_accel_bias_std_mps2, init_gyro_scale_std, init_accel_scale_std;

  KfGinsImuNoise imu_noise;
  Vec3 antenna_lever_b_m = Vec3::Zero();  // yaml: antlever, front-right-down [m]

  YAML::Node ldv;  // the optional `ldv:` extension section, as written
};

// A path named in a configuration file: as given when absolute or present from the working directory, else
// beside the configuration file when there, else as given (so an error names it as the user wrote it).
std::string resolve_data_path(const std::string& path, const std::string& config_path);

// Whether the configuration's `ldv:` section sets `key` (then the user's value wins over what the data say).
bool has_ldv_key(const KfGinsConfig& cfg, const char* key);

// Throws InputError naming the file and key on a missing required key or a value of the wrong type.
// Relative data paths are resolved against the working directory first (as KF-GINS does), then
// against the configuration file's directory.
KfGinsConfig load_kfgins_config(const std::string& path);
void save_kfgins_config(const KfGinsConfig& cfg, const std::string& path);

}  // namespace ldv
