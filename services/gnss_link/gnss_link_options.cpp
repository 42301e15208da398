#include "services/gnss_link/gnss_link_options.hpp"

#include <stdexcept>

#include <yaml-cpp/yaml.h>

namespace ldv::gnss {

GnssLinkOptions load_gnss_link_options(const std::string& path) {
  GnssLinkOptions o;
  if (path.empty()) return o;
  const YAML::Node y = YAML::LoadFile(path);
  if (y["bus_url"]) o.bus_url = y["bus_url"].as<std::string>();
  o.input = io::byte_source_options_from_yaml(y["input"], path);
  if (y["protocol"]) {
    const std::string name = y["protocol"].as<std::string>();
    const auto p = link_protocol_from_name(name);
    if (!p) throw std::runtime_error(path + ": protocol must be nmea, rtklib, ubx or auto, not '" + name + "'");
    o.decoder.protocol = *p;
  }
  if (y["gps_minus_utc_s"]) {
    o.decoder.nmea.gps_minus_utc_s = y["gps_minus_utc_s"].as<double>();
    o.decoder.rtklib.gps_minus_utc_s = o.decoder.nmea.gps_minus_utc_s;
  }
  if (const auto n = y["nmea"]) {
    if (n["default_std_m"]) {
      const auto v = n["default_std_m"].as<std::vector<double>>();
      if (v.size() != 6) throw std::runtime_error(path + ": nmea.default_std_m needs 6 values (fixed float sbas dgps single ppp)");
      for (int i = 0; i < 6; ++i) o.decoder.nmea.default_std_m[i] = v[i];
    }
    if (n["horizontal_velocity_std_mps"]) o.decoder.nmea.horizontal_velocity_std_mps = n["horizontal_velocity_std_mps"].as<double>();
    if (n["quiet_flush_s"]) o.quiet_flush_s = n["quiet_flush_s"].as<double>();
  }
  if (const auto g = y["jump_gate"]) {
    if (g["max_jump_m"]) o.jump_gate.max_jump_m = g["max_jump_m"].as<double>();
    if (g["max_gap_s"]) o.jump_gate.max_gap_s = g["max_gap_s"].as<double>();
    if (g["rejections_to_reset"]) o.jump_gate.rejections_to_reset = g["rejections_to_reset"].as<int>();
  }
  if (y["stale_after_s"]) o.stale_after_s = y["stale_after_s"].as<double>();
  if (const auto c = y["channels"]) {
    if (c["solution"]) o.solution_channel = c["solution"].as<std::string>();
    if (c["pps"]) o.pps_channel = c["pps"].as<std::string>();
  }
  if (o.jump_gate.max_jump_m <= 0) throw std::runtime_error(path + ": jump_gate.max_jump_m must be > 0");
  if (o.jump_gate.rejections_to_reset < 1) throw std::runtime_error(path + ": jump_gate.rejections_to_reset must be >= 1");
  return o;
}

}  // namespace ldv::gnss
