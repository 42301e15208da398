// The built-in scenarios, written in the same YAML a user writes (`ldv sim --print-scenario NAME`
// prints one to start from). Start: near Geodetics Inc., San Diego, 100 m above the ellipsoid.
#include <map>

#include "sim/scenario.hpp"

namespace ldv::sim {
namespace {
const std::map<std::string, std::string>& builtins() {
  static const std::map<std::string, std::string> m = {
      {"static", R"(name: static
description: "the vehicle stands still, levelled with a small tilt and heading 30 deg"
start: {lat_deg: 32.8801, lon_deg: -117.2340, h_m: 100, yaw_deg: 30, pitch_deg: 1.5, roll_deg: -2.0}
loop:
  - {type: static, duration_s: 3600}
)"},
      {"straight", R"(name: straight
description: "straight runs at 5, 15 and 25 m/s with stops between them"
start: {yaw_deg: 45}
segments:
  - {type: static, duration_s: 10}
loop:
  - {type: accelerate, to_speed_mps: 5, duration_s: 5}
  - {type: straight, duration_s: 30}
  - {type: accelerate, to_speed_mps: 15, duration_s: 10}
  - {type: straight, duration_s: 60}
  - {type: accelerate, to_speed_mps: 25, duration_s: 10}
  - {type: straight, duration_s: 60}
  - {type: stop, brake_s: 15, duration_s: 10}
)"},
      {"accelerate", R"(name: accelerate
description: "repeated hard acceleration to 20 m/s and braking to a stop"
start: {yaw_deg: -60}
loop:
  - {type: static, duration_s: 5}
  - {type: accelerate, to_speed_mps: 20, duration_s: 8}
  - {type: straight, duration_s: 5}
  - {type: stop, brake_s: 6, duration_s: 0}
)"},
      {"turns", R"(name: turns
description: "90 deg turns right and left at 10 m/s, a city block pattern"
start: {yaw_deg: 0}
segments:
  - {type: static, duration_s: 10}
  - {type: accelerate, to_speed_mps: 10, duration_s: 6}
loop:
  - {type: straight, duration_s: 15}
  - {type: turn, angle_deg: 90, duration_s: 6}
  - {type: straight, duration_s: 15}
  - {type: turn, angle_deg: -90, duration_s: 6}
  - {type: straight, duration_s: 10}
  - {type: turn, angle_deg: -90, duration_s: 6}
  - {type: straight, duration_s: 10}
  - {type: turn, angle_deg: 90, duration_s: 6}
)"},
      {"figure8", R"(name: figure8
description: "figure-eights of 30 m loops at 8 m/s"
start: {yaw_deg: 90}
segments:
  - {type: static, duration_s: 10}
  - {type: accelerate, to_speed_mps: 8, duration_s: 5}
loop:
  - {type: figure8, radius_m: 30, ramp_s: 3}
)"},
      {"circle", R"(name: circle
description: "constant-speed circles of 50 m radius at 10 m/s, clockwise"
start: {yaw_deg: 0, speed_mps: 10}
segments:
  - {type: circle, radius_m: 50, turns: 1, ramp_s: 0}
loop:
  - {type: circle, radius_m: 50, turns: 10, ramp_s: 0}
)"},
      {"uturn", R"(name: uturn
description: "out and back along a road with U-turns both ways"
start: {yaw_deg: 10}
segments:
  - {type: static, duration_s: 10}
  - {type: accelerate, to_speed_mps: 8, duration_s: 5}
loop:
  - {type: straight, duration_s: 30}
  - {type: accelerate, to_speed_mps: 4, duration_s: 4}
  - {type: uturn, direction: left, duration_s: 10}
  - {type: accelerate, to_speed_mps: 8, duration_s: 4}
  - {type: straight, duration_s: 30}
  - {type: accelerate, to_speed_mps: 4, duration_s: 4}
  - {type: uturn, direction: right, duration_s: 10}
  - {type: accelerate, to_speed_mps: 8, duration_s: 4}
)"},
      {"reversing", R"(name: reversing
description: "drive forward, stop, reverse into a bay with a turn, drive out"
start: {yaw_deg: 0}
loop:
  - {type: static, duration_s: 5}
  - {type: accelerate, to_speed_mps: 4, duration_s: 4}
  - {type: straight, duration_s: 10}
  - {type: stop, brake_s: 3, duration_s: 3}
  - {type: accelerate, to_speed_mps: -2, duration_s: 3}
  - {type: turn, angle_deg: -90, duration_s: 8}
  - {type: straight, duration_s: 3}
  - {type: stop, brake_s: 2, duration_s: 5}
  - {type: accelerate, to_speed_mps: 3, duration_s: 3}
  - {type: turn, angle_deg: 90, duration_s: 8}
  - {type: stop, brake_s: 3, duration_s: 0}
)"},
      {"hills", R"(name: hills
description: "climbs and descents of 3 to 8 deg at 15 m/s with bends and a banked road"
start: {yaw_deg: 200}
segments:
  - {type: static, duration_s: 10}
  - {type: accelerate, to_speed_mps: 15, duration_s: 8}
loop:
  - {type: hill, pitch_deg: 6, duration_s: 30, ramp_s: 5}
  - {type: straight, duration_s: 10}
  - {type: hill, pitch_deg: -8, duration_s: 25, ramp_s: 5}
  - {type: roll, to_deg: 3, duration_s: 3}
  - {type: turn, angle_deg: 45, duration_s: 8}
  - {type: roll, to_deg: 0, duration_s: 3}
  - {type: hill, pitch_deg: 3, duration_s: 40, ramp_s: 6}
  - {type: turn, angle_deg: -45, duration_s: 8}
  - {type: hill, pitch_deg: -3, duration_s: 40, ramp_s: 6}
)"},
      {"stops", R"(name: stops
description: "stop-and-go traffic: short drives with stops of 5 to 30 s"
start: {yaw_deg: 120}
loop:
  - {type: static, duration_s: 20}
  - {type: accelerate, to_speed_mps: 12, duration_s: 7}
  - {type: straight, duration_s: 15}
  - {type: stop, brake_s: 5, duration_s: 5}
  - {type: accelerate, to_speed_mps: 6, duration_s: 4}
  - {type: turn, angle_deg: 90, duration_s: 6}
  - {type: stop, brake_s: 3, duration_s: 30}
  - {type: accelerate, to_speed_mps: 9, duration_s: 5}
  - {type: stop, brake_s: 4, duration_s: 0}
)"},
      {"airborne", R"(name: airborne
description: "a light aircraft at 60 m/s, 1000 m up: coordinated turns, climbs and descents"
start: {h_m: 1000, yaw_deg: 0, speed_mps: 60}
loop:
  - {type: straight, duration_s: 30}
  - {type: turn, angle_deg: 90, duration_s: 20, coordinated: true}
  - {type: hill, pitch_deg: 5, duration_s: 40, ramp_s: 5}
  - {type: turn, angle_deg: -180, duration_s: 40, coordinated: true}
  - {type: straight, duration_s: 20}
  - {type: hill, pitch_deg: -4, duration_s: 40, ramp_s: 5}
  - {type: turn, angle_deg: 90, duration_s: 20, coordinated: true}
  - {type: accelerate, to_speed_mps: 70, duration_s: 15}
  - {type: accelerate, to_speed_mps: 60, duration_s: 15}
)"},
      {"drive", R"(name: drive
description: "a varied land-vehicle drive using every manoeuvre (the default); 60 s static alignment first"
start: {lat_deg: 32.8801, lon_deg: -117.2340, h_m: 100, yaw_deg: 15}
segments:
  - {type: static, duration_s: 60}
loop:
  - {type: accelerate, to_speed_mps: 10, duration_s: 8}
  - {type: straight, duration_s: 20}
  - {type: turn, angle_deg: 90, duration_s: 8}
  - {type: accelerate, to_speed_mps: 18, duration_s: 10}
  - {type: hill, pitch_deg: 5, duration_s: 30, ramp_s: 5}
  - {type: turn, angle_deg: -60, duration_s: 8}
  - {type: hill, pitch_deg: -4, duration_s: 25, ramp_s: 5}
  - {type: accelerate, to_speed_mps: 8, duration_s: 8}
  - {type: circle, radius_m: 25, turns: 1, ramp_s: 3}
  - {type: figure8, radius_m: 30, ramp_s: 3}
  - {type: turn, angle_deg: -120, duration_s: 10}
  - {type: stop, brake_s: 6, duration_s: 15}
  - {type: accelerate, to_speed_mps: -2.5, duration_s: 4}
  - {type: turn, angle_deg: 45, duration_s: 8}
  - {type: stop, brake_s: 2, duration_s: 5}
  - {type: accelerate, to_speed_mps: 12, duration_s: 8}
  - {type: roll, to_deg: 2.5, duration_s: 3}
  - {type: straight, duration_s: 15}
  - {type: roll, to_deg: 0, duration_s: 3}
  - {type: accelerate, to_speed_mps: 6, duration_s: 5}
  - {type: uturn, direction: left, duration_s: 12}
  - {type: accelerate, to_speed_mps: 25, duration_s: 15}
  - {type: straight, duration_s: 30}
  - {type: stop, brake_s: 12, duration_s: 20}
)"},
  };
  return m;
}
}  // namespace

std::vector<std::string> builtin_scenario_names() {
  std::vector<std::string> names;
  for (const auto& [name, text] : builtins()) names.push_back(name);
  names.push_back("mixed");
  return names;
}

std::string builtin_scenario_yaml(const std::string& name) {
  const auto it = builtins().find(name == "mixed" ? "drive" : name);
  return it == builtins().end() ? std::string() : it->second;
}

}  // namespace ldv::sim
