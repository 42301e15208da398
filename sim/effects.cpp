#include "sim/effects.hpp"

#include <charconv>
#include <cmath>

#include "common/io/input_error.hpp"
#include "common/io/number_text.hpp"
#include "common/math/rotation.hpp"

namespace ldv::sim {
namespace {
constexpr double kGravity_mps2 = 9.80665;
constexpr double kDegPerHour_rad_s = kDegToRad / 3600.0;
constexpr double kMilliG_mps2 = 1e-3 * kGravity_mps2;
constexpr double kArcsec_rad = kDegToRad / 3600.0;
constexpr double kMgal = 1e-5;

std::vector<double> rep(double v, int n) { return std::vector<double>(n, v); }
}  // namespace

const std::vector<EffectInfo>& effect_table() {
  static const std::vector<EffectInfo> table = {
      {"gyro_bias",
       {3},
       {"deg/h", "deg/h", "deg/h"},
       rep(kDegPerHour_rad_s, 3),
       {5.0, -3.0, 8.0},
       "constant gyro bias x y z",
       rep(36000.0, 3)},
      {"accel_bias",
       {3},
       {"mg", "mg", "mg"},
       rep(kMilliG_mps2, 3),
       {2.0, -1.5, 3.0},
       "constant accelerometer bias x y z",
       rep(1000.0, 3)},
      {"gyro_scale",
       {3},
       {"ppm", "ppm", "ppm"},
       rep(1e-6, 3),
       {300.0, -200.0, 500.0},
       "gyro scale-factor error",
       rep(1e5, 3)},
      {"accel_scale",
       {3},
       {"ppm", "ppm", "ppm"},
       rep(1e-6, 3),
       {300.0, -200.0, 500.0},
       "accelerometer scale-factor error",
       rep(1e5, 3)},
      {"gyro_misalignment",
       {3},
       {"arcsec", "arcsec", "arcsec"},
       rep(kArcsec_rad, 3),
       {100.0, -60.0, 80.0},
       "gyro non-orthogonality m_x m_y m_z (symmetric N(m))",
       rep(36000.0, 3)},
      {"accel_misalignment",
       {3},
       {"arcsec", "arcsec", "arcsec"},
       rep(kArcsec_rad, 3),
       {100.0, -60.0, 80.0},
       "accelerometer non-orthogonality m_x m_y m_z (symmetric N(m))",
       rep(36000.0, 3)},
      {"g_sensitivity",
       {3},
       {"deg/h/g", "deg/h/g", "deg/h/g"},
       rep(kDegPerHour_rad_s / kGravity_mps2, 3),
       {2.0, -1.0, 1.5},
       "gyro bias per specific force on the same axis",
       rep(3600.0, 3)},
      {"gyro_nonlinear_scale",
       {3},
       {"ppm/(deg/s)", "ppm/(deg/s)", "ppm/(deg/s)"},
       rep(1e-6 / kDegToRad, 3),
       {5.0, -3.0, 4.0},
       "quadratic gyro scale: w_meas += k w^2",
       rep(1e4, 3)},
      {"accel_nonlinear_scale",
       {3},
       {"ug/g^2", "ug/g^2", "ug/g^2"},
       rep(1e-6 / kGravity_mps2, 3),
       {50.0, -30.0, 40.0},
       "quadratic accelerometer scale: f_meas += k f^2",
       rep(1e5, 3)},
      {"lever_arm",
       {3},
       {"m", "m", "m"},
       rep(1.0, 3),
       {0.5, -0.3, -1.2},
       "antenna minus IMU, body front-right-down",
       rep(100.0, 3)},
      {"time_offset", {1}, {"s"}, {1.0}, {0.05}, "GNSS time tag minus IMU time", {10.0}},
      {"gravity_anomaly",
       {3, 4},
       {"mGal", "mGal", "mGal", "s"},
       {kMgal, kMgal, kMgal, 1.0},
       {20.0, 20.0, 30.0, 300.0},
       "true minus normal gravity, NED; 3 values: constant; 4 values or default: Gauss-Markov sigmas and time "
       "constant",
       {1000.0, 1000.0, 1000.0, 1e7}},
      {"gyro_moving_bias",
       {5},
       {"deg/h", "deg/h", "s", "deg/h/sqrt(h)", "deg/h/h"},
       {kDegPerHour_rad_s, kDegPerHour_rad_s, 1.0, kDegPerHour_rad_s / 60.0, kDegPerHour_rad_s / 3600.0},
       {0.5, 0.3, 600.0, 0.1, 0.05},
       "per axis: constant, Gauss-Markov sigma B, its time constant, rate random walk K, ramp R",
       {36000.0, 36000.0, 1e7, 36000.0, 36000.0}},
      {"accel_moving_bias",
       {5},
       {"mg", "mg", "s", "m/s/h/sqrt(h)", "m/s/h^2"},
       {kMilliG_mps2, kMilliG_mps2, 1.0, 1.0 / 3600.0 / 60.0, 1.0 / 3600.0 / 3600.0},
       {0.2, 0.05, 600.0, 0.02, 0.02},
       "per axis: constant, Gauss-Markov sigma B, its time constant, rate random walk K, ramp R",
       {1000.0, 1000.0, 1e7, 1e4, 1e4}},
      {"odometer_scale", {1}, {"%"}, {0.01}, {0.5}, "odometer scale-factor error: speed x (1 + s)", {50.0}},
  };
  return table;
}

const EffectInfo* find_effect(const std::string& name) {
  for (const auto& e : effect_table())
    if (e.name == name) return &e;
  return nullptr;
}

std::vector<EffectValue> parse_effect(const std::string& spec, const std::string& origin) {
  const auto eq = spec.find('=');
  const std::string name = spec.substr(0, eq);
  if (name == "moving_bias") {
    if (eq != std::string::npos)
      throw InputError(origin, 0,
                       "effect 'moving_bias' takes no values; give gyro_moving_bias=... and accel_moving_bias=...");
    auto g = parse_effect("gyro_moving_bias", origin);
    auto a = parse_effect("accel_moving_bias", origin);
    g.push_back(a.front());
    return g;
  }
  const EffectInfo* info = find_effect(name);
  if (!info) {
    std::string names;
    for (const auto& e : effect_table()) names += (names.empty() ? "" : ", ") + e.name;
    throw InputError(origin, 0, "unknown effect '" + name + "': expected one of " + names + ", moving_bias");
  }
  EffectValue v;
  v.name = name;
  if (eq == std::string::npos) {
    v.engineering = info->defaults;
    v.defaulted = true;
  } else {
    const std::string list = spec.substr(eq + 1);
    size_t pos = 0;
    while (pos <= list.size()) {
      const size_t comma = std::min(list.find(',', pos), list.size());
      const std::string item = list.substr(pos, comma - pos);
      double x = 0;
      const char* b = item.data();
      const char* e = b + item.size();
      if (b != e && *b == '+') ++b;
      auto [ptr, ec] = std::from_chars(b, e, x);
      if (item.empty() || ec != std::errc() || ptr != e || !std::isfinite(x))
        throw InputError(origin, 0,
                         "effect '" + name + "': value " + std::to_string(v.engineering.size() + 1) + " '" + item +
                             "' is not a number");
      v.engineering.push_back(x);
      pos = comma + 1;
    }
  }
  bool count_ok = false;
  std::string counts;
  for (int c : info->counts) {
    count_ok |= static_cast<int>(v.engineering.size()) == c;
    counts += (counts.empty() ? "" : " or ") + std::to_string(c);
  }
  if (!count_ok) {
    std::string units;
    for (const auto& u : info->units) units += (units.empty() ? "" : ",") + u;
    throw InputError(origin, 0,
                     "effect '" + name + "': expected " + counts + " comma-separated values [" + units + "], found " +
                         std::to_string(v.engineering.size()));
  }
  for (size_t i = 0; i < v.engineering.size() && i < info->max_abs.size(); ++i)
    if (std::abs(v.engineering[i]) > info->max_abs[i])
      throw InputError(origin, 0,
                       "effect '" + name + "': value " + std::to_string(i + 1) + " (" +
                           six_significant(v.engineering[i]) + " " + info->units[i] +
                           ") is beyond what a physical sensor or installation shows; expected |value| <= " +
                           six_significant(info->max_abs[i]) + " " + info->units[i]);
  for (size_t i = 0; i < v.engineering.size(); ++i) v.si.push_back(v.engineering[i] * info->si_per_unit[i]);
  if (name == "gravity_anomaly" && v.si.size() == 4 && v.si[3] <= 0)
    throw InputError(origin, 0, "effect 'gravity_anomaly': the time constant (4th value) must be positive [s]");
  if (name.find("moving_bias") != std::string::npos && v.si[2] <= 0)
    throw InputError(origin, 0,
                     "effect '" + name + "': the Gauss-Markov time constant (3rd value) must be positive [s]");
  return {v};
}

}  // namespace ldv::sim
