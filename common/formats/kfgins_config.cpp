#include "common/formats/kfgins_config.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

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
  // A finite number in [lo, hi] (unit: how the user writes it, for the message).
  double number(const std::string& key, double lo = -1e300, double hi = 1e300, const char* unit = "") const {
    const YAML::Node n = at(key);
    if (!n.IsDefined()) fail(key, n, "a number (key is missing)");
    double v = 0.0;
    try {
      if (!n.IsScalar()) throw YAML::BadConversion(n.Mark());
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      fail(key, n, "a number" + range_text(lo, hi, unit) + found(n));
    }
    if (!std::isfinite(v) || v < lo || v > hi) fail(key, n, "a finite number" + range_text(lo, hi, unit) + found(n));
    return v;
  }
  static std::string range_text(double lo, double hi, const char* unit) {
    if (lo <= -1e300 && hi >= 1e300) return "";
    char b[96];
    std::snprintf(b, sizeof b, " in [%g, %g]%s%s", lo, hi, *unit ? " " : "", unit);
    return b;
  }
  static std::string found(const YAML::Node& n) {
    return ", found '" + (n.IsScalar() ? n.Scalar() : std::string(n.IsSequence() ? "a list" : "a map")) + "'";
  }
  std::string text(const std::string& key) const {
    const YAML::Node n = at(key);
    if (!n.IsDefined() || !n.IsScalar()) fail(key, n, "a path string" + std::string(n.IsDefined() ? "" : " (key is missing)"));
    // A NUL would cut the path short where the C library opens it ("a\0b" opened "a").
    if (n.Scalar().find('\0') != std::string::npos) fail(key, n, "a path string without a NUL character");
    return n.as<std::string>();
  }
  // Three finite numbers, element i in [lo[i], hi[i]].
  Vec3 vec3(const std::string& key, const Vec3& lo = Vec3::Constant(-1e300), const Vec3& hi = Vec3::Constant(1e300),
            const char* unit = "") const {
    const YAML::Node n = at(key);
    if (!n.IsDefined()) fail(key, n, "a list of 3 numbers (key is missing)");
    if (!n.IsSequence() || n.size() != 3) fail(key, n, "a list of 3 numbers");
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
      const std::string element = " (element " + std::to_string(i + 1) + " is '" + (n[i].IsScalar() ? n[i].Scalar() : "?") + "')";
      try {
        if (!n[i].IsScalar()) throw YAML::BadConversion(n[i].Mark());
        v[i] = n[i].as<double>();
      } catch (const YAML::Exception&) {
        fail(key, n, "a list of 3 numbers" + element);
      }
      if (!std::isfinite(v[i]) || v[i] < lo[i] || v[i] > hi[i])
        fail(key, n, "a list of 3 finite numbers, element " + std::to_string(i + 1) + range_text(lo[i], hi[i], unit) +
                         element);
    }
    return v;
  }
  Vec3 vec3(const std::string& key, double lo, double hi, const char* unit) const {
    return vec3(key, Vec3::Constant(lo), Vec3::Constant(hi), unit);
  }
  std::optional<Vec3> optional_vec3(const std::string& key, double lo = -1e300, double hi = 1e300,
                                    const char* unit = "") const {
    if (!has(key)) return std::nullopt;
    return vec3(key, lo, hi, unit);
  }
  std::optional<Vec3> optional_vec3(const std::string& key, const Vec3& lo, const Vec3& hi, const char* unit) const {
    if (!has(key)) return std::nullopt;
    return vec3(key, lo, hi, unit);
  }
};

}  // namespace

std::string resolve_data_path(const std::string& p, const std::string& config_path) {
  // Without throwing: a path the system cannot even look up (too long, a NUL) stays as given, and opening it
  // names it (a fuzz finding: "filesystem error: status: File name too long" named no file).
  std::error_code ec;
  if (p.empty() || fs::path(p).is_absolute() || fs::exists(p, ec)) return p;
  const fs::path beside = fs::path(config_path).parent_path() / p;
  if (fs::exists(beside, ec)) return beside.lexically_normal().string();
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
    "adapt_imu_noise", "split_noise_adaptation", "use_gnss_velocity", "zupt", "history_s", "align_speed_mps",
    "align_hypotheses", "gnss_bias_sigma_m", "gnss_bias_tau_s", "time_offset_s", "priors",
    // the stated GNSS position variance times this, per solution quality [fixed, float, other] (estimator/options.hpp)
    "gnss_variance_scale",
    // geoldv51's moving bias per term (SI; estimator/README.md "State layout"), instead of imunoise's one
    // Gauss-Markov: B with its time constant, K, R
    "moving_bias_gyro_gm_rad_s", "moving_bias_gyro_gm_time_s", "moving_bias_gyro_rw_rad_s_sqrt_s",
    "moving_bias_gyro_ramp_rad_s2", "moving_bias_accel_gm_mps2", "moving_bias_accel_gm_time_s",
    "moving_bias_accel_rw_mps2_sqrt_s", "moving_bias_accel_ramp_mps3",
    // the gyros' Allan Q [rad]: a white error of the integrated angle (estimator/options.hpp)
    "gyro_quantization_rad",
    // the 1-sigma of the IMU time tags about the sampling instants [s] (estimator/options.hpp)
    "imu_stamp_jitter_s",
    // land-vehicle aids (estimator/options.hpp AidOptions)
    "aids", "vehicle_mounting_deg", "nhc_std_mps", "odometer_std_mps", "odometer_lever_arm_m", "odometer_scale",
    // inputs
    "week", "pos_height_offset_m", "float_std_min_m", "imu_time_shift_s", "imu_latency", "calibration",
    "odopath",  // odometer text file (common/formats/odometer_text.hpp), written by `ldv sim --odometer`
    // a user's own tables instead of imupath / gnsspath (input/tables/imu_table.hpp, gnss_table.hpp)
    "imu_table", "gnss_table",
    // written by `ldv sim` (its truth and settings, for the record)
    "simulator", "declared_effects_si", "gnss_latency_s"};

// The numbers of the `ldv:` section, checked at load so a NaN or an absurd value is refused naming the user's
// key (it reached the estimator as an error about alignment or the initial state, or silently unused every fix).
// Lists (vectors, per-axis values) take the range per element. Keys not here are text, flags or lists of names.
struct LdvNumberKey {
  const char* key;
  double lo, hi;
  const char* unit;
};
const LdvNumberKey kLdvNumbers[] = {
    {"cov_period_s", 0.0, 3600.0, "s"},
    {"gate_probability", 0.5, 1.0 - 1e-12, ""},
    {"step_confirm_s", 0.0, 3600.0, "s"},
    {"history_s", 0.0, 600.0, "s"},
    {"align_speed_mps", 0.0, 1000.0, "m/s"},
    {"align_hypotheses", 1.0, 360.0, ""},
    {"gnss_bias_sigma_m", 0.0, 1e4, "m"},
    {"gnss_bias_tau_s", 1e-3, 1e9, "s"},
    {"time_offset_s", -10.0, 10.0, "s"},
    {"gnss_variance_scale", 1e-4, 1e6, "(a factor on the variance)"},
    {"moving_bias_gyro_gm_rad_s", 0.0, 100.0, "rad/s"},
    {"moving_bias_gyro_gm_time_s", 1e-3, 1e9, "s"},
    {"moving_bias_gyro_rw_rad_s_sqrt_s", 0.0, 100.0, "rad/s/sqrt(s)"},
    {"moving_bias_gyro_ramp_rad_s2", 0.0, 100.0, "rad/s^2"},
    {"moving_bias_accel_gm_mps2", 0.0, 2000.0, "m/s^2"},
    {"moving_bias_accel_gm_time_s", 1e-3, 1e9, "s"},
    {"moving_bias_accel_rw_mps2_sqrt_s", 0.0, 2000.0, "m/s^2/sqrt(s)"},
    {"moving_bias_accel_ramp_mps3", 0.0, 2000.0, "m/s^3"},
    {"gyro_quantization_rad", 0.0, 0.1, "rad"},
    {"imu_stamp_jitter_s", 0.0, 1.0, "s"},
    {"vehicle_mounting_deg", -360.0, 360.0, "deg"},
    {"nhc_std_mps", 0.0, 100.0, "m/s"},
    {"odometer_std_mps", 0.0, 100.0, "m/s"},
    {"odometer_lever_arm_m", -100.0, 100.0, "m"},
    {"odometer_scale", -0.9, 10.0, ""},
    {"week", 1042.0, 8191.0, "(a GPS week)"},
    {"pos_height_offset_m", -1e4, 1e4, "m"},
    {"float_std_min_m", 0.0, 1e4, "m"},
    {"imu_time_shift_s", -10.0, 10.0, "s"},
    {"gnss_latency_s", 0.0, 10.0, "s"},
};

void check_ldv_numbers(const std::string& path, const YAML::Node& ldv) {
  if (!ldv || !ldv.IsMap()) return;
  for (const LdvNumberKey& k : kLdvNumbers) {
    const YAML::Node n = ldv[k.key];
    if (!n || n.IsNull()) continue;
    const auto refuse = [&](const YAML::Node& at, const std::string& found) {
      char range[160];
      std::snprintf(range, sizeof range, "a finite number in [%g, %g]%s%s", k.lo, k.hi, *k.unit ? " " : "", k.unit);
      throw InputError(path, at.Mark().line + 1,
                       std::string("key 'ldv.") + k.key + "': expected " + range +
                           (n.IsSequence() ? " (or a list of them)" : "") + ", found '" + found + "'");
    };
    const auto check = [&](const YAML::Node& v) {
      if (!v.IsScalar()) refuse(v, "a list or map");
      double x = 0.0;
      try {
        x = v.as<double>();
      } catch (const YAML::Exception&) {
        refuse(v, v.Scalar());
      }
      if (!std::isfinite(x) || x < k.lo || x > k.hi) refuse(v, v.Scalar());
    };
    if (n.IsSequence())
      for (const YAML::Node& v : n) check(v);
    else
      check(n);
  }
}

void refuse_unknown_in(const std::string& path, const YAML::Node& map, const std::vector<std::string>& known,
                       const std::string& prefix) {
  if (!map.IsMap()) return;
  for (const auto& kv : map) {
    // A key is a name: a list or a map in a key's place (a fuzz finding: yaml-cpp's "bad conversion", no file)
    if (!kv.first.IsScalar())
      throw InputError(path, kv.first.Mark().line + 1,
                       "expected a key name" + (prefix.empty() ? std::string() : " in '" + prefix + "'") + ", found " +
                           (kv.first.IsSequence() ? "a list" : "a map"));
    const std::string key = kv.first.Scalar();
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
  if (const auto d = config::find_duplicate_key(root)) throw InputError(path, d->line, d->describe());
  for (const char* section : {"imunoise", "ldv"})
    if (const YAML::Node n = root[section]; n && !n.IsNull() && !n.IsMap())
      throw InputError(path, n.Mark().line + 1,
                       std::string("key '") + section + "': expected a section of keys (a map), found " +
                           (n.IsScalar() ? "'" + n.Scalar() + "'" : std::string("a list")));
  refuse_unknown_keys(path, root);
  check_ldv_numbers(path, root["ldv"]);
  const Reader r{path, root};
  KfGinsConfig c;
  c.config_path = path;
  // A table described under ldv: (input/tables/) stands for the file; its reader names it.
  const auto table = [&](const char* key) { return root["ldv"] && root["ldv"].IsMap() && root["ldv"][key]; };
  if (!(table("imu_table") && !r.has("imupath"))) c.imu_path = resolve_data_path(r.text("imupath"), path);
  if (!(table("gnss_table") && !r.has("gnsspath"))) c.gnss_path = resolve_data_path(r.text("gnsspath"), path);
  c.output_path = r.has("outputpath") ? resolve_data_path(r.text("outputpath"), path) : ".";
  if (r.has("imudatalen")) c.imu_data_columns = static_cast<int>(r.number("imudatalen", 7, 64, "columns"));
  if (r.has("imudatarate")) c.imu_rate_hz = r.number("imudatarate", 1e-3, 1e5, "Hz");
  if (c.imu_rate_hz <= 0) r.fail("imudatarate", r.at("imudatarate"), "a positive rate [Hz]");
  // Seconds of week, going on past 604800 after a rollover (KF-GINS); endtime -1: to the end.
  constexpr double kMaxTime_s = 1e10;
  if (r.has("starttime")) c.start_time_s = r.number("starttime", 0.0, kMaxTime_s, "s");
  if (r.has("endtime")) c.end_time_s = r.number("endtime", -1.0, kMaxTime_s, "s");

  if (auto p = r.optional_vec3("initpos", Vec3(-90, -360, -1000), Vec3(90, 360, 100000), "(deg, deg, m)"))
    c.init_pos = Geodetic{(*p)[0] * kDegToRad, wrap_pi((*p)[1] * kDegToRad), (*p)[2]};
  c.init_vel_n_mps = r.optional_vec3("initvel", -1000, 1000, "m/s");
  if (auto a = r.optional_vec3("initatt", Vec3(-180, -90, -360), Vec3(180, 90, 360), "deg"))
    c.init_rpy_rad = Vec3((*a)[0], (*a)[1], wrap_pi((*a)[2] * kDegToRad) * kRadToDeg) * kDegToRad;

  const double deg_per_h = kDegToRad / 3600.0, mgal = 1e-5, ppm = 1e-6;
  // Beyond these no sensor measures anything: a gyro bias of 100 rad/s, an accelerometer bias of 2000 m/s^2, a
  // scale error of 100 %, a noise density that hides a full turn in a second.
  constexpr double kMaxGyroBias_deg_h = 2.0e7, kMaxAccelBias_mgal = 2.0e8, kMaxScale_ppm = 1e6;
  if (auto v = r.optional_vec3("initgyrbias", -kMaxGyroBias_deg_h, kMaxGyroBias_deg_h, "deg/h"))
    c.init_gyro_bias_rad_s = *v * deg_per_h;
  if (auto v = r.optional_vec3("initaccbias", -kMaxAccelBias_mgal, kMaxAccelBias_mgal, "mGal"))
    c.init_accel_bias_mps2 = *v * mgal;
  if (auto v = r.optional_vec3("initgyrscale", -kMaxScale_ppm, kMaxScale_ppm, "ppm")) c.init_gyro_scale = *v * ppm;
  if (auto v = r.optional_vec3("initaccscale", -kMaxScale_ppm, kMaxScale_ppm, "ppm")) c.init_accel_scale = *v * ppm;
  if (auto v = r.optional_vec3("initposstd", 0, 1e7, "m")) c.init_pos_std_ned_m = *v;
  if (auto v = r.optional_vec3("initvelstd", 0, 1000, "m/s")) c.init_vel_std_n_mps = *v;
  if (auto v = r.optional_vec3("initattstd", 0, 180, "deg")) c.init_att_std_rad = *v * kDegToRad;
  if (auto v = r.optional_vec3("initbgstd", 0, kMaxGyroBias_deg_h, "deg/h")) c.init_gyro_bias_std_rad_s = *v * deg_per_h;
  if (auto v = r.optional_vec3("initbastd", 0, kMaxAccelBias_mgal, "mGal")) c.init_accel_bias_std_mps2 = *v * mgal;
  if (auto v = r.optional_vec3("initsgstd", 0, kMaxScale_ppm, "ppm")) c.init_gyro_scale_std = *v * ppm;
  if (auto v = r.optional_vec3("initsastd", 0, kMaxScale_ppm, "ppm")) c.init_accel_scale_std = *v * ppm;

  if (!r.has("imunoise")) throw InputError(path, 0, "key 'imunoise': expected a section with arw, vrw, gbstd, abstd, gsstd, asstd, corrtime");
  auto& n = c.imu_noise;
  n.arw_rad_per_sqrt_s = r.vec3("imunoise.arw", 0, 1e5, "deg/sqrt(h)") * (kDegToRad / 60.0);
  n.vrw_mps_per_sqrt_s = r.vec3("imunoise.vrw", 0, 1e5, "m/s/sqrt(h)") / 60.0;
  n.gyro_bias_std_rad_s = r.vec3("imunoise.gbstd", 0, kMaxGyroBias_deg_h, "deg/h") * deg_per_h;
  n.accel_bias_std_mps2 = r.vec3("imunoise.abstd", 0, kMaxAccelBias_mgal, "mGal") * mgal;
  n.gyro_scale_std = r.has("imunoise.gsstd") ? Vec3(r.vec3("imunoise.gsstd", 0, kMaxScale_ppm, "ppm") * ppm)
                                              : Vec3(Vec3::Zero());
  n.accel_scale_std = r.has("imunoise.asstd") ? Vec3(r.vec3("imunoise.asstd", 0, kMaxScale_ppm, "ppm") * ppm)
                                               : Vec3(Vec3::Zero());
  n.corr_time_s = r.number("imunoise.corrtime", 0, 1e6, "h") * 3600.0;
  if (n.corr_time_s <= 0) r.fail("imunoise.corrtime", r.at("imunoise.corrtime"), "a positive correlation time [h]");
  c.antenna_lever_b_m = r.has("antlever") ? r.vec3("antlever", -100, 100, "m") : Vec3::Zero();
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
