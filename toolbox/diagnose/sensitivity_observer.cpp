#include "toolbox/diagnose/sensitivity_observer.hpp"

#include "common/geo/earth_model.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/state/state_layout.hpp"
#include "estimator/update/gyro_coupling.hpp"

namespace ldv::diag {

using est::kAtt;
using est::kVel;
using est::Mat3X;

SensitivityRecord SensitivityRecord::from(const est::InnovationRecord& r) {
  SensitivityRecord rec;
  rec.t_s = r.t_s;
  rec.sensor = r.sensor;
  rec.innovation = r.innovation;
  rec.S = r.S;
  rec.nis = r.nis;
  rec.accepted = r.accepted;
  rec.used = r.used();
  return rec;
}

SensitivityObserver::SensitivityObserver(const est::NavFilter& filter, const CandidateSet& candidates)
    : filter_(filter), set_(candidates) {
  Psi_ = Eigen::MatrixXd::Zero(filter.layout().size(), set_.columns);
  Gamma_ = Eigen::Matrix<double, 9, Eigen::Dynamic>::Zero(9, set_.columns);
}

void SensitivityObserver::on_imu_epoch() {
  const est::NavState& s = filter_.state();
  if (last_t_s_ < 0.0 || s.t_s <= last_t_s_) {
    last_t_s_ = s.t_s;
    return;
  }
  const double dt = s.t_s - last_t_s_;
  last_t_s_ = s.t_s;
  const est::MechanizationStep& st = filter_.last_step();
  est::LinearizationPoint lp;
  lp.C_b_n = s.C_b_n();
  lp.omega_ib_b_rad_s = st.omega_ib_b_rad_s;
  lp.f_b_mps2 = st.f_b_mps2;
  const Mat3 Cdt = lp.C_b_n * dt;
  for (const Candidate& c : set_.candidates) {
    const est::Effect& e = *c.effect;
    const bool g = e.drives_gyro(), a = e.drives_accel();
    if (g || a) {
      J_gyro_ = Mat3X::Zero(3, c.dim);
      J_accel_ = Mat3X::Zero(3, c.dim);
      e.imu_jacobians(lp, J_gyro_, J_accel_);
      // Same couplings as the filter's F: d(phi)/dt = -C_b_n delta_w, d(delta_v)/dt = C_b_n delta_f.
      if (g) Gamma_.block(kAtt, c.column, 3, c.dim).noalias() -= Cdt * J_gyro_;
      if (a) Gamma_.block(kVel, c.column, 3, c.dim).noalias() += Cdt * J_accel_;
    }
    if (e.drives_velocity_n()) {
      Mat3X J = Mat3X::Zero(3, c.dim);
      e.velocity_n_jacobian(J);
      Gamma_.block(kVel, c.column, 3, c.dim) += J * dt;
    }
  }
}

void SensitivityObserver::on_propagation(double t_s, double, const Eigen::MatrixXd& Phi, const Eigen::MatrixXd&) {
  Psi_ = Phi * Psi_;
  // Gamma was accumulated along the step: half a step of the navigation error dynamics acts on it
  // (the filter's Phi_ne = B + A B / 2 with A ~ Phi_nn - I).
  const Eigen::Matrix<double, 9, 9> half = 0.5 * (Phi.topLeftCorner<9, 9>() + Eigen::Matrix<double, 9, 9>::Identity());
  Psi_.topRows<9>() += half * Gamma_;
  Gamma_.setZero();
  constexpr double kKeep_s = 4.0;  // beyond the filter's retraction history (2.5 s) and late-fix horizon (3 s)
  std::erase_if(kept_, [&](const Kept& k) { return k.t_s < t_s - kKeep_s; });
  kept_.push_back({t_s, Psi_, Gamma_});
}

void SensitivityObserver::on_restart(double t_s, const Eigen::MatrixXd&) {
  std::erase_if(records_, [&](const SensitivityRecord& r) { return r.t_s > t_s + 1e-9; });
  while (!kept_.empty() && kept_.back().t_s > t_s + 1e-9) kept_.pop_back();
  if (!kept_.empty()) Psi_ = kept_.back().Psi, Gamma_ = kept_.back().Gamma;
  last_t_s_ = std::min(last_t_s_, t_s);
}

void SensitivityObserver::on_update(const est::InnovationRecord& r, const Eigen::MatrixXd& H,
                                    const Eigen::MatrixXd& K) {
  // Linearisation point at the measurement epoch (the state was just corrected: a negligible change).
  const est::LinearizationPoint lp = filter_.linearization_point();
  SensitivityRecord rec = SensitivityRecord::from(r);
  rec.s = H * Psi_;                                                  // rows x P
  const Eigen::MatrixXd G = est::gyro_error_coupling(r.sensor, lp);  // a gyro error enters directly
  for (const Candidate& c : set_.candidates) {
    const est::Effect& e = *c.effect;
    if (e.enters(r.sensor)) {
      Eigen::MatrixXd Hc = Eigen::MatrixXd::Zero(H.rows(), c.dim);
      e.measurement_jacobian(r.sensor, lp, Hc);
      rec.s.middleCols(c.column, c.dim) += Hc;
    }
    if (G.rows() > 0 && e.drives_gyro()) {
      J_gyro_ = Mat3X::Zero(3, c.dim);
      J_accel_ = Mat3X::Zero(3, c.dim);
      e.imu_jacobians(lp, J_gyro_, J_accel_);
      rec.s.middleCols(c.column, c.dim) += G * J_gyro_;
    }
  }
  if (r.accepted) Psi_.noalias() -= K * rec.s;
  records_.push_back(std::move(rec));
}

}  // namespace ldv::diag
