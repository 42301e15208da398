#include "toolbox/calib/damping_sweep.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace ldv::calib {

std::vector<double> default_ev_grid() {
  std::vector<double> g = {0.0, 1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3};
  for (int i = 1; i <= 40; ++i) g.push_back(0.01 * i);
  return g;
}

namespace {
double rms_of_norms(const std::vector<VectorXd>& w) {
  double s = 0.0;
  size_t n = 0;
  for (const VectorXd& v : w) {
    s += v.squaredNorm();
    n += v.size();
  }
  return n ? std::sqrt(s / n) : 0.0;
}
}  // namespace

DampingSweep sweep_damping(const ConditionModel& model, const std::vector<ConditionBlock>& blocks, const VectorXd& x0,
                           const std::vector<double>& grid) {
  DampingSweep sweep;
  GaussHelmertOptions opt;
  opt.ev = 0.0;
  const GaussHelmertResult undamped = solve_gauss_helmert(model, blocks, x0, opt);
  // Standardise with the undamped normal matrix so every EV is measured in the same units.
  VectorXd d = undamped.N.diagonal();
  for (int i = 0; i < d.size(); ++i) d[i] = d[i] > 0.0 ? std::sqrt(d[i]) : 1.0;
  const double s0 = std::isfinite(undamped.sigma0) ? undamped.sigma0 : 1.0;
  VectorXd x_start = undamped.x;
  for (double ev : grid) {
    opt.ev = ev;
    const GaussHelmertResult r = ev == 0.0 ? undamped : solve_gauss_helmert(model, blocks, x_start, opt);
    x_start = r.x;
    DampingPoint p;
    p.ev = ev;
    p.x = r.x;
    p.bias = r.x - undamped.x;
    p.sigma0 = r.sigma0;
    p.rms_misclosure = rms_of_norms(r.misclosure);
    const MatrixXd cov_z = s0 * s0 * d.asDiagonal() * r.cov_x_apriori * d.asDiagonal();
    p.max_cov_eigenvalue = Eigen::SelfAdjointEigenSolver<MatrixXd>(cov_z).eigenvalues().maxCoeff();
    p.mse = cov_z.trace() + d.cwiseProduct(p.bias).squaredNorm();
    sweep.points.push_back(p);
  }
  for (size_t i = 1; i < sweep.points.size(); ++i)
    if (sweep.points[i].mse < sweep.points[sweep.chosen].mse) sweep.chosen = static_cast<int>(i);
  return sweep;
}

}  // namespace ldv::calib
