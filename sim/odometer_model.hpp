#pragma once
// The odometer: forward speed of the odometer point (rear-axle centre, `lever_arm_b_m` from the IMU in
// IMU body axes) along the VEHICLE x axis, at the instant of each sample on the GPS-time grid of the rate
// (true GPS time: no IMU latency), times (1 + scale), plus white noise (stream "odometer_white"),
// optionally rounded to a resolution.
#include <cstdint>
#include <vector>

#include "common/formats/odometer_text.hpp"
#include "sim/motion_profile.hpp"
#include "sim/truth_sample.hpp"

namespace ldv::sim {

struct OdometerModel {
  double rate_hz = 50.0;
  Vec3 lever_arm_b_m = Vec3::Zero();
  double scale = 0.0;        // fraction (0.005 = 0.5 %)
  double noise_mps = 0.02;   // white, std per sample
  double quantum_mps = 0.0;  // 0: no rounding
  bool with_noise = true;
};

// The true forward speed of the odometer point at run time t (no scale, no noise).
double odometer_true_speed_at(const MotionProfile& m, const std::vector<TruthSample>& truth, double dt_s, double t_s,
                              const Vec3& lever_arm_b_m);

std::vector<OdometerSample> simulate_odometer(const MotionProfile& m, const std::vector<TruthSample>& truth,
                                              double dt_s, const OdometerModel& model, uint64_t seed);

}  // namespace ldv::sim
