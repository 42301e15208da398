#include "services/fusion/warm_start.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "common/formats/gnss_solution_checks.hpp"
#include "common/io/atomic_file.hpp"

namespace ldv {

void save_warm_state(const std::string& path, const WarmState& w) {
  std::ostringstream out;
  out.precision(15);
  const Vec3 rpy = w.state.rpy_rad();
  out << "saved_host_time_s: " << w.saved_host_time_s << "\n"
      << "t_s: " << w.state.t_s << "\n"
      << "lat_rad: " << w.state.pos.lat_rad << "\nlon_rad: " << w.state.pos.lon_rad << "\nh_m: " << w.state.pos.h_m
      << "\n"
      << "v_n_mps: [" << w.state.v_n_mps.x() << ", " << w.state.v_n_mps.y() << ", " << w.state.v_n_mps.z() << "]\n"
      << "rpy_rad: [" << rpy.x() << ", " << rpy.y() << ", " << rpy.z() << "]\n"
      << "att_std_rad: [" << w.std.att_rad.x() << ", " << w.std.att_rad.y() << ", " << w.std.att_rad.z() << "]\n"
      << "gyro_bias_rad_s: [" << w.gyro_bias_rad_s.x() << ", " << w.gyro_bias_rad_s.y() << ", " << w.gyro_bias_rad_s.z()
      << "]\n";
  write_file_atomically(path, out.str());  // a read-only state directory must not stop navigation
}

namespace {
// The largest turn-on bias of the gyros we know (consumer MEMS: a few deg/s); 1 rad/s is 57 deg/s.
constexpr double kMaxTurnOnGyroBias_rad_s = 1.0;

// Why the loaded state cannot be one (the key named), "" when it can.
std::string implausible_field(const WarmState& w) {
  const auto three = [](const Vec3& v) {
    char b[96];
    std::snprintf(b, sizeof b, "[%g, %g, %g]", v.x(), v.y(), v.z());
    return std::string(b);
  };
  if (!std::isfinite(w.state.t_s)) return "t_s: not finite";
  const Geodetic& p = w.state.pos;
  if (!std::isfinite(p.lat_rad) || std::abs(p.lat_rad) > kPi / 2) return "lat_rad: not finite in [-pi/2, pi/2]";
  if (!std::isfinite(p.lon_rad) || std::abs(p.lon_rad) > 2 * kPi) return "lon_rad: not finite in [-2 pi, 2 pi]";
  if (!std::isfinite(p.h_m) || p.h_m < gnss::kMinPlausibleHeight_m || p.h_m > gnss::kMaxPlausibleHeight_m)
    return "h_m: not finite within a vehicle's heights";
  if (!w.state.v_n_mps.allFinite() || w.state.v_n_mps.norm() > gnss::kMaxPlausibleSpeed_mps)
    return "v_n_mps: " + three(w.state.v_n_mps) + " not finite below 1000 m/s";
  const Vec3 rpy = w.state.rpy_rad();
  if (!rpy.allFinite() || !w.state.q_b_n.coeffs().allFinite() || std::abs(rpy.y()) > kPi / 2 + 1e-9)
    return "rpy_rad: not finite with a pitch within +-pi/2";
  if (!w.std.att_rad.allFinite() || !(w.std.att_rad.array() > 0.0).all() || !(w.std.att_rad.array() <= kPi).all())
    return "att_std_rad: " + three(w.std.att_rad) + " not in (0, pi]";
  if (!w.gyro_bias_rad_s.allFinite() || w.gyro_bias_rad_s.cwiseAbs().maxCoeff() > kMaxTurnOnGyroBias_rad_s)
    return "gyro_bias_rad_s: " + three(w.gyro_bias_rad_s) + " not finite within a gyro's range";
  return "";
}
}  // namespace

std::optional<WarmState> load_warm_state(const std::string& path, double now_host_s, double max_age_s, std::string* why) {
  const auto refuse = [&](const std::string& reason) -> std::optional<WarmState> {
    if (why) *why = reason;
    return std::nullopt;
  };
  try {
    const YAML::Node y = YAML::LoadFile(path);
    WarmState w;
    w.saved_host_time_s = y["saved_host_time_s"].as<double>();
    if (!std::isfinite(w.saved_host_time_s)) return refuse("saved_host_time_s: not finite");
    if (now_host_s - w.saved_host_time_s > max_age_s) return refuse("saved_host_time_s: older than warm_start_max_age_s");
    if (now_host_s < w.saved_host_time_s - 1.0) return refuse("saved_host_time_s: in the future of the host clock");
    w.state.t_s = y["t_s"].as<double>();
    w.state.pos = {y["lat_rad"].as<double>(), y["lon_rad"].as<double>(), y["h_m"].as<double>()};
    const auto v = y["v_n_mps"].as<std::vector<double>>();
    const auto a = y["rpy_rad"].as<std::vector<double>>();
    const auto s = y["att_std_rad"].as<std::vector<double>>();
    if (v.size() != 3) return refuse("v_n_mps: expected 3 numbers");
    if (a.size() != 3) return refuse("rpy_rad: expected 3 numbers");
    if (s.size() != 3) return refuse("att_std_rad: expected 3 numbers");
    w.state.v_n_mps = Vec3(v[0], v[1], v[2]);
    const Vec3 rpy(a[0], a[1], a[2]);
    if (!rpy.allFinite() || std::abs(rpy.y()) > kPi / 2) return refuse("rpy_rad: not finite with a pitch within +-pi/2");
    w.state.q_b_n = quat_from_euler(rpy);
    w.std.att_rad = Vec3(s[0], s[1], s[2]);
    if (const YAML::Node b = y["gyro_bias_rad_s"]) {
      const auto bias = b.as<std::vector<double>>();
      if (bias.size() != 3) return refuse("gyro_bias_rad_s: expected 3 numbers");
      w.gyro_bias_rad_s = Vec3(bias[0], bias[1], bias[2]);
    }
    if (const std::string bad = implausible_field(w); !bad.empty()) return refuse(bad);
    return w;
  } catch (const std::exception& e) {
    return refuse(std::string("not readable: ") + e.what());
  }
}

}  // namespace ldv
