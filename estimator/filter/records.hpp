#pragma once
// What the filter reports per measurement, and the optional observer hook through which
// `ldv diagnose` sees transition matrices, H and gains.
#include <Eigen/Core>

#include "estimator/effects/effect.hpp"

namespace ldv::est {

const char* measurement_name(MeasurementKind k);

// One measurement's pre-update innovation (predicted minus measured) and its gate decision.
struct InnovationRecord {
  double t_s = 0.0;  // IMU-time epoch the measurement was applied at
  MeasurementKind kind = MeasurementKind::kGnssPosition;
  Vec3 innovation = Vec3::Zero();  // z_hat - z: NED [m] for position, [m/s] for velocities
  Mat3 S = Mat3::Zero();           // innovation covariance H P H^T + R
  double nis = 0.0;                // innovation^T S^-1 innovation
  bool accepted = true;
  // The factor on R the update used: 1 within the gate; > 1 for a measurement beyond it that the robust
  // update kept with less weight (its effective S is H P H^T + noise_scale R).
  double noise_scale = 1.0;
  bool replayed = false;
  // A measurement counts as used when applied with at least a quarter of its weight; beyond that the
  // robust update kept only a trace of it (an outlier), which counts as a gate rejection.
  static constexpr double kMaxNoiseScaleUsed = 4.0;
  bool used() const { return accepted && noise_scale <= kMaxNoiseScaleUsed; }           // recomputed while re-processing a late measurement
};

class FilterObserver {
 public:
  virtual ~FilterObserver() = default;
  // Whether on_propagation / on_update should receive dense matrices (costs time).
  virtual bool wants_matrices() const { return false; }
  // Covariance propagation over (t_s - dt_s, t_s]: P+ = Phi P Phi^T + Qd.
  virtual void on_propagation(double t_s, double dt_s, const Eigen::MatrixXd& Phi, const Eigen::MatrixXd& Qd) {}
  // A measurement: its record, H (3 x n) and gain K (n x 3; zero when rejected).
  virtual void on_update(const InnovationRecord& r, const Eigen::MatrixXd& H, const Eigen::MatrixXd& K) {}
};

}  // namespace ldv::est
