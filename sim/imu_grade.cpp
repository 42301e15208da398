#include "sim/imu_grade.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

#include "common/config/config_section.hpp"
#include "common/io/input_error.hpp"
#include "common/io/text_file_lines.hpp"

namespace ldv::sim {
namespace {

// ---- The paper's units -> SI (the rate unit u is rad/s for the gyro, m/s^2 for the accelerometer) ----
constexpr double kDeg = kDegToRad;                 // deg -> rad
constexpr double kArcsec = kDegToRad / 3600.0;     // arcsec -> rad
constexpr double kHour = 3600.0;                   // h -> s
constexpr double kSqrtHour = 60.0;                 // sqrt(h) -> sqrt(s)
constexpr double kG = 9.80665;                     // g -> m/s^2 (standard gravity)

struct UnitKey {
  const char* key;
  double si;  // SI value of one unit
};
struct Term {
  Vec3 TriadErrorModel::*field;
  bool may_be_negative;
  std::vector<UnitKey> keys;  // alternative spellings, one unit each; at most one of them in a file
};

// Gyro: Q angle, N angle random walk, B rate, K rate / sqrt(time), R rate / time.
const std::vector<Term>& gyro_terms() {
  static const std::vector<Term> t = {
      {&TriadErrorModel::quantization_Q, false,
       {{"Q_arcsec", kArcsec},            // arcsec -> rad: pi / 180 / 3600
        {"Q_deg", kDeg},                  // deg -> rad: pi / 180
        {"Q_urad", 1e-6}}},               // urad -> rad
      {&TriadErrorModel::white_N, false,
       {{"N_deg_sqrt_h", kDeg / kSqrtHour}}},           // deg/sqrt(h) -> rad/sqrt(s): pi / 180 / 60
      {&TriadErrorModel::instability_B, false,
       {{"B_deg_h", kDeg / kHour},                      // deg/h -> rad/s: pi / 180 / 3600
        {"B_deg_s", kDeg}}},                            // deg/s -> rad/s
      {&TriadErrorModel::instability_T_s, false, {{"B_time_constant_s", 1.0}}},
      {&TriadErrorModel::rate_rw_K, false,
       {{"K_deg_h_sqrt_h", kDeg / kHour / kSqrtHour}}},  // deg/h/sqrt(h) -> rad/s/sqrt(s): pi / 180 / 3600 / 60
      {&TriadErrorModel::ramp_R, true,
       {{"R_deg_h2", kDeg / kHour / kHour}}},            // deg/h^2 -> rad/s^2: pi / 180 / 3600^2
      {&TriadErrorModel::turn_on_bias_std, false,
       {{"turn_on_bias_deg_h", kDeg / kHour},           // deg/h -> rad/s
        {"turn_on_bias_deg_s", kDeg}}},                 // deg/s -> rad/s
      {&TriadErrorModel::scale_std, false, {{"scale_ppm", 1e-6}, {"scale_percent", 1e-2}}},
      {&TriadErrorModel::non_orthogonality_std, false,
       {{"non_orthogonality_urad", 1e-6}, {"non_orthogonality_arcsec", kArcsec}}},
  };
  return t;
}

// Accelerometer: Q velocity, N velocity random walk, B acceleration, K acceleration / sqrt(time), R / time.
const std::vector<Term>& accel_terms() {
  static const std::vector<Term> t = {
      {&TriadErrorModel::quantization_Q, false,
       {{"Q_m_h", 1.0 / kHour},           // m/h -> m/s: / 3600
        {"Q_mps", 1.0}}},
      {&TriadErrorModel::white_N, false,
       {{"N_mps_sqrt_h", 1.0 / kSqrtHour}}},             // m/s/sqrt(h) -> m/s/sqrt(s) = m/s^2/sqrt(Hz): / 60
      {&TriadErrorModel::instability_B, false,
       {{"B_mps_h", 1.0 / kHour},                        // m/s/h -> m/s^2: / 3600
        {"B_mg", 1e-3 * kG},                             // mg -> m/s^2: 9.80665e-3
        {"B_ug", 1e-6 * kG}}},                           // ug -> m/s^2: 9.80665e-6
      {&TriadErrorModel::instability_T_s, false, {{"B_time_constant_s", 1.0}}},
      {&TriadErrorModel::rate_rw_K, false,
       {{"K_mps_h_sqrt_h", 1.0 / kHour / kSqrtHour}}},   // m/s/h/sqrt(h) -> m/s^2/sqrt(s): / 3600 / 60
      {&TriadErrorModel::ramp_R, true,
       {{"R_mps_h2", 1.0 / kHour / kHour}}},             // m/s/h^2 -> m/s^3: / 3600^2
      {&TriadErrorModel::turn_on_bias_std, false,
       {{"turn_on_bias_mg", 1e-3 * kG},                  // mg -> m/s^2
        {"turn_on_bias_g", kG},                          // g -> m/s^2
        {"turn_on_bias_mps_h", 1.0 / kHour}}},           // m/s/h -> m/s^2
      {&TriadErrorModel::scale_std, false, {{"scale_ppm", 1e-6}, {"scale_percent", 1e-2}}},
      {&TriadErrorModel::non_orthogonality_std, false,
       {{"non_orthogonality_urad", 1e-6}, {"non_orthogonality_arcsec", kArcsec}}},
  };
  return t;
}

long line_of(const YAML::Node& n) { return n.IsDefined() ? n.Mark().line + 1 : 0; }

std::string list_of(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

class GradeReader {
 public:
  explicit GradeReader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const YAML::Node& at, const std::string& key, const std::string& msg) const {
    throw InputError(file_, line_of(at), "key '" + key + "': " + msg);
  }

  // One number (every axis) or [x, y, z] with numbers or null (null: the term is absent on that axis).
  Vec3 per_axis(const YAML::Node& n, const std::string& key, bool may_be_negative) const {
    auto number = [&](const YAML::Node& e, const std::string& what) {
      double v = 0;
      try {
        v = e.as<double>();
      } catch (const YAML::Exception&) {
        fail(e, key, "expected " + what + ", found '" + (e.IsScalar() ? e.Scalar() : std::string("a non-scalar")) + "'");
      }
      if (!std::isfinite(v)) fail(e, key, "expected a finite number, found '" + e.Scalar() + "'");
      if (v < 0 && !may_be_negative) fail(e, key, "expected a number >= 0, found " + e.Scalar());
      return v;
    };
    if (n.IsScalar()) return Vec3::Constant(number(n, "a number or a list [x, y, z]"));
    if (!n.IsSequence() || n.size() != 3)
      fail(n, key, "expected a number (every axis) or a list of 3 values [x, y, z] (null: absent on that axis)" +
                       std::string(n.IsSequence() ? ", found " + std::to_string(n.size()) + " values" : ""));
    Vec3 v = Vec3::Zero();
    for (int i = 0; i < 3; ++i)
      if (!n[i].IsNull()) v[i] = number(n[i], "a number or null (element " + std::to_string(i + 1) + ")");
    return v;
  }

  TriadErrorModel triad(const YAML::Node& node, const std::string& name, const std::vector<Term>& terms) const {
    TriadErrorModel m;
    if (!node.IsMap()) fail(node, name, "expected a mapping of noise terms (see sim/README.md, Grade YAML)");
    std::vector<std::string> known = {"quantization"};
    for (const Term& t : terms)
      for (const UnitKey& k : t.keys) known.push_back(k.key);
    for (const auto& kv : node) {
      const std::string key = kv.first.as<std::string>();
      if (std::find(known.begin(), known.end(), key) != known.end()) continue;
      const std::string near = config::nearest_name(key, known);
      throw InputError(file_, line_of(kv.first),
                       "unknown key '" + name + "." + key + "'" +
                           (near.empty() ? "" : " (did you mean '" + name + "." + near + "'?)") + "; known: " +
                           list_of(known));
    }
    bool has_T = false;
    YAML::Node b_node, t_node;
    std::string b_key;
    for (const Term& t : terms) {
      const UnitKey* given = nullptr;
      YAML::Node given_node;
      for (const UnitKey& k : t.keys) {
        const YAML::Node n = node[k.key];
        if (!n.IsDefined() || n.IsNull()) continue;
        if (given) {  // name the one further down the file
          const bool later = line_of(n) >= line_of(given_node);
          fail(later ? n : given_node, name + "." + (later ? k.key : given->key),
               std::string("expected one unit for this term, but '") + (later ? given->key : k.key) +
                   "' is also given");
        }
        given = &k;
        given_node = n;
      }
      if (!given) continue;
      const std::string key = name + "." + given->key;
      const Vec3 v = per_axis(given_node, key, t.may_be_negative) * given->si;
      m.*(t.field) = v;
      if (t.field == &TriadErrorModel::instability_T_s) has_T = true, t_node = given_node;
      if (t.field == &TriadErrorModel::instability_B) b_node = given_node, b_key = key;
    }
    // B is a Gauss-Markov process: every axis with a B needs its time constant.
    const std::string t_key = name + ".B_time_constant_s";
    if (!has_T) m.instability_T_s = Vec3::Constant(3600.0);
    for (int i = 0; i < 3; ++i) {
      if (m.instability_B[i] > 0 && !has_T)
        fail(b_node, b_key, "needs its Gauss-Markov time constant: add '" + t_key + "' [s]");
      if (m.instability_B[i] > 0 && !(m.instability_T_s[i] > 0))
        fail(t_node, t_key, "expected a positive time constant [s] on axis " + std::string(1, "xyz"[i]) +
                                " (it has a B)");
      if (has_T && m.instability_B[i] == 0 && m.instability_T_s[i] > 0 && b_node.IsDefined() == false)
        fail(t_node, t_key, "given without a B (bias instability) term");
      if (!(m.instability_T_s[i] > 0)) m.instability_T_s[i] = 3600.0;  // unused (no B on this axis)
    }
    const YAML::Node q = node["quantization"];
    if (q.IsDefined() && !q.IsNull()) {
      const std::string mode = q.IsScalar() ? q.Scalar() : "";
      if (mode == "rounding")
        m.quantization_rounding = true;
      else if (mode != "white")
        fail(q, name + ".quantization",
             "expected 'white' (the paper's Q: white error of the integrated quantity) or 'rounding' (ADC "
             "rounding of the running integral), found '" + mode + "'");
    }
    return m;
  }

  ImuGrade grade(const std::string& text, const std::string& default_name) const {
    YAML::Node root;
    try {
      root = YAML::Load(text);
    } catch (const YAML::ParserException& e) {
      throw InputError(file_, e.mark.line + 1, "YAML syntax error: " + e.msg);
    }
    if (!root.IsMap()) throw InputError(file_, 0, "expected a YAML mapping with 'gyro:' and/or 'accel:' (sim/README.md, Grade YAML)");
    const std::vector<std::string> known = {"name", "source", "gyro", "accel"};
    for (const auto& kv : root) {
      const std::string key = kv.first.as<std::string>();
      if (std::find(known.begin(), known.end(), key) != known.end()) continue;
      const std::string near = config::nearest_name(key, known);
      throw InputError(file_, line_of(kv.first),
                       "unknown key '" + key + "'" + (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                           "; known: " + list_of(known));
    }
    if (!root["gyro"] && !root["accel"]) throw InputError(file_, 0, "expected a 'gyro:' and/or an 'accel:' section");
    ImuGrade g;
    auto text_of = [&](const char* key, const std::string& fallback) {
      const YAML::Node n = root[key];
      if (!n.IsDefined() || n.IsNull()) return fallback;
      if (!n.IsScalar()) fail(n, key, "expected a text value");
      return n.Scalar();
    };
    g.name = text_of("name", default_name);
    g.source = text_of("source", "grade file " + file_);
    if (root["gyro"]) g.gyro = triad(root["gyro"], "gyro", gyro_terms());
    if (root["accel"]) g.accel = triad(root["accel"], "accel", accel_terms());
    return g;
  }

 private:
  std::string file_;
};

// ---- The typical grades (`hg1700-typical`, `hg1900-typical`, `3dm-gx2-typical`): datasheet-level values with
// in-run terms typical for the class, quantisation as ADC rounding of the running integral. Not the paper's
// numbers. The suite's engineering tests were tuned on them, and the physics tests that check the filter's
// consistency use them: the estimator does not model the paper's large gyro Q (nor the HG1700 gyro without any
// bias term, nor the 3DM-GX2 gyro Q as printed in degrees). No YAML form. ----
namespace typical {
// Engineering units -> SI, converted once here.
constexpr double kDegPerH = kDegToRad / 3600.0;            // deg/h -> rad/s
constexpr double kDegPerSqrtH = kDegToRad / 60.0;          // deg/sqrt(h) -> rad/sqrt(s)
constexpr double kDegPerHPerSqrtH = kDegPerH / 60.0;       // deg/h/sqrt(h) -> rad/s/sqrt(s)
constexpr double kDegPerHPerH = kDegPerH / 3600.0;         // deg/h/h -> rad/s^2
constexpr double kMg = 9.80665e-3;                         // mg -> m/s^2
constexpr double kMpsPerSqrtH = 1.0 / 60.0;                // m/s/sqrt(h) -> m/s/sqrt(s)
constexpr double kMpsPerHPerSqrtH = 1.0 / 3600.0 / 60.0;   // m/s/h/sqrt(h) -> m/s^2/sqrt(s)
constexpr double kMpsPerHH = 1.0 / 3600.0 / 3600.0;        // m/s/h^2 -> m/s^3
constexpr double kPpm = 1e-6;

Vec3 c(double v) { return Vec3::Constant(v); }

ImuGrade hg1700() {
  ImuGrade g;
  g.name = "hg1700-typical";
  g.source =
      "Honeywell HG1700-AG58 datasheet (gyro bias 1 deg/h, ARW 0.125 deg/sqrt(h), scale 150 ppm; accel bias 1 mg, "
      "VRW 0.0296 m/s/sqrt(h), scale 300 ppm); in-run B, K, R, Q: typical ring-laser tactical-grade values";
  g.gyro.white_N = c(0.125 * kDegPerSqrtH);
  g.gyro.quantization_Q = c(1.2e-6 / std::sqrt(12.0));  // angle LSB ~1.2e-6 rad
  g.gyro.instability_B = c(0.3 * kDegPerH);
  g.gyro.instability_T_s = c(1800.0);
  g.gyro.rate_rw_K = c(0.05 * kDegPerHPerSqrtH);
  g.gyro.ramp_R = Vec3(0.02, -0.015, 0.01) * kDegPerHPerH;
  g.gyro.turn_on_bias_std = c(1.0 * kDegPerH);
  g.gyro.scale_std = c(150 * kPpm);
  g.accel.white_N = c(0.0296 * kMpsPerSqrtH);
  g.accel.quantization_Q = c(1.9e-5 / std::sqrt(12.0));  // velocity LSB ~1.9e-5 m/s
  g.accel.instability_B = c(0.05 * kMg);
  g.accel.instability_T_s = c(1800.0);
  g.accel.rate_rw_K = c(0.02 * kMpsPerHPerSqrtH);
  g.accel.ramp_R = Vec3(0.01, -0.01, 0.02) * kMpsPerHH;
  g.accel.turn_on_bias_std = c(1.0 * kMg);
  g.accel.scale_std = c(300 * kPpm);
  g.gyro.quantization_rounding = g.accel.quantization_rounding = true;
  return g;
}

ImuGrade hg1900() {
  ImuGrade g;
  g.name = "hg1900-typical";
  g.source =
      "Honeywell HG1900 (MEMS gyro, tactical) datasheet-level values: gyro bias 2 deg/h, ARW 0.09 deg/sqrt(h), "
      "scale 150 ppm; accel bias 1 mg, VRW 0.05 m/s/sqrt(h), scale 300 ppm; in-run terms typical for the class";
  g.gyro.white_N = c(0.09 * kDegPerSqrtH);
  g.gyro.quantization_Q = c(1.2e-6 / std::sqrt(12.0));
  g.gyro.instability_B = c(0.6 * kDegPerH);
  g.gyro.instability_T_s = c(1000.0);
  g.gyro.rate_rw_K = c(0.1 * kDegPerHPerSqrtH);
  g.gyro.ramp_R = Vec3(0.05, -0.03, 0.04) * kDegPerHPerH;
  g.gyro.turn_on_bias_std = c(2.0 * kDegPerH);
  g.gyro.scale_std = c(150 * kPpm);
  g.accel.white_N = c(0.05 * kMpsPerSqrtH);
  g.accel.quantization_Q = c(1.9e-5 / std::sqrt(12.0));  // velocity LSB ~1.9e-5 m/s
  g.accel.instability_B = c(0.1 * kMg);
  g.accel.instability_T_s = c(1000.0);
  g.accel.rate_rw_K = c(0.04 * kMpsPerHPerSqrtH);
  g.accel.ramp_R = Vec3(0.02, -0.02, 0.03) * kMpsPerHH;
  g.accel.turn_on_bias_std = c(1.0 * kMg);
  g.accel.scale_std = c(300 * kPpm);
  g.gyro.quantization_rounding = g.accel.quantization_rounding = true;
  return g;
}

ImuGrade gx2() {
  ImuGrade g;
  g.name = "3dm-gx2-typical";
  g.source =
      "MicroStrain 3DM-GX2 datasheet-level values (consumer MEMS): gyro in-run bias instability 18 deg/h "
      "(0.005 deg/s), ARW 0.05 deg/sqrt(s) = 3 deg/sqrt(h), turn-on bias 0.2 deg/s, scale 0.5 %; accel bias "
      "10 mg, in-run 0.2 mg, VRW 0.1 m/s/sqrt(h), scale 0.5 %";
  g.gyro.white_N = c(3.0 * kDegPerSqrtH);
  g.gyro.quantization_Q = c(0.1 * kArcsec);  // 16-bit rate ADC integrated over a sample
  g.gyro.instability_B = c(18.0 * kDegPerH);
  g.gyro.instability_T_s = c(300.0);
  g.gyro.rate_rw_K = c(5.0 * kDegPerHPerSqrtH);
  g.gyro.ramp_R = Vec3(2.0, -1.5, 1.0) * kDegPerHPerH;
  g.gyro.turn_on_bias_std = c(0.2 * 3600.0 * kDegPerH);
  g.gyro.scale_std = c(5000 * kPpm);
  g.accel.white_N = c(0.1 * kMpsPerSqrtH);
  g.accel.quantization_Q = c(5e-5);
  g.accel.instability_B = c(0.2 * kMg);
  g.accel.instability_T_s = c(300.0);
  g.accel.rate_rw_K = c(0.3 * kMpsPerHPerSqrtH);
  g.accel.ramp_R = Vec3(0.5, -0.3, 0.4) * kMpsPerHH;
  g.accel.turn_on_bias_std = c(10.0 * kMg);
  g.accel.scale_std = c(5000 * kPpm);
  g.gyro.quantization_rounding = g.accel.quantization_rounding = true;
  return g;
}
}  // namespace typical

// ---- The named grades (`hg1700`, `hg1900`, `3dm-gx2`, `3dm-gx2-q-arcsec`): the paper's Tables 4-9 per axis as
// printed (absent terms absent), the turn-on bias, scale and non-orthogonality from Table 3's datasheets.
// tests/sim/test_grades.cpp checks every number against ../shared/data/paper/geo_ldv_tables.yaml. ----
// Each body without its `name:` line (builtin_text adds the name asked for).
const char* kHg1700Body = R"YAML(source: "Moafipoor et al. Table 5 (gyro Q+N) and Table 4 (accel Q+N+B+K) per axis; turn-on bias, scale and non-orthogonality from Table 3 (Honeywell HG1700-AG58 datasheet)"
gyro:                           # Table 5: Q + N (no B, K, R identified)
  Q_arcsec: [6.360, 7.853, 16.687]
  N_deg_sqrt_h: [0.041, 0.037, 0.045]
  turn_on_bias_deg_h: 1         # Table 3: bias repeatability
  scale_ppm: 150                # Table 3: scale factor linearity (no repeatability printed)
  non_orthogonality_urad: 100   # Table 3
accel:                          # Table 4: Q + N + B + K
  Q_m_h: [0.878, 0.540, 0.354]
  N_mps_sqrt_h: [0.004, 0.003, 0.003]
  B_mps_h: [0.090, 0.099, 0.065]
  B_time_constant_s: [96, 96, 288]
  K_mps_h_sqrt_h: [0.162, 0.458, 0.181]
  turn_on_bias_mg: 1.0          # Table 3: bias repeatability
  scale_ppm: 300                # Table 3: scale factor repeatability
  non_orthogonality_urad: 100   # Table 3
)YAML";

const char* kHg1900Body = R"YAML(source: "Moafipoor et al. Table 7 (gyro N+B+K) and Table 6 (accel Q+B+K+R) per axis; turn-on bias, scale and non-orthogonality from Table 3 (Honeywell HG1900-CA29 datasheet)"
gyro:                           # Table 7: N + B + K
  N_deg_sqrt_h: [0.045, 0.054, 0.04]
  B_deg_h: [0.514, 0.551, 0.421]
  B_time_constant_s: [192, 192, 192]
  K_deg_h_sqrt_h: [2.18, 3.126, 1.846]
  turn_on_bias_deg_h: 5         # Table 3: bias repeatability
  scale_ppm: 150                # Table 3: scale factor linearity (no repeatability printed)
  non_orthogonality_urad: 200   # Table 3
accel:                          # Table 6: Q + B + K + R (N "insignificant, 0.003 m/s/sqrt(h)": absent); Y has no R
  Q_m_h: [0.359, 0.315, 0.376]
  B_mps_h: [0.049, 0.027, 0.028]
  B_time_constant_s: [17, 28, 33]
  K_mps_h_sqrt_h: [0.618, 0.951, 0.817]
  R_mps_h2: [1.546, null, 0.03]
  turn_on_bias_mg: 1            # Table 3: bias repeatability
  scale_ppm: 300                # Table 3: scale factor repeatability
  non_orthogonality_urad: 100   # Table 3
)YAML";

// The 3DM-GX2: Table 9 prints the gyro Q in degrees (0.18-0.23). `3dm-gx2` takes it as printed; `3dm-gx2-q-arcsec`
// reads the same numbers as arcsec (what a 16-bit converter of the +-300 deg/s range gives: an LSB of 0.0092
// deg/s over a 10 ms sample is 0.33 arcsec, Q = LSB / sqrt(12) = 0.095 arcsec). Everything else is the same.
std::string gx2_text(const std::string& name, const std::string& q_key, const std::string& q_note) {
  return "name: " + name + "\n" +
         "source: \"Moafipoor et al. Table 9 (gyro Q+N+B+K, " + q_note +
         ") and Table 8 (accel Q+N+B+K) per axis; turn-on bias and scale from Table 3 (MicroStrain 3DM-GX2 "
         "datasheet, no non-orthogonality printed)\"\n" +
         "gyro:                           # Table 9: Q + N + B + K\n"
         "  " + q_key + ": [0.18, 0.23, 0.18]\n" +
         R"YAML(  N_deg_sqrt_h: [3.54, 4.23, 3.17]
  B_deg_h: [39.96, 58.16, 32.73]
  B_time_constant_s: [55, 72, 144]
  K_deg_h_sqrt_h: [198.63, 99.92, 136.03]
  turn_on_bias_deg_s: 0.2       # Table 3: bias repeatability
  scale_percent: 0.2            # Table 3: scale factor linearity
accel:                          # Table 8: Q + N + B + K
  Q_m_h: [0.02, 0.26, 1.52]
  N_mps_sqrt_h: [0.08, 0.07, 0.07]
  B_mps_h: [3.42, 3.62, 1.80]
  B_time_constant_s: [4.5, 9, 18]
  K_mps_h_sqrt_h: [13.56, 29.70, 5.70]
  turn_on_bias_g: 0.01          # Table 3: bias in-run stability (the only bias figure printed)
  scale_percent: 0.2            # Table 3: scale factor repeatability
)YAML";
}

// The paper's grades by name; the `-paper` names (and `3dmgx2`, `gx2`) are aliases. A `-paper` alias keeps the
// name asked for; `3dmgx2` and `gx2` are named `3dm-gx2`.
std::string builtin_text(const std::string& name) {
  if (name == "hg1700" || name == "hg1700-paper") return "name: " + name + "\n" + kHg1700Body;
  if (name == "hg1900" || name == "hg1900-paper") return "name: " + name + "\n" + kHg1900Body;
  if (name == "3dm-gx2" || name == "3dm-gx2-paper" || name == "3dmgx2" || name == "gx2")
    return gx2_text(name == "3dm-gx2-paper" ? name : "3dm-gx2", "Q_deg", "Q in degrees as printed");
  if (name == "3dm-gx2-q-arcsec" || name == "3dm-gx2-paper-q-arcsec")
    return gx2_text(name, "Q_arcsec", "the printed Q read as arcsec instead of degrees");
  return "";
}

bool looks_like_file(const std::string& name) {
  auto ends_with = [&](const std::string& s) {
    return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
  };
  return ends_with(".yaml") || ends_with(".yml") || name.find('/') != std::string::npos;
}
}  // namespace

std::vector<std::string> imu_grade_names() {
  return {"perfect",        "hg1700",         "hg1900",         "3dm-gx2", "3dm-gx2-q-arcsec",
          "hg1700-typical", "hg1900-typical", "3dm-gx2-typical"};
}

std::string builtin_grade_yaml(const std::string& name) { return builtin_text(name); }

ImuGrade parse_imu_grade_yaml(const std::string& text, const std::string& file) {
  return GradeReader(file).grade(text, file);
}

ImuGrade load_imu_grade_file(const std::string& path) {
  std::string text;
  try {
    text = read_small_text_file(path, static_cast<size_t>(1) << 20);
  } catch (const InputError& e) {
    throw InputError("--grade", 0, std::string("cannot read the grade file: ") + e.what());
  }
  return parse_imu_grade_yaml(text, path);
}

ImuGrade imu_grade(const std::string& name) {
  if (name == "perfect") {
    ImuGrade g;
    g.name = "perfect";
    g.source = "no sensor errors";
    return g;
  }
  if (name == "hg1700-typical") return typical::hg1700();
  if (name == "hg1900-typical") return typical::hg1900();
  if (name == "3dm-gx2-typical") return typical::gx2();
  const std::string text = builtin_grade_yaml(name);
  if (!text.empty()) return parse_imu_grade_yaml(text, "built-in grade " + name);
  if (looks_like_file(name)) return load_imu_grade_file(name);
  throw InputError("--grade", 0, "unknown IMU grade '" + name + "': expected one of " + list_of(imu_grade_names()) +
                                     ", or a grade YAML file (NAME.yaml)");
}

}  // namespace ldv::sim
