#pragma once
// Exact truth and exact IMU increments from a motion profile.
// The position ODE (lat, lon, h) is integrated with RK4 on sub-steps; between sub-step ends the
// position is a cubic Hermite interpolant. The increments are Gauss-Legendre (3-point, order 6)
// quadratures of omega_ib_b and f_b over each sub-step, with
//   f_b      = C_n_b (dv_n/dt + (2 w_ie_n + w_en_n) x v_n - g_n)        (g_n: normal gravity + anomaly)
//   omega_ib = omega_nb_b + C_n_b (w_ie_n + w_en_n).
#include <functional>
#include <vector>

#include "common/formats/nav_types.hpp"
#include "sim/motion_profile.hpp"
#include "sim/truth_sample.hpp"

namespace ldv::sim {

struct TruthOptions {
  double t0_sow_s = 0.0;  // GPS seconds of week of run time 0
  double dt_s = 0.005;    // IMU interval
  size_t intervals = 0;   // number of IMU increments
  int substeps = 2;       // RK4 / quadrature sub-steps per IMU interval
  bool with_squares = false;                           // also integrate w_i^2 and f_i^2 (nonlinear scale)
  const std::vector<Vec3>* gravity_anomaly_n = nullptr;  // per interval [m/s^2], true minus normal gravity
};

struct TruthRun {
  std::vector<TruthSample> truth;          // intervals + 1 samples, at t0 + k dt
  std::vector<ImuIncrement> increments;    // exact, error-free increments over (t_{k-1}, t_k]
  std::vector<Vec3> omega_sq_integral;     // integral of omega_ib_b^2 per axis [rad^2/s] (if with_squares)
  std::vector<Vec3> f_sq_integral;         // integral of f_b^2 per axis [m^2/s^3] (if with_squares)
};

TruthRun integrate_truth(const MotionProfile& motion, const TruthOptions& opt,
                         const std::function<void(double)>& progress = {});

// What a perfect IMU senses at run time t at position lla = (lat [rad], lon [rad], h [m]).
struct Sensed {
  Vec3 omega_ib_b_rad_s, f_b_mps2;
};
Sensed sensed_at(const Kinematics& k, const Vec3& lla, const Vec3& gravity_anomaly_n_mps2);

// d(lat, lon, h)/dt for NED velocity v_n.
Vec3 lla_rate(const Vec3& lla, const Vec3& v_n_mps);

}  // namespace ldv::sim
