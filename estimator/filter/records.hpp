#pragma once
// What the filter reports per measurement, and the optional observer hook through which
// `ldv diagnose` sees transition matrices, H and gains.
#include <Eigen/Core>

#include "estimator/effects/effect.hpp"
#include "estimator/update/sensor_names.hpp"

namespace ldv::est {

// One measurement's pre-update innovation (predicted minus measured) and its gate decision.
struct InnovationRecord {
  double t_s = 0.0;  // IMU-time epoch the measurement was applied at
  SensorName sensor = sensors::kGnssPosition;
  // z_hat - z, one row per measured component: NED [m] for GNSS position, NED [m/s] for GNSS velocity and
  // ZUPT, vehicle-frame [m/s] for the aids (nhc: lateral, vertical; odometer: forward), body [rad/s] for ZARU.
  Eigen::VectorXd innovation = Eigen::VectorXd::Zero(3);
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(3, 3);  // innovation covariance H P H^T + R
  double nis = 0.0;                // innovation^T S^-1 innovation
  bool accepted = true;
  // The factor on R the update used: 1 within the gate; > 1 for a measurement beyond it that the robust
  // update kept with less weight (its effective S is H P H^T + noise_scale R).
  double noise_scale = 1.0;
  bool replayed = false;  // recomputed while re-processing a late measurement
  // A measurement counts as used when applied with at least a quarter of its weight; beyond that the
  // robust update kept only a trace of it (an outlier), which counts as a gate rejection.
  static constexpr double kMaxNoiseScaleUsed = 4.0;
  bool used() const { return accepted && noise_scale <= kMaxNoiseScaleUsed; }
};

class FilterObserver {
 public:
  virtual ~FilterObserver() = default;
  // Whether on_propagation / on_update should receive dense matrices (costs time).
  virtual bool wants_matrices() const { return false; }
  // Covariance propagation over (t_s - dt_s, t_s]: P+ = Phi P Phi^T + Qd. Also an instant change (dt_s = 0,
  // Phi = I): the variance a re-synchronisation opens before its update.
  virtual void on_propagation(double t_s, double dt_s, const Eigen::MatrixXd& Phi, const Eigen::MatrixXd& Qd) {}
  // The filter goes on from t_s (its covariance epoch) with covariance P that does not follow from what the
  // observer saw before: initialize (also after restart, possibly earlier than what was seen), a covariance
  // reset, a state reset to the last healthy state, a rewind to a snapshot for a late reading. What was seen
  // after t_s is void.
  virtual void on_restart(double t_s, const Eigen::MatrixXd& P) {}
  // A measurement: its record, H (rows x n) and gain K (n x rows; zero when rejected).
  virtual void on_update(const InnovationRecord& r, const Eigen::MatrixXd& H, const Eigen::MatrixXd& K) {}
};

}  // namespace ldv::est
