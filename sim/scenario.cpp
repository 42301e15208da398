#include "sim/scenario.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "common/io/input_error.hpp"
#include "common/io/text_file_lines.hpp"

namespace ldv::sim {
namespace {

long line_of(const YAML::Node& n) { return n.IsDefined() ? n.Mark().line + 1 : 0; }

// Reads the fields of one YAML mapping, remembering which keys were used so that unknown keys
// (typos) are reported instead of silently ignored.
class Fields {
 public:
  Fields(const YAML::Node& node, std::string file, std::string where)
      : node_(node), file_(std::move(file)), where_(std::move(where)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& expected) const {
    const YAML::Node n = node_[key];
    throw InputError(file_, n.IsDefined() ? line_of(n) : line_of(node_),
                     where_ + "field '" + key + "': expected " + expected);
  }
  bool has(const std::string& key) const {
    return node_[key].IsDefined() && !node_[key].IsNull();
  }
  double number(const std::string& key, const std::string& unit_and_range) {
    if (!has(key)) fail(key, unit_and_range + " (the field is missing)");
    try {
      const double v = node_[key].as<double>();
      if (!std::isfinite(v)) fail(key, unit_and_range);
      return v;
    } catch (const YAML::Exception&) {
      fail(key, unit_and_range + ", found '" + scalar_text(key) + "'");
    }
  }
  double number_or(const std::string& key, double fallback, const std::string& unit_and_range) {
    return has(key) ? number(key, unit_and_range) : fallback;
  }
  double positive(const std::string& key, const std::string& unit) {
    const double v = number(key, "a positive number " + unit);
    if (v <= 0) fail(key, "a positive number " + unit + ", found " + scalar_text(key));
    return v;
  }
  double in_range(const std::string& key, double fallback, double lo, double hi, const std::string& unit) {
    std::ostringstream what;
    what << "a number " << unit << " in [" << lo << ", " << hi << "]";
    if (!has(key)) return fallback;
    const double v = number(key, what.str());
    if (v < lo || v > hi) fail(key, what.str() + ", found " + scalar_text(key));
    return v;
  }
  std::string text(const std::string& key, const std::string& fallback) {
    if (!has(key)) return fallback;
    if (!node_[key].IsScalar()) fail(key, "a text value");
    return node_[key].as<std::string>();
  }
  void reject_unknown(const std::set<std::string>& allowed) const {
    for (const auto& kv : node_) {
      const std::string key = kv.first.as<std::string>();
      if (!allowed.count(key)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        throw InputError(file_, line_of(kv.first), where_ + "unknown field '" + key + "' (allowed: " + list + ")");
      }
    }
  }
  std::string scalar_text(const std::string& key) const {
    const YAML::Node n = node_[key];
    return n.IsScalar() ? n.Scalar() : std::string("a non-scalar value");
  }

 private:
  YAML::Node node_;
  std::string file_, where_;
};

int direction_of(Fields& f) {
  const std::string d = f.text("direction", "right");
  if (d == "right") return +1;
  if (d == "left") return -1;
  f.fail("direction", "'right' or 'left', found '" + d + "'");
}

Segment parse_segment(const YAML::Node& node, const std::string& file, const std::string& list, size_t index) {
  const std::string where0 = list + " " + std::to_string(index + 1);
  if (!node.IsMap())
    throw InputError(file, line_of(node), where0 + ": expected a mapping like {type: turn, angle_deg: 90, duration_s: 8}");
  Segment s;
  s.line = line_of(node);
  Fields f0(node, file, where0 + ": ");
  s.type = f0.text("type", "");
  if (s.type.empty()) f0.fail("type", "one of static straight accelerate stop turn uturn circle figure8 hill pitch roll pose");
  Fields f(node, file, where0 + " (" + s.type + "): ");
  const double kDeg = kDegToRad;
  auto duration = [&] { s.duration_s = f.positive("duration_s", "[s]"); };
  std::set<std::string> allowed{"type", "duration_s"};
  if (s.type == "static" || s.type == "straight" || s.type == "cruise") {
    duration();
  } else if (s.type == "accelerate" || s.type == "brake") {
    duration();
    s.to_speed_mps = f.in_range("to_speed_mps", 0.0, -100.0, 300.0, "[m/s]");
    if (!f.has("to_speed_mps")) f.fail("to_speed_mps", "the target speed [m/s] (negative = reversing)");
    allowed.insert("to_speed_mps");
  } else if (s.type == "stop") {
    s.brake_s = f.positive("brake_s", "[s] (braking time)");
    s.duration_s = f.in_range("duration_s", 0.0, 0.0, 1e7, "[s] (standing time after braking)");
    allowed.insert("brake_s");
  } else if (s.type == "turn") {
    duration();
    s.angle_rad = f.number("angle_deg", "a heading change [deg] (+ right, - left)") * kDeg;
    s.bank_rad = f.in_range("bank_deg", 0.0, -60.0, 60.0, "[deg]") * kDeg;
    const std::string c = f.text("coordinated", "false");
    if (c != "true" && c != "false") f.fail("coordinated", "true or false");
    s.coordinated = c == "true";
    allowed.insert({"angle_deg", "bank_deg", "coordinated"});
  } else if (s.type == "uturn") {
    duration();
    s.direction = direction_of(f);
    s.angle_rad = s.direction * kPi;
    allowed.insert("direction");
  } else if (s.type == "circle" || s.type == "figure8") {
    s.direction = direction_of(f);
    s.ramp_s = f.in_range("ramp_s", 2.0, 0.0, 600.0, "[s]");
    if (f.has("radius_m")) s.radius_m = f.positive("radius_m", "[m]");
    if (s.type == "circle") {
      if (f.has("yaw_rate_dps")) s.yaw_rate_rad_s = f.positive("yaw_rate_dps", "[deg/s]") * kDeg;
      if ((s.radius_m > 0) == (s.yaw_rate_rad_s > 0)) f.fail("radius_m", "exactly one of radius_m [m] or yaw_rate_dps [deg/s]");
      s.turns = f.in_range("turns", 1.0, 0.01, 1e5, "(number of full turns)");
      allowed.insert({"yaw_rate_dps", "turns"});
    } else if (s.radius_m <= 0) {
      f.fail("radius_m", "the radius of each loop [m]");
    }
    allowed.erase("duration_s");
    allowed.insert({"direction", "ramp_s", "radius_m"});
  } else if (s.type == "hill") {
    duration();
    s.angle_to_rad = f.in_range("pitch_deg", 0.0, -45.0, 45.0, "[deg] (+ = climbing)") * kDeg;
    if (!f.has("pitch_deg")) f.fail("pitch_deg", "the road pitch [deg] (+ = climbing)");
    s.ramp_s = f.in_range("ramp_s", 2.0, 0.0, 600.0, "[s]");
    if (2 * s.ramp_s > s.duration_s) f.fail("ramp_s", "at most half of duration_s");
    allowed.insert({"pitch_deg", "ramp_s"});
  } else if (s.type == "pitch" || s.type == "roll") {
    duration();
    if (!f.has("to_deg")) f.fail("to_deg", "the target angle [deg]");
    s.angle_to_rad = f.in_range("to_deg", 0.0, -80.0, 80.0, "[deg]") * kDeg;
    allowed.insert("to_deg");
  } else if (s.type == "pose") {
    // A standing body turned to an attitude (a calibration table, a hand): the Euler angles ramp together.
    duration();
    if (f.has("roll_deg")) s.pose_roll_rad = f.in_range("roll_deg", 0.0, -360.0, 360.0, "[deg]") * kDeg;
    if (f.has("pitch_deg")) s.pose_pitch_rad = f.in_range("pitch_deg", 0.0, -90.0, 90.0, "[deg]") * kDeg;
    if (f.has("yaw_deg")) s.pose_yaw_rad = f.in_range("yaw_deg", 0.0, -360.0, 360.0, "[deg]") * kDeg;
    if (!s.pose_roll_rad && !s.pose_pitch_rad && !s.pose_yaw_rad)
      f.fail("roll_deg", "at least one of roll_deg, pitch_deg, yaw_deg (the attitude to turn to)");
    allowed.insert({"roll_deg", "pitch_deg", "yaw_deg"});
  } else {
    f0.fail("type", "one of static straight accelerate stop turn uturn circle figure8 hill pitch roll pose, found '" +
                        s.type + "'");
  }
  f.reject_unknown(allowed);
  return s;
}

std::vector<Segment> parse_segments(const YAML::Node& root, const std::string& key, const std::string& file) {
  std::vector<Segment> out;
  const YAML::Node list = root[key];
  if (!list.IsDefined() || list.IsNull()) return out;
  if (!list.IsSequence()) throw InputError(file, line_of(list), "field '" + key + "': expected a list of segments");
  for (size_t i = 0; i < list.size(); ++i) out.push_back(parse_segment(list[i], file, key + " segment", i));
  return out;
}

}  // namespace

Scenario parse_scenario(const std::string& text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(source, e.mark.line + 1, "YAML syntax error: " + e.msg);
  }
  if (!root.IsMap()) throw InputError(source, 0, "expected a YAML mapping with 'start' and 'segments' (see sim/README.md)");
  Fields top(root, source, "");
  top.reject_unknown({"name", "description", "start", "segments", "loop"});
  Scenario s;
  s.source = source;
  s.name = top.text("name", std::filesystem::path(source).stem().string());
  s.description = top.text("description", "");
  const YAML::Node start = root["start"];
  if (start.IsDefined() && !start.IsNull()) {
    if (!start.IsMap()) throw InputError(source, line_of(start), "field 'start': expected a mapping");
    Fields f(start, source, "start: ");
    f.reject_unknown({"lat_deg", "lon_deg", "h_m", "yaw_deg", "pitch_deg", "roll_deg", "speed_mps"});
    s.start.pos.lat_rad = f.in_range("lat_deg", 32.8801, -89.0, 89.0, "[deg]") * kDegToRad;
    s.start.pos.lon_rad = f.in_range("lon_deg", -117.2340, -180.0, 360.0, "[deg]") * kDegToRad;
    s.start.pos.h_m = f.in_range("h_m", 100.0, -500.0, 20000.0, "[m] above the ellipsoid");
    s.start.yaw_rad = f.in_range("yaw_deg", 0.0, -360.0, 360.0, "[deg]") * kDegToRad;
    s.start.pitch_rad = f.in_range("pitch_deg", 0.0, -80.0, 80.0, "[deg]") * kDegToRad;
    s.start.roll_rad = f.in_range("roll_deg", 0.0, -80.0, 80.0, "[deg]") * kDegToRad;
    s.start.speed_mps = f.in_range("speed_mps", 0.0, -100.0, 300.0, "[m/s]");
  } else {
    s.start.pos = {32.8801 * kDegToRad, -117.2340 * kDegToRad, 100.0};
  }
  s.segments = parse_segments(root, "segments", source);
  s.loop = parse_segments(root, "loop", source);
  if (s.segments.empty() && s.loop.empty())
    throw InputError(source, line_of(root), "field 'segments': expected at least one segment in 'segments' or 'loop'");
  return s;
}

Scenario load_scenario(const std::string& name_or_path) {
  const std::string builtin = builtin_scenario_yaml(name_or_path);
  if (!builtin.empty()) return parse_scenario(builtin, "built-in:" + name_or_path);
  if (!std::ifstream(name_or_path)) {
    std::string names;
    for (const auto& n : builtin_scenario_names()) names += " " + n;
    throw InputError(name_or_path, 0, "scenario: expected a built-in name (" + names.substr(1) + ") or a readable YAML file");
  }
  // Bounded, regular files only: /dev/zero or a huge file given as a scenario is a clear error, not all memory.
  return parse_scenario(read_small_text_file(name_or_path, static_cast<size_t>(1) << 20), name_or_path);
}

namespace {
// Appends one segment's ramps at time t; updates t and the running speed.
struct Compiler {
  const Scenario& sc;
  MotionProfile& m;
  double t = 0.0;
  double speed = 0.0;

  [[noreturn]] void fail(const Segment& s, const std::string& msg) const {
    throw InputError(sc.source, s.line, "segment '" + s.type + "': " + msg);
  }
  // A bump of the channel: rises to `peak` over the first half of [t0, t0 + d], returns over the second.
  static void bump(Channel& c, double t0, double d, double peak) {
    const double base = c.final_value();
    c.ramp_to(t0, 0.5 * d, base + peak);
    c.ramp_to(t0 + 0.5 * d, 0.5 * d, base);
  }
  double yaw_rate_for_radius(const Segment& s) const {
    if (std::abs(speed) < 0.1)
      fail(s, "radius_m needs a moving vehicle (speed here is " + std::to_string(speed) +
                  " m/s); accelerate first or give yaw_rate_dps");
    return std::abs(speed) / s.radius_m;
  }

  void add(const Segment& s) {
    if (s.type == "static") {
      if (std::abs(speed) > 1e-9)
        fail(s, "the vehicle moves at " + std::to_string(speed) + " m/s here; add 'stop' or 'accelerate' to 0 first");
      t += s.duration_s;
    } else if (s.type == "straight" || s.type == "cruise") {
      t += s.duration_s;
    } else if (s.type == "accelerate" || s.type == "brake") {
      bump(m.accel_mps2, t, s.duration_s, 2.0 * (s.to_speed_mps - speed) / s.duration_s);
      speed = s.to_speed_mps;
      t += s.duration_s;
    } else if (s.type == "stop") {
      bump(m.accel_mps2, t, s.brake_s, -2.0 * speed / s.brake_s);
      speed = 0.0;
      t += s.brake_s + s.duration_s;
    } else if (s.type == "turn" || s.type == "uturn") {
      const double peak_rate = 2.0 * s.angle_rad / s.duration_s;
      bump(m.yaw_rate_rad_s, t, s.duration_s, peak_rate);
      if (s.coordinated) {  // the bank follows the yaw rate exactly (MotionProfile::coordinated)
        m.coordinated.ramp_to(t, 0.0, 1.0);
        m.coordinated.ramp_to(t + s.duration_s, 0.0, 0.0);
      } else if (s.bank_rad != 0.0) {
        bump(m.roll_rad, t, s.duration_s, s.bank_rad);
      }
      t += s.duration_s;
    } else if (s.type == "circle") {
      const double rate = s.direction * (s.radius_m > 0 ? yaw_rate_for_radius(s) : s.yaw_rate_rad_s);
      const double hold = 2.0 * kPi * s.turns / std::abs(rate) - s.ramp_s;
      if (hold < 0) fail(s, "ramp_s is longer than the whole circle; shorten ramp_s");
      m.yaw_rate_rad_s.ramp_to(t, s.ramp_s, rate);
      m.yaw_rate_rad_s.ramp_to(t + s.ramp_s + hold, s.ramp_s, 0.0);
      t += 2.0 * s.ramp_s + hold;
    } else if (s.type == "figure8") {
      // Two loops of opposite sense; each loop turns 360 deg (the reversal ramp contributes 0.6875 ramp_s
      // of yaw rate to each loop: integral of 1 - 2 S(u) over the first half, times 2 ramp_s).
      const double rate = s.direction * yaw_rate_for_radius(s);
      const double hold = 2.0 * kPi / std::abs(rate) - 1.1875 * s.ramp_s;
      if (hold < 0) fail(s, "ramp_s is too long for this radius and speed; shorten ramp_s");
      m.yaw_rate_rad_s.ramp_to(t, s.ramp_s, rate);
      m.yaw_rate_rad_s.ramp_to(t + s.ramp_s + hold, 2.0 * s.ramp_s, -rate);
      m.yaw_rate_rad_s.ramp_to(t + 3.0 * s.ramp_s + 2.0 * hold, s.ramp_s, 0.0);
      t += 4.0 * s.ramp_s + 2.0 * hold;
    } else if (s.type == "hill") {
      const double base = m.pitch_rad.final_value();
      m.pitch_rad.ramp_to(t, s.ramp_s, base + s.angle_to_rad);
      m.pitch_rad.ramp_to(t + s.duration_s - s.ramp_s, s.ramp_s, base);
      t += s.duration_s;
    } else if (s.type == "pitch") {
      m.pitch_rad.ramp_to(t, s.duration_s, s.angle_to_rad);
      t += s.duration_s;
    } else if (s.type == "roll") {
      m.roll_rad.ramp_to(t, s.duration_s, s.angle_to_rad);
      t += s.duration_s;
    } else if (s.type == "pose") {
      if (std::abs(speed) > 1e-9)
        fail(s, "the vehicle moves at " + std::to_string(speed) + " m/s here; a pose is turned standing ('stop' first)");
      if (s.pose_roll_rad) m.roll_rad.ramp_to(t, s.duration_s, *s.pose_roll_rad);
      if (s.pose_pitch_rad) m.pitch_rad.ramp_to(t, s.duration_s, *s.pose_pitch_rad);
      if (s.pose_yaw_rad) {
        // The heading now (closed form), and the change to the target the shorter way round, in (-180, 180] deg.
        const double yaw_now = m.start.yaw_rad + m.yaw_rate_rad_s.at(t).integral;
        double change = std::remainder(*s.pose_yaw_rad - yaw_now, 2.0 * kPi);
        if (change <= -kPi + 1e-9) change += 2.0 * kPi;  // a half turn is +180 deg, whatever the rounding
        if (change != 0.0) bump(m.yaw_rate_rad_s, t, s.duration_s, 2.0 * change / s.duration_s);
      }
      t += s.duration_s;
    }
  }
};
}  // namespace

MotionProfile compile_scenario(const Scenario& sc, double duration_s) {
  MotionProfile m;
  m.start = sc.start;
  m.pitch_rad = Channel(sc.start.pitch_rad);
  m.roll_rad = Channel(sc.start.roll_rad);
  Compiler c{sc, m, 0.0, sc.start.speed_mps};
  for (const Segment& s : sc.segments) {
    if (c.t >= duration_s) break;
    c.add(s);
  }
  if (!sc.loop.empty()) {
    while (c.t < duration_s) {
      const double before = c.t;
      for (const Segment& s : sc.loop) {
        if (c.t >= duration_s) break;
        c.add(s);
      }
      if (c.t <= before) throw InputError(sc.source, sc.loop.front().line, "field 'loop': the loop takes no time");
    }
  }
  m.scheduled_s = c.t;
  return m;
}

}  // namespace ldv::sim
