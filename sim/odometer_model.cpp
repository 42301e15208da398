#include "sim/odometer_model.hpp"

#include <cmath>

#include "sim/gnss_model.hpp"
#include "sim/random.hpp"

namespace ldv::sim {

double odometer_true_speed_at(const MotionProfile& m, const std::vector<TruthSample>& truth, double dt, double t,
                              const Vec3& lever_b) {
  // The odometer point moves with the body like the antenna does: same rigid-body velocity.
  const Vec3 v_point_n = antenna_truth_at(m, truth, dt, t, lever_b).vel_n_mps;
  return (kinematics_at(m, t).C_v_n.transpose() * v_point_n).x();
}

std::vector<OdometerSample> simulate_odometer(const MotionProfile& m, const std::vector<TruthSample>& truth, double dt,
                                              const OdometerModel& od, uint64_t seed) {
  std::vector<OdometerSample> out;
  Rng white(seed, "odometer_white");
  const double t0_sow = truth.front().t_s, t_end = truth.back().t_s - t0_sow;
  const long first = static_cast<long>(std::ceil(t0_sow * od.rate_hz - 1e-9));
  const long last = static_cast<long>(std::floor((t0_sow + t_end) * od.rate_hz + 1e-9));
  for (long j = first; j <= last; ++j) {
    const double t_sow = static_cast<double>(j) / od.rate_hz;
    const double t = std::min(std::max(t_sow - t0_sow, 0.0), t_end);
    double speed = odometer_true_speed_at(m, truth, dt, t, od.lever_arm_b_m) * (1.0 + od.scale);
    if (od.with_noise) speed += od.noise_mps * white.normal();
    if (od.quantum_mps > 0.0) speed = od.quantum_mps * std::round(speed / od.quantum_mps);
    out.push_back({t_sow, speed + 0.0});  // + 0 turns -0 into 0 for the text
  }
  return out;
}

}  // namespace ldv::sim
