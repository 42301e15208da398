#pragma once
// IMU grades: the stochastic terms of the paper's eq. 12 / the Allan model per axis, plus the run-to-run
// constants (turn-on bias, scale factor, non-orthogonality) drawn once per run. SI units of the *rate*
// inside: gyro rad/s, accel m/s^2 (so N is [rad/s/sqrt(Hz)] = [rad/sqrt(s)], K [rad/s/sqrt(s)], ...).
//
// A grade is written in YAML in the paper's units (sim/README.md, "Grades"; example: sim/grades/example.yaml).
// The named grades `hg1700`, `hg1900`, `3dm-gx2` are the paper's (Tables 4-9 per axis as printed, the 3DM-GX2 gyro
// Q in degrees, and Table 3's datasheets; `3dm-gx2-q-arcsec` reads that Q as arcsec): YAML texts compiled into
// imu_grade.cpp, read by the same parser as a user's file (tests/sim/test_grades.cpp checks every value against
// ../shared/data/paper/geo_ldv_tables.yaml). Aliases: `hg1700-paper`, `hg1900-paper`, `3dm-gx2-paper`, `3dmgx2`,
// `gx2`, `3dm-gx2-paper-q-arcsec`. `hg1700-typical`, `hg1900-typical`, `3dm-gx2-typical` are datasheet-level
// stand-ins with typical in-run terms, the ones the engineering and filter-consistency tests use (sim/README.md).
#include <string>
#include <vector>

#include "common/math/rotation.hpp"

namespace ldv::sim {

struct TriadErrorModel {
  Vec3 white_N = Vec3::Zero();            // angle / velocity random walk [u/sqrt(s)], u = rate unit
  // The paper's Q [u*s] (rad or m/s): an additive white error of std Q on the integrated quantity (each
  // increment gets e_k - e_{k-1}; Allan deviation Q sqrt(3) / tau). With quantization_rounding: the running
  // integral is rounded to the step Q sqrt(12) instead (a true ADC; white only when dithered).
  Vec3 quantization_Q = Vec3::Zero();
  bool quantization_rounding = false;
  Vec3 instability_B = Vec3::Zero();      // bias instability as Gauss-Markov: stationary sigma [u]
  Vec3 instability_T_s = Vec3::Constant(3600.0);  // its correlation time [s] (per axis)
  Vec3 rate_rw_K = Vec3::Zero();          // rate random walk [u/sqrt(s)]
  Vec3 ramp_R = Vec3::Zero();             // rate ramp [u/s]
  Vec3 sinusoid_amplitude = Vec3::Zero(); // [u]
  Vec3 sinusoid_hz = Vec3::Zero();
  Vec3 turn_on_bias_std = Vec3::Zero();   // constant bias drawn per run [u]
  Vec3 scale_std = Vec3::Zero();          // constant scale-factor error drawn per run [-]
  Vec3 non_orthogonality_std = Vec3::Zero();  // m of the symmetric N(m) (docs/effects.md) drawn per run [rad]
};

struct ImuGrade {
  std::string name;
  std::string source;  // where the numbers come from
  TriadErrorModel gyro;   // rate unit rad/s
  TriadErrorModel accel;  // rate unit m/s^2
};

// A built-in name (imu_grade_names()) or a grade YAML file (a NAME ending in .yaml / .yml or containing '/').
// Throws InputError: file "--grade" listing the known names, or FILE:LINE naming the key for a bad file.
ImuGrade imu_grade(const std::string& name);
std::vector<std::string> imu_grade_names();

// A grade YAML file (sim/README.md, "Grade YAML"). Errors name the file, the line and the key.
ImuGrade load_imu_grade_file(const std::string& path);
// The same from text; `file` names it in errors.
ImuGrade parse_imu_grade_yaml(const std::string& text, const std::string& file);
// The YAML text of a built-in grade ("" for an unknown name, "perfect" and the `-typical` grades): what
// `ldv sim --print-grade` prints.
std::string builtin_grade_yaml(const std::string& name);

}  // namespace ldv::sim
