// The built-in scenarios, written in the same YAML a user writes (`ldv sim --print-scenario NAME`
// prints one to start from). Start: near Geodetics Inc., San Diego, 100 m above the ellipsoid.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

#include "sim/scenario.hpp"

namespace ldv::sim {
namespace {
// The multi-position calibration session (`multiposition`, `multiposition:N`, `multiposition:N:POSE_S`): a body
// standing on a calibration table, turned between static poses as `ldv calib static` needs them: the six
// axis-up/down poses, the eight cube corners (every pair of axes tilted against gravity: the non-orthogonality),
// four cube edges; each rotation tilts gravity by 48 deg or more (the gyro rotation method's conditions) about a
// different axis. Every pose is 2 to 5 deg off its nominal one, as a hand-placed table is, and so that no two of
// the gravity direction's components have the same magnitude (at an exact cube pose they do, and the tangent
// basis of ldv calib static's rotation condition then switches axes with the noise: bench/paper_tables/
// table2_notes.md). Yaws chosen so that the 18 attitude matrices sum to nearly zero (|sum C_b_n| = 1.15 of 18):
// the mean static gyro reading, which the rotation method reports as the bias, holds < 0.064 of Earth rate.
// Poses 19..36 repeat 1..18 turned by 180 deg in heading.
struct TablePose {
  double roll_deg, pitch_deg, yaw_deg;
  const char* down;  // the body axis / direction that points down (nominally)
};
constexpr TablePose kTablePoses[18] = {
    {2, -3, 0, "z down (level)"},           {87, 2, 180, "y down"},
    {183, -2, 180, "z up"},                 {133, 38, 180, "corner -x+y-z down"},
    {138, -37, 90, "corner +x+y-z down"},   {140, -86, -90, "x down"},
    {42, -33, 180, "corner +x+y+z down"},   {47, 32, 0, "corner -x+y+z down"},
    {40, 86, -90, "x up"},                  {-47, 37, 180, "corner -x-y+z down"},
    {-42, -37, 0, "corner +x-y+z down"},    {-92, 3, 180, "y up"},
    {-133, -38, -90, "corner +x-y-z down"}, {-138, 37, 0, "corner -x-y-z down"},
    {-177, -42, 0, "edge +x-z down"},       {-92, 43, 0, "edge -x-y down"},
    {2, 48, 180, "edge -x+z down"},         {42, 2, 0, "edge +y+z down"},
};
constexpr double kFirstPoseS = 30.0;  // the detector's default initial static period (imu_tk)
constexpr double kRotationS = 3.0;  // body rates up to 132 deg/s (HG1700: +-1000 deg/s)

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.15g", v);
  return b;
}

std::string multiposition_yaml(const std::string& name, int poses, double pose_s) {
  const double first_s = std::max(kFirstPoseS, pose_s);
  const double total_s = first_s + (poses - 1) * (kRotationS + pose_s);
  std::string y = "name: \"" + name + "\"\n";
  y += "description: \"multi-position static calibration (ldv calib static): " + std::to_string(poses) +
       " static poses on a table (axis up/down, cube corners and edges, 2-5 deg off), the first " +
       number(first_s) + " s, the others " + number(pose_s) + " s, " + number(kRotationS) +
       " s rotations tilting gravity by 48 deg or more; " + number(total_s) + " s in all\"\n";
  const TablePose& p0 = kTablePoses[0];
  y += "start: {lat_deg: 32.8801, lon_deg: -117.2340, h_m: 100, yaw_deg: " + number(p0.yaw_deg) +
       ", pitch_deg: " + number(p0.pitch_deg) + ", roll_deg: " + number(p0.roll_deg) + "}\n";
  y += "segments:\n";
  for (int k = 0; k < poses; ++k) {
    const TablePose& p = kTablePoses[k % 18];
    double yaw = p.yaw_deg;
    if (k >= 18) yaw = yaw > 0 ? yaw - 180 : yaw + 180;
    if (k > 0)
      y += "  - {type: pose, roll_deg: " + number(p.roll_deg) + ", pitch_deg: " + number(p.pitch_deg) +
           ", yaw_deg: " + number(yaw) + ", duration_s: " + number(kRotationS) + "}\n";
    y += "  - {type: static, duration_s: " + number(k == 0 ? first_s : pose_s) + "}   # pose " + std::to_string(k + 1) +
         ": " + p.down + "\n";
  }
  return y;
}

// "multiposition", "multiposition:N", "multiposition:N:POSE_S" -> the YAML; "" when not such a name.
std::string multiposition_from_name(const std::string& name) {
  const std::string base = "multiposition";
  if (name.compare(0, base.size(), base) != 0) return "";
  if (name.size() == base.size()) return multiposition_yaml(name, 18, 10.0);
  if (name[base.size()] != ':') return "";
  const std::string rest = name.substr(base.size() + 1);
  const size_t colon = rest.find(':');
  auto parse = [](const std::string& text, double& v) {
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    return !text.empty() && ec == std::errc() && ptr == text.data() + text.size() && std::isfinite(v);
  };
  double n = 0, pose_s = 10.0;
  if (!parse(rest.substr(0, colon), n) || n != std::floor(n) || n < 1 || n > 36) return "";
  if (colon != std::string::npos && (!parse(rest.substr(colon + 1), pose_s) || pose_s < 1 || pose_s > 3600)) return "";
  return multiposition_yaml(name, static_cast<int>(n), pose_s);
}

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
  names.push_back("multiposition");
  return names;
}

std::string builtin_scenario_yaml(const std::string& name) {
  const auto it = builtins().find(name == "mixed" ? "drive" : name);
  return it == builtins().end() ? multiposition_from_name(name) : it->second;
}

}  // namespace ldv::sim
