#pragma once
// IMU grade presets: the stochastic terms of the paper's eq. 12 / the Allan model per axis, plus the
// run-to-run constants (turn-on bias, scale factor) drawn once per run. SI units of the *rate*
// inside: gyro rad/s, accel m/s^2 (so N is [rad/s/sqrt(Hz)] = [rad/sqrt(s)], K [rad/s/sqrt(s)], ...).
#include <string>
#include <vector>

#include "common/math/rotation.hpp"

namespace ldv::sim {

struct TriadErrorModel {
  Vec3 white_N = Vec3::Zero();            // angle / velocity random walk [u/sqrt(s)], u = rate unit
  Vec3 quantization_Q = Vec3::Zero();     // [u*s] (rad or m/s): std of the quantisation error of the integral
  Vec3 instability_B = Vec3::Zero();      // bias instability as Gauss-Markov: stationary sigma [u]
  Vec3 instability_T_s = Vec3::Constant(3600.0);  // its correlation time [s]
  Vec3 rate_rw_K = Vec3::Zero();          // rate random walk [u/sqrt(s)]
  Vec3 ramp_R = Vec3::Zero();             // rate ramp [u/s]
  Vec3 sinusoid_amplitude = Vec3::Zero(); // [u]
  Vec3 sinusoid_hz = Vec3::Zero();
  Vec3 turn_on_bias_std = Vec3::Zero();   // constant bias drawn per run [u]
  Vec3 scale_std = Vec3::Zero();          // constant scale-factor error drawn per run [-]
};

struct ImuGrade {
  std::string name;
  std::string source;  // where the numbers come from
  TriadErrorModel gyro;   // rate unit rad/s
  TriadErrorModel accel;  // rate unit m/s^2
};

// Throws InputError (file "--grade") listing the known names.
ImuGrade imu_grade(const std::string& name);
std::vector<std::string> imu_grade_names();

}  // namespace ldv::sim
