#pragma once
// What the car's vibration adds to the increments of an installed IMU (a sensor-error term: the
// micrometre motion it comes from is not in the truth):
//  - broadband white vibration: the installed white noise is `factor` x the grade's ARW / VRW, so the
//    vibration adds density N sqrt(factor^2 - 1) per body axis (stream "vibration_white");
//  - engine harmonics in vehicle axes, at a frequency rising with speed (idle 25 Hz to 70 Hz at 30 m/s):
//    accel a_i(t) = A_i sin(phi(t) + phi_i), rate w_i(t) = G_i sin(phi(t) + psi_i). Each increment is the
//    exact integral over the IMU interval, the difference of the antiderivative -A_i/omega cos(..) at its
//    ends, so the sampled sensor aliases the harmonic as a real one does and the sum of the increments
//    stays bounded (|sum| <= 2 A / omega). The amplitude ramps up over the first second (smootherstep), so
//    the antiderivative starts at zero and the velocity and attitude errors it causes have zero mean:
//    no bias in the navigation.
#include <cstdint>

#include "common/formats/nav_types.hpp"
#include "sim/imu_grade.hpp"
#include "sim/random.hpp"
#include "sim/vehicle_realism.hpp"

namespace ldv::sim {

struct EngineFrequencyLaw {
  double idle_hz = 25.0, max_hz = 70.0, speed_at_max_mps = 30.0;
  double hz_at(double speed_mps) const;
};

class VehicleVibration {
 public:
  // `speed0_mps`: speed at run time 0.
  VehicleVibration(const VehicleRealism& r, const ImuGrade& grade, double dt_s, double speed0_mps, uint64_t seed);
  // Adds the vibration over the next IMU interval (ending at speed `speed_end_mps`) to `inc` (IMU body).
  void add(ImuIncrement& inc, double speed_end_mps);

  static EngineFrequencyLaw law() { return {}; }
  static constexpr double kRampUp_s = 1.0;  // the engine harmonic's amplitude ramp at the start

 private:
  void antiderivatives(double omega, Vec3& vel_v, Vec3& angle_v) const;
  Mat3 C_v_b_;
  double dt_, t_ = 0.0;
  Vec3 white_gyro_, white_accel_;  // added densities, body axes [u/sqrt(s)]
  Vec3 accel_amp_v_, gyro_amp_v_;  // vehicle axes
  Vec3 accel_phase_, gyro_phase_;
  double phase_ = 0.0, omega_prev_ = 0.0;
  Vec3 vel_prev_v_ = Vec3::Zero(), angle_prev_v_ = Vec3::Zero();
  Rng white_;
};

}  // namespace ldv::sim
