#include "sim/vehicle_vibration.hpp"

#include <algorithm>
#include <cmath>

namespace ldv::sim {

double EngineFrequencyLaw::hz_at(double speed) const {
  return idle_hz + (max_hz - idle_hz) * std::min(std::abs(speed) / speed_at_max_mps, 1.0);
}

VehicleVibration::VehicleVibration(const VehicleRealism& r, const ImuGrade& grade, double dt, double speed0,
                                   uint64_t seed)
    : C_v_b_(r.C_b_v.transpose()), dt_(dt), white_(seed, "vibration_white") {
  const double extra = r.vibration_factor >= 1.0 ? std::sqrt(r.vibration_factor * r.vibration_factor - 1.0) : 0.0;
  white_gyro_ = grade.gyro.white_N * extra;
  white_accel_ = grade.accel.white_N * extra;
  // Mostly vertical shaking; the rotation mostly about the roll and pitch axes.
  accel_amp_v_ = Vec3(0.5, 0.5, 1.0) * r.engine_accel_mps2;
  gyro_amp_v_ = Vec3(1.0, 1.0, 0.5) * r.engine_gyro_rad_s;
  Rng phases(seed, "vibration_phase");
  for (int i = 0; i < 3; ++i) accel_phase_[i] = 2.0 * kPi * phases.uniform();
  for (int i = 0; i < 3; ++i) gyro_phase_[i] = 2.0 * kPi * phases.uniform();
  phase_ = 2.0 * kPi * phases.uniform();
  omega_prev_ = 2.0 * kPi * law().hz_at(speed0);
  antiderivatives(omega_prev_, vel_prev_v_, angle_prev_v_);
}

void VehicleVibration::antiderivatives(double omega, Vec3& vel_v, Vec3& angle_v) const {
  const double u = std::min(t_ / kRampUp_s, 1.0), ramp = u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
  for (int i = 0; i < 3; ++i) {
    vel_v[i] = -ramp * accel_amp_v_[i] / omega * std::cos(phase_ + accel_phase_[i]);
    angle_v[i] = -ramp * gyro_amp_v_[i] / omega * std::cos(phase_ + gyro_phase_[i]);
  }
}

void VehicleVibration::add(ImuIncrement& inc, double speed_end) {
  // The frequency follows the speed; the phase advances by its mean over the interval.
  const double omega = 2.0 * kPi * law().hz_at(speed_end);
  phase_ = std::fmod(phase_ + 0.5 * (omega_prev_ + omega) * dt_, 2.0 * kPi);
  t_ += dt_;
  omega_prev_ = omega;
  Vec3 vel_v, angle_v;
  antiderivatives(omega, vel_v, angle_v);
  inc.dvel_b_mps += C_v_b_ * (vel_v - vel_prev_v_);
  inc.dtheta_b_rad += C_v_b_ * (angle_v - angle_prev_v_);
  vel_prev_v_ = vel_v;
  angle_prev_v_ = angle_v;
  const double sqrt_dt = std::sqrt(dt_);
  for (int i = 0; i < 3; ++i) {
    const double ng = white_.normal(), na = white_.normal();  // both drawn always: one realisation per seed
    inc.dtheta_b_rad[i] += white_gyro_[i] * sqrt_dt * ng;
    inc.dvel_b_mps[i] += white_accel_[i] * sqrt_dt * na;
  }
}

}  // namespace ldv::sim
