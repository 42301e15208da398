#include "services/fusion/warm_start.hpp"

#include <sstream>

#include <yaml-cpp/yaml.h>

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

std::optional<WarmState> load_warm_state(const std::string& path, double now_host_s, double max_age_s) {
  try {
    const YAML::Node y = YAML::LoadFile(path);
    WarmState w;
    w.saved_host_time_s = y["saved_host_time_s"].as<double>();
    if (now_host_s - w.saved_host_time_s > max_age_s || now_host_s < w.saved_host_time_s - 1.0) return std::nullopt;
    w.state.t_s = y["t_s"].as<double>();
    w.state.pos = {y["lat_rad"].as<double>(), y["lon_rad"].as<double>(), y["h_m"].as<double>()};
    const auto v = y["v_n_mps"].as<std::vector<double>>();
    const auto a = y["rpy_rad"].as<std::vector<double>>();
    const auto s = y["att_std_rad"].as<std::vector<double>>();
    if (v.size() != 3 || a.size() != 3 || s.size() != 3) return std::nullopt;
    w.state.v_n_mps = Vec3(v[0], v[1], v[2]);
    w.state.q_b_n = quat_from_euler(Vec3(a[0], a[1], a[2]));
    w.std.att_rad = Vec3(s[0], s[1], s[2]);
    if (const YAML::Node b = y["gyro_bias_rad_s"]) {
      const auto bias = b.as<std::vector<double>>();
      if (bias.size() != 3) return std::nullopt;
      w.gyro_bias_rad_s = Vec3(bias[0], bias[1], bias[2]);
    }
    if (!w.gyro_bias_rad_s.allFinite()) return std::nullopt;
    return w;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace ldv
