#pragma once
// The vehicle's motion as four smooth scalar schedules (channels) of run time t [s, from 0]:
// along-track acceleration, yaw rate, pitch and roll. Speed and yaw are their closed-form
// integrals, so velocity and attitude are exact at any time and only the position needs an ODE.
// The vehicle moves along its own x axis (no side slip), so v_n = speed * C_v_n * [1 0 0], unless a
// wheel slip is asked for. The IMU body may be mounted rotated in the vehicle (C_b_v): the schedules
// move the VEHICLE frame (x forward, y right, z down); the IMU point is the vehicle's reference point.
#include <vector>

#include "common/geo/geodetic.hpp"
#include "common/math/rotation.hpp"

namespace ldv::sim {

// A C2-continuous transition of a channel from `from` to `to` over [t0_s, t0_s + length_s]
// (quintic smootherstep 10u^3 - 15u^4 + 6u^5: value, slope and curvature continuous at both ends).
// length_s = 0 is a step (allowed, but the data then has a discontinuity).
struct Ramp {
  double t0_s = 0.0, length_s = 0.0, from = 0.0, to = 0.0;
};

class Channel {
 public:
  explicit Channel(double initial = 0.0) : initial_(initial) {}
  // Appends a transition to `to`; ramps must come in time order and must not overlap.
  void ramp_to(double t0_s, double length_s, double to);
  double final_value() const { return ramps_.empty() ? initial_ : ramps_.back().to; }
  double initial_value() const { return initial_; }
  const std::vector<Ramp>& ramps() const { return ramps_; }

  struct Sample {
    double value = 0.0;
    double rate = 0.0;      // d value / dt
    double integral = 0.0;  // integral of value from t = 0 to t
  };
  Sample at(double t_s) const;

 private:
  double initial_;
  std::vector<Ramp> ramps_;
  std::vector<double> integral_at_ramp_start_;
};

struct MotionStart {
  Geodetic pos;
  double yaw_rad = 0.0, pitch_rad = 0.0, roll_rad = 0.0;
  double speed_mps = 0.0;  // along body x; negative = reversing
};

struct MotionProfile {
  MotionStart start;
  Channel accel_mps2, yaw_rate_rad_s, pitch_rad, roll_rad;
  // 1 during coordinated turns: roll += atan(speed * yaw_rate / g0), the bank of zero side force
  // (switched only where the yaw rate is zero, so the roll stays smooth).
  Channel coordinated;
  double scheduled_s = 0.0;  // time covered by the scenario's segments

  // IMU body axes in the vehicle frame: v = C_b_v b, C_b_v = Rz(yaw) Ry(pitch) Rx(roll) of the mounting
  // angles. `mounted` false: the body is the vehicle frame (and the arithmetic is the original one).
  bool mounted = false;
  Mat3 C_b_v = Mat3::Identity();
  // Side slip on turns: the velocity leaves vehicle x by beta = -k * a_lat (a_lat = speed * yaw rate,
  // + right), i.e. the vehicle drifts to the outside of the turn. 0: no slip.
  double slip_rad_per_mps2 = 0.0;
};

// Kinematics at run time t, independent of position. rpy, omega_nb_b and C_b_n are the IMU body's
// (the vehicle's when not mounted); C_v_n and vehicle_rpy the vehicle's.
struct Kinematics {
  Vec3 rpy_rad = Vec3::Zero();          // IMU body; yaw unwrapped (continuous) when not mounted
  Vec3 vehicle_rpy_rad = Vec3::Zero();  // yaw unwrapped
  Vec3 vehicle_rpy_rate_rad_s = Vec3::Zero();
  double speed_mps = 0.0, accel_mps2 = 0.0;  // along the path (along vehicle x without slip)
  double slip_rad = 0.0;                     // angle from vehicle x to the velocity, about vehicle z
  Vec3 v_n_mps = Vec3::Zero();
  Vec3 dv_n_dt_mps2 = Vec3::Zero();   // time derivative of the NED velocity components
  Vec3 omega_nb_b_rad_s = Vec3::Zero();
  Vec3 omega_nv_v_rad_s = Vec3::Zero();
  Mat3 C_b_n = Mat3::Identity();
  Mat3 C_v_n = Mat3::Identity();
};
Kinematics kinematics_at(const MotionProfile& m, double t_s);

constexpr double kStandardGravity_mps2 = 9.80665;  // g0 of the coordinated-turn bank

}  // namespace ldv::sim
