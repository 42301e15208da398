#include "common/formats/kfgins_config.hpp"

#include <algorithm>

#include <filesystem>
#include <fstream>
#include <vector>

#include "common/config/config_section.hpp"
#include "common/io/input_error.hpp"
#include "common/io/output_file.hpp"
#include "common/io/text_file_lines.hpp"

namespace ldv {
namespace {
namespace fs = std::filesystem;

struct Reader {
  const std::string& file;
  const YAML::Node& root;

  [[noreturn]] void fail(const std::string& key, const YAML::Node& n, const std::string& expected) const {
    const long line = n.IsDefined() ? n.Mark().line + 1 : 0;
    throw InputError(file, line, "key '" + key + "': expected " + expected);
  }
  YAML::Node at(const std::string& key) const {
    // Supports "section.key".
    const auto dot = key.find('.');
    if (dot == std::string::npos) return root[key];
    return root[key.substr(0, dot)][key.substr(dot + 1)];
  }
  bool has(const std::string& key) const {
    const YAML::Node n = at(key);
    return n.IsDefined() && !n.IsNull();
  }
  double number(const std::string& key) const {
    const YAML::Node n = at(key);
    if (!n.IsDefined()) fail(key, n, "a number (key is missing)");
    try {
      return n.as<double>();
    } catch (const YAML::Exception&) {
      fail(key, n, "a number");
    }
  }
  std::string text(const std::string& key) const {
    const YAML::Node n = at(key);
    if (!n.IsDefined() || !n.IsScalar()) fail(key, n, "a path string" + std::string(n.IsDefined() ? "" : " (key is missing)"));
    return n.as<std::string>();
  }
  Vec3 vec3(const std::string& key) const {
    const YAML::Node n = at(key);
    if (!n.IsDefined()) fail(key, n, "a list of 3 numbers (key is missing)");
    if (!n.IsSequence() || n.size() != 3) fail(key, n, "a list of 3 numbers");
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
      try {
        v[i] = n[i].as<double>();
      } catch (const YAML::Exception&) {
        fail(key, n, "a list of 3 numbers (element " + std::to_string(i + 1) + " is not a number)");
      }
    }
    return v;
  }
  std::optional<Vec3> optional_vec3(const std::string& key) const {
    if (!has(key)) return std::nullopt;
    return vec3(key);
  }
};

}  // namespace

std::string resolve_data_path(const std::string& p, const std::string& config_path) {
  if (p.empty() || fs::path(p).is_absolute() || fs::exists(p)) return p;
  const fs::path beside = fs::path(config_path).parent_path() / p;
  if (fs::exists(beside)) return beside.lexically_normal().string();
  return p;
}

namespace {

// Every key a KF-GINS configuration may hold: KF-GINS's own, and ldvnav's `ldv:` section (read by
// estimator/run/run_navigation.cpp options_from_kfgins, toolbox/assess/nav_inputs.cpp and `ldv nav`;
// written by `ldv sim` and `ldv diagnose --write-config`). A key not listed here is a typo: refused with
// the nearest valid key rather than silently ignored.
const std::vector<std::string> kKfGinsKeys = {
    "imupath", "gnsspath", "outputpath", "imudatalen", "imudatarate", "starttime", "endtime", "initpos",
    "initvel", "initatt", "initposstd", "initvelstd", "initattstd", "initgyrbias", "initaccbias", "initgyrscale",
    "initaccscale", "initbgstd", "initbastd", "initsgstd", "initsastd", "imunoise", "antlever", "ldv"};
const std::vector<std::string> kImuNoiseKeys = {"arw", "vrw", "gbstd", "abstd", "gsstd", "asstd", "corrtime"};
const std::vector<std::string> kLdvKeys = {
    // model and filter
    "model", "add", "drop", "cov_period_s", "gate_probability", "kfgins_compatible", "step_confirm_s",
    "adapt_imu_noise", "use_gnss_velocity", "zupt", "history_s", "align_speed_mps", "align_hypotheses",
    "gnss_bias_sigma_m", "gnss_bias_tau_s", "time_offset_s",
    // geoldv51's moving bias per term (SI; estimator/README.md "State layout"), instead of imunoise's one
    // Gauss-Markov: B with its time constant, K, R
    "moving_bias_gyro_gm_rad_s", "moving_bias_gyro_gm_time_s", "moving_bias_gyro_rw_rad_s_sqrt_s",
    "moving_bias_gyro_ramp_rad_s2", "moving_bias_accel_gm_mps2", "moving_bias_accel_gm_time_s",
    "moving_bias_accel_rw_mps2_sqrt_s", "moving_bias_accel_ramp_mps3",
    // the gyros' Allan Q [rad]: a white error of the integrated angle (estimator/options.hpp)
    "gyro_quantization_rad",
    // land-vehicle aids (estimator/options.hpp AidOptions)
    "aids", "vehicle_mounting_deg", "nhc_std_mps", "odometer_std_mps", "odometer_lever_arm_m", "odometer_scale",
    // inputs
    "week", "pos_height_offset_m", "float_std_min_m", "imu_time_shift_s", "imu_latency", "calibration",
    "odopath",  // odometer text file (common/formats/odometer_text.hpp), written by `ldv sim --odometer`
    // written by `ldv sim` (its truth and settings, for the record)
    "simulator", "declared_effects_si", "gnss_latency_s"};

void refuse_unknown_in(const std::string& path, const YAML::Node& map, const std::vector<std::string>& known,
                       const std::string& prefix) {
  if (!map.IsMap()) return;
  for (const auto& kv : map) {
    const std::string key = kv.first.as<std::string>();
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    const std::string near = config::nearest_name(key, known);
    throw InputError(path, kv.first.Mark().line + 1,
                     "unknown key '" + prefix + key + "'" + (near.empty() ? "" : " (did you mean '" + prefix + near + "'?)"));
  }
}

void refuse_unknown_keys(const std::string& path, const YAML::Node& root) {
  refuse_unknown_in(path, root, kKfGinsKeys, "");
  if (root["imunoise"]) refuse_unknown_in(path, root["imunoise"], kImuNoiseKeys, "imunoise.");
  if (root["ldv"]) refuse_unknown_in(path, root["ldv"], kLdvKeys, "ldv.");
}

}  // namespace

bool has_ldv_key(const KfGinsConfig& cfg, const char* key) {
  return cfg.ldv.IsDefined() && cfg.ldv.IsMap() && cfg.ldv[key];
}

KfGinsConfig load_kfgins_config(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::Load(read_small_text_file(path));  // bounded: /dev/zero or a huge file is refused
  } catch (const YAML::BadFile&) {
    throw InputError(path, 0, "cannot open configuration file");
  } catch (const YAML::ParserException& e) {
    throw InputError(path, e.mark.line + 1, "YAML syntax error: " + e.msg);
  }
  if (!root.IsMap()) throw InputError(path, 0, "expected a YAML mapping of KF-GINS keys");
  refuse_unknown_keys(path, root);
  const Reader r{path, root};
  KfGinsConfig c;
  c.config_path = path;
  c.imu_path = resolve_data_path(r.text("imupath"), path);
  c.gnss_path = resolve_data_path(r.text("gnsspath"), path);
  c.output_path = r.has("outputpath") ? resolve_data_path(r.text("outputpath"), path) : ".";
  if (r.has("imudatalen")) c.imu_data_columns = static_cast<int>(r.number("imudatalen"));
  if (r.has("imudatarate")) c.imu_rate_hz = r.number("imudatarate");
  if (c.imu_rate_hz <= 0) r.fail("imudatarate", r.at("imudatarate"), "a positive rate [Hz]");
  if (r.has("starttime")) c.start_time_s = r.number("starttime");
  if (r.has("endtime")) c.end_time_s = r.number("endtime");

  if (auto p = r.optional_vec3("initpos")) c.init_pos = Geodetic{(*p)[0] * kDegToRad, (*p)[1] * kDegToRad, (*p)[2]};
  c.init_vel_n_mps = r.optional_vec3("initvel");
  if (auto a = r.optional_vec3("initatt")) c.init_rpy_rad = Vec3((*a)[0], (*a)[1], wrap_pi((*a)[2] * kDegToRad) * kRadToDeg) * kDegToRad;

  const double deg_per_h = kDegToRad / 3600.0, mgal = 1e-5, ppm = 1e-6;
  if (auto v = r.optional_vec3("initgyrbias")) c.init_gyro_bias_rad_s = *v * deg_per_h;
  if (auto v = r.optional_vec3("initaccbias")) c.init_accel_bias_mps2 = *v * mgal;
  if (auto v = r.optional_vec3("initgyrscale")) c.init_gyro_scale = *v * ppm;
  if (auto v = r.optional_vec3("initaccscale")) c.init_accel_scale = *v * ppm;
  if (auto v = r.optional_vec3("initposstd")) c.init_pos_std_ned_m = *v;
  if (auto v = r.optional_vec3("initvelstd")) c.init_vel_std_n_mps = *v;
  if (auto v = r.optional_vec3("initattstd")) c.init_att_std_rad = *v * kDegToRad;
  if (auto v = r.optional_vec3("initbgstd")) c.init_gyro_bias_std_rad_s = *v * deg_per_h;
  if (auto v = r.optional_vec3("initbastd")) c.init_accel_bias_std_mps2 = *v * mgal;
  if (auto v = r.optional_vec3("initsgstd")) c.init_gyro_scale_std = *v * ppm;
  if (auto v = r.optional_vec3("initsastd")) c.init_accel_scale_std = *v * ppm;

  if (!r.has("imunoise")) throw InputError(path, 0, "key 'imunoise': expected a section with arw, vrw, gbstd, abstd, gsstd, asstd, corrtime");
  auto& n = c.imu_noise;
  n.arw_rad_per_sqrt_s = r.vec3("imunoise.arw") * (kDegToRad / 60.0);
  n.vrw_mps_per_sqrt_s = r.vec3("imunoise.vrw") / 60.0;
  n.gyro_bias_std_rad_s = r.vec3("imunoise.gbstd") * deg_per_h;
  n.accel_bias_std_mps2 = r.vec3("imunoise.abstd") * mgal;
  n.gyro_scale_std = r.has("imunoise.gsstd") ? Vec3(r.vec3("imunoise.gsstd") * ppm) : Vec3(Vec3::Zero());
  n.accel_scale_std = r.has("imunoise.asstd") ? Vec3(r.vec3("imunoise.asstd") * ppm) : Vec3(Vec3::Zero());
  n.corr_time_s = r.number("imunoise.corrtime") * 3600.0;
  if (n.corr_time_s <= 0) r.fail("imunoise.corrtime", r.at("imunoise.corrtime"), "a positive correlation time [h]");
  c.antenna_lever_b_m = r.has("antlever") ? r.vec3("antlever") : Vec3::Zero();
  if (root["ldv"]) c.ldv = root["ldv"];
  return c;
}

void save_kfgins_config(const KfGinsConfig& c, const std::string& path) {
  YAML::Emitter e;
  auto seq = [&](const char* key, const Vec3& v, const char* comment) {
    e << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq << v[0] << v[1] << v[2] << YAML::EndSeq
      << YAML::Comment(comment);
  };
  e.SetDoublePrecision(12);
  e << YAML::BeginMap;
  e << YAML::Key << "imupath" << YAML::Value << c.imu_path;
  e << YAML::Key << "gnsspath" << YAML::Value << c.gnss_path;
  e << YAML::Key << "outputpath" << YAML::Value << c.output_path;
  e << YAML::Key << "imudatalen" << YAML::Value << c.imu_data_columns;
  e << YAML::Key << "imudatarate" << YAML::Value << c.imu_rate_hz << YAML::Comment("[Hz]");
  e << YAML::Key << "starttime" << YAML::Value << c.start_time_s << YAML::Comment("[s of GPS week]");
  e << YAML::Key << "endtime" << YAML::Value << c.end_time_s << YAML::Comment("-1: to the end");
  if (c.init_pos)
    seq("initpos", Vec3(c.init_pos->lat_rad * kRadToDeg, c.init_pos->lon_rad * kRadToDeg, c.init_pos->h_m),
        "lat lon [deg], h [m]");
  if (c.init_vel_n_mps) seq("initvel", *c.init_vel_n_mps, "N E D [m/s]");
  if (c.init_rpy_rad) seq("initatt", *c.init_rpy_rad * kRadToDeg, "roll pitch yaw [deg]");
  const double deg_per_h = kDegToRad / 3600.0;
  seq("initgyrbias", c.init_gyro_bias_rad_s / deg_per_h, "[deg/h]");
  seq("initaccbias", c.init_accel_bias_mps2 / 1e-5, "[mGal]");
  seq("initgyrscale", c.init_gyro_scale / 1e-6, "[ppm]");
  seq("initaccscale", c.init_accel_scale / 1e-6, "[ppm]");
  seq("initposstd", c.init_pos_std_ned_m, "N E D [m]");
  seq("initvelstd", c.init_vel_std_n_mps, "N E D [m/s]");
  seq("initattstd", c.init_att_std_rad * kRadToDeg, "roll pitch yaw [deg]");
  if (c.init_gyro_bias_std_rad_s) seq("initbgstd", *c.init_gyro_bias_std_rad_s / deg_per_h, "[deg/h]");
  if (c.init_accel_bias_std_mps2) seq("initbastd", *c.init_accel_bias_std_mps2 / 1e-5, "[mGal]");
  if (c.init_gyro_scale_std) seq("initsgstd", *c.init_gyro_scale_std / 1e-6, "[ppm]");
  if (c.init_accel_scale_std) seq("initsastd", *c.init_accel_scale_std / 1e-6, "[ppm]");
  e << YAML::Key << "imunoise" << YAML::Value << YAML::BeginMap;
  const auto& n = c.imu_noise;
  seq("arw", n.arw_rad_per_sqrt_s / (kDegToRad / 60.0), "[deg/sqrt(h)]");
  seq("vrw", n.vrw_mps_per_sqrt_s * 60.0, "[m/s/sqrt(h)]");
  seq("gbstd", n.gyro_bias_std_rad_s / deg_per_h, "[deg/h]");
  seq("abstd", n.accel_bias_std_mps2 / 1e-5, "[mGal]");
  seq("gsstd", n.gyro_scale_std / 1e-6, "[ppm]");
  seq("asstd", n.accel_scale_std / 1e-6, "[ppm]");
  e << YAML::Key << "corrtime" << YAML::Value << n.corr_time_s / 3600.0 << YAML::Comment("[h]");
  e << YAML::EndMap;
  seq("antlever", c.antenna_lever_b_m, "front right down [m]");
  if (c.ldv.IsDefined() && !c.ldv.IsNull()) e << YAML::Key << "ldv" << YAML::Value << c.ldv;
  e << YAML::EndMap;
  std::ofstream out(path);
  if (!out) throw InputError(path, 0, "cannot open file for writing");
  out << "# KF-GINS configuration (written by ldvnav; readable by KF-GINS and `ldv nav --kfgins-config`)\n"
      << e.c_str() << "\n";
  close_checked(out, path);
}

}  // namespace ldv
