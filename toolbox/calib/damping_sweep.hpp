#pragma once
// The paper's damping constant EV (eq. 13-14): a ridge (N_s + EV I) on the standardised normal matrix.
// Sweeping EV from 0 to 0.4 shows the trade-off: the largest eigenvalue of the parameter covariance falls
// (ill-determined directions are pulled to the nominal sensor) while the residual and the bias grow.
// The chosen EV minimises the estimated mean-square error, trace(covariance) + |bias|^2 in standardised
// units, with the bias estimated as the shift from the undamped solution (Hoerl-Kennard style): a well
// determined problem gets EV = 0, an ill-conditioned one gets the damping it needs.
#include <vector>

#include "toolbox/calib/gauss_helmert.hpp"

namespace ldv::calib {

struct DampingPoint {
  double ev = 0.0;
  double max_cov_eigenvalue = 0.0;  // of the standardised a posteriori covariance
  double sigma0 = 0.0;              // of the damped solution (residual grows with EV)
  double rms_misclosure = 0.0;      // in the condition's units (m/s^2 for gravity)
  double mse = 0.0;                 // standardised trace(cov) + |bias|^2
  VectorXd x;
  VectorXd bias;                    // x(EV) - x(0): what the damping adds
};

struct DampingSweep {
  std::vector<DampingPoint> points;
  int chosen = 0;
  const DampingPoint& best() const { return points[chosen]; }
};

// 0, then 1e-4 ... 5e-3 (so small EVs are resolved), then 0.01 ... 0.4 in steps of 0.01.
std::vector<double> default_ev_grid();

DampingSweep sweep_damping(const ConditionModel& model, const std::vector<ConditionBlock>& blocks, const VectorXd& x0,
                           const std::vector<double>& grid);

}  // namespace ldv::calib
