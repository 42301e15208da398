#pragma once
// Carries every candidate's sensitivity through the filter's own transition matrices and gains, in
// the same pass as the filter (the "consider state" recursion of a score test):
//   candidate error e = assumed - true (the filter's error convention: estimate minus truth)
//   propagation  Psi <- Phi Psi + Gamma     Gamma = how e drives the navigation error over the step
//   measurement  s = H Psi + H_e            (E[innovation] = s e, innovation = z_hat - z)
//                Psi <- Psi - K s           (the filter's correction also absorbs part of e)
// Psi is n x P (n = the model's full error state, P = all candidate parameters).
#include <Eigen/Core>
#include <vector>

#include "estimator/filter/records.hpp"
#include "toolbox/diagnose/candidates.hpp"

namespace ldv::est {
class NavFilter;  // nav_filter.hpp (watched, never held)
}

namespace ldv::diag {

// One measurement as the diagnosis needs it: pre-gate innovation, its covariance, and its sensitivity.
struct SensitivityRecord {
  double t_s = 0.0;
  est::SensorName sensor = est::sensors::kGnssPosition;
  Eigen::VectorXd innovation;  // z_hat - z, the measurement's rows
  Eigen::MatrixXd S;
  double nis = 0.0;
  bool accepted = true;  // applied to the state (the robust update may apply an outlier with a trace of weight)
  bool used = true;      // applied with at least a quarter of its weight (est::InnovationRecord::used)
  Eigen::MatrixXd s;     // d(innovation)/d(e), rows x P

  // The filter's record of a measurement, without sensitivities.
  static SensitivityRecord from(const est::InnovationRecord& r);
};

class SensitivityObserver final : public est::FilterObserver {
 public:
  SensitivityObserver(const est::NavFilter& filter, const CandidateSet& candidates);

  bool wants_matrices() const override { return true; }
  void on_propagation(double t_s, double dt_s, const Eigen::MatrixXd& Phi, const Eigen::MatrixXd& Qd) override;
  void on_update(const est::InnovationRecord& r, const Eigen::MatrixXd& H, const Eigen::MatrixXd& K) override;
  // The filter goes back to t_s (an edge fix undone, a late fix): the records after it are void and the
  // sensitivities are taken back to what they were then (kept for a few seconds); further back, they go on.
  void on_restart(double t_s, const Eigen::MatrixXd& P) override;
  // Call after every IMU sample (RunCallbacks::on_epoch): accumulates Gamma at the filter's own
  // compensated rate, specific force and attitude.
  void on_imu_epoch();

  const std::vector<SensitivityRecord>& records() const { return records_; }

 private:
  const est::NavFilter& filter_;
  const CandidateSet& set_;
  Eigen::MatrixXd Psi_;                             // n x P
  Eigen::Matrix<double, 9, Eigen::Dynamic> Gamma_;  // 9 x P, accumulated since the last propagation
  est::Mat3X J_gyro_, J_accel_;
  double last_t_s_ = -1.0;
  std::vector<SensitivityRecord> records_;
  struct Kept {
    double t_s;
    Eigen::MatrixXd Psi;
    Eigen::Matrix<double, 9, Eigen::Dynamic> Gamma;
  };
  std::vector<Kept> kept_;  // Psi after each propagation of the last seconds, for on_restart
};

}  // namespace ldv::diag
