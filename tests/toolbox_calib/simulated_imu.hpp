#pragma once
// Simulated multi-position calibration logs with known truth (docs/effects.md sensor model): an initial
// static period, static poses at random orientations, and constant-rate rotations between them. Gravity
// from GeographicLib (earth::gravity_n), Earth rate from the WGS84 constant.
#include <random>

#include "common/geo/earth_model.hpp"
#include "common/formats/imu_calibration.hpp"
#include "toolbox/calib/imu_log.hpp"

namespace ldv::calib::testing {

struct SimulatedSensor {
  ImuCalibration truth;
  double accel_noise_mps2 = 0.01;     // per-sample white noise std
  double gyro_noise_rad_s = 1e-3;
  bool earth_rate = true;
};

struct SimulatedLogSpec {
  double lat_rad = 45.0 * kDegToRad, h_m = 100.0;
  double dt_s = 0.01;
  double init_static_s = 30.0;
  int poses = 24;
  double pose_s = 5.0;
  double motion_s = 2.0;
  std::vector<Mat3> orientations;  // C_b_n of the poses in order (then `poses` is their count); empty: random
};

struct SimulatedLog {
  ImuLog log;
  std::vector<std::pair<size_t, size_t>> pose_samples;  // [begin, end) of every static pose incl. the first
};

inline Mat3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Quat(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

inline SimulatedLog simulate_log(const SimulatedSensor& s, const SimulatedLogSpec& spec, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  const Vec3 g_n = earth::gravity_n(spec.lat_rad, spec.h_m);
  const Vec3 w_ie_n = earth::omega_ie_n(spec.lat_rad);
  const Mat3 Ma = s.truth.accel.sensor_matrix(), Mg = s.truth.gyro.sensor_matrix();
  SimulatedLog out;
  ImuLog& log = out.log;
  log.dt_s = spec.dt_s;
  log.source = "simulated";
  auto emit = [&](const Mat3& C_b_n, const Vec3& w_nb_b) {
    const Vec3 f_b = C_b_n.transpose() * (-g_n);
    const Vec3 w_b = w_nb_b + (s.earth_rate ? Vec3(C_b_n.transpose() * w_ie_n) : Vec3::Zero());
    const Vec3 nf(n01(rng), n01(rng), n01(rng)), nw(n01(rng), n01(rng), n01(rng));
    log.t_s.push_back(static_cast<double>(log.t_s.size()) * spec.dt_s);
    log.f_mps2.push_back(Ma * f_b + s.truth.accel.bias + s.accel_noise_mps2 * nf);
    log.w_rad_s.push_back(Mg * w_b + s.truth.gyro.bias + s.gyro_noise_rad_s * nw);
  };
  const int poses = spec.orientations.empty() ? spec.poses : static_cast<int>(spec.orientations.size());
  auto orientation = [&](int k) { return spec.orientations.empty() ? random_rotation(rng) : spec.orientations[k]; };
  Mat3 C = orientation(0);
  for (int k = 0; k < poses; ++k) {
    const double duration = k == 0 ? spec.init_static_s : spec.pose_s;
    const size_t begin = log.t_s.size();
    for (int i = 0; i < static_cast<int>(std::lround(duration / spec.dt_s)); ++i) emit(C, Vec3::Zero());
    out.pose_samples.emplace_back(begin, log.t_s.size());
    if (k + 1 == poses) break;
    // Rotate at constant body rate to the next orientation: C(t) = C Exp(phi t / T).
    const Mat3 C_next = orientation(k + 1);
    const Vec3 phi = rotvec_from_quat(Quat(C.transpose() * C_next));
    const int steps = static_cast<int>(std::lround(spec.motion_s / spec.dt_s));
    for (int i = 1; i <= steps; ++i) {
      const Mat3 C_t = C * quat_from_rotvec(phi * (static_cast<double>(i) / steps)).toRotationMatrix();
      emit(C_t, phi / spec.motion_s);
    }
    C = C_next;
  }
  return out;
}

// A sensor with every effect switched on, sized for its grade.
inline ImuCalibration truth_for_grade(bool tactical) {
  ImuCalibration t;
  t.accel.bias = Vec3(0.05, -0.08, 0.12);
  t.accel.scale = Vec3(2e-3, -1.5e-3, 3e-3);
  t.accel.misalignment_rad = Vec3(1e-3, -2e-3, 1.5e-3);
  if (tactical) {
    t.gyro.bias = Vec3(3.0, -2.0, 4.0) * kDegToRad / 3600.0;  // deg/h
    t.gyro.scale = Vec3(300e-6, -200e-6, 500e-6);
    t.gyro.misalignment_rad = Vec3(1e-4, -2e-4, 1.5e-4);
    t.gyro.frame_rotation_rad = Vec3(2e-3, -1e-3, 1.5e-3);
  } else {
    t.gyro.bias = Vec3(0.5, -0.8, 0.3) * kDegToRad;  // deg/s
    t.gyro.scale = Vec3(0.01, -0.02, 0.015);
    t.gyro.misalignment_rad = Vec3(5e-3, -4e-3, 6e-3);
    t.gyro.frame_rotation_rad = Vec3(8e-3, -6e-3, 5e-3);
  }
  return t;
}

}  // namespace ldv::calib::testing
