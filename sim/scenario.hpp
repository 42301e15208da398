#pragma once
// Scenarios: a start state and a list of manoeuvre segments, read from YAML (a file or a built-in
// name), compiled into a MotionProfile. Schema in sim/README.md. Every error is an InputError naming
// the file, the line, the segment, the field and what was expected.
#include <optional>
#include <string>
#include <vector>

#include "sim/motion_profile.hpp"

namespace ldv::sim {

struct Segment {
  std::string type;  // static straight accelerate stop turn uturn circle figure8 hill pitch roll pose
  long line = 0;     // in the scenario text (for messages)
  double duration_s = 0.0;
  double to_speed_mps = 0.0;
  double angle_rad = 0.0;    // turn: + = right (clockwise seen from above, yaw increases)
  double radius_m = 0.0;     // circle, figure8
  double yaw_rate_rad_s = 0.0;  // circle alternative to radius
  double turns = 1.0;        // circle
  double ramp_s = 2.0;       // circle, figure8, hill
  double angle_to_rad = 0.0;  // pitch / roll target, hill pitch
  double bank_rad = 0.0;     // turn: roll at the middle of the turn
  bool coordinated = false;  // turn: bank = atan(v * yaw_rate / g)
  double brake_s = 5.0;      // stop
  int direction = +1;        // circle, figure8, uturn: +1 right, -1 left
  // pose (a standing body turned to an attitude, e.g. on a calibration table): the ZYX Euler targets; an absent
  // one keeps its value. Roll and pitch ramp from their current values to these as given (no wrapping: roll
  // 170 -> -170 turns by -340 deg); the heading turns the shorter way round (by a change in (-180, 180]).
  std::optional<double> pose_roll_rad, pose_pitch_rad, pose_yaw_rad;
};

struct Scenario {
  std::string name;
  std::string source;  // file path or "built-in:NAME" (for messages)
  std::string description;
  MotionStart start;
  std::vector<Segment> segments;  // run once
  std::vector<Segment> loop;      // then repeated until the run ends (may be empty: hold the last state)
};

// `name_or_path`: a built-in name (see builtin_scenario_names; also `multiposition:N` and
// `multiposition:N:POSE_S`, see builtin_scenario_yaml) or a YAML file.
Scenario load_scenario(const std::string& name_or_path);
Scenario parse_scenario(const std::string& yaml_text, const std::string& source);

std::vector<std::string> builtin_scenario_names();
// Empty if unknown. Besides the names of builtin_scenario_names(), `multiposition:N` (N static poses, 1..36)
// and `multiposition:N:POSE_S` (each pose but the first POSE_S seconds, 1..3600) are built on demand.
std::string builtin_scenario_yaml(const std::string& name);

// Compiles the segments into smooth channels covering at least duration_s.
// Throws InputError when a segment cannot be flown from the state the previous ones leave
// (e.g. `static` while moving, a circle by radius while stopped).
MotionProfile compile_scenario(const Scenario& s, double duration_s);

}  // namespace ldv::sim
