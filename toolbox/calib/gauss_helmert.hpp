#pragma once
// Gauss-Helmert adjustment (condition equations with unknowns, f(l + v, x) = 0): observations l with their
// own covariance, conditions that mix observations and unknowns (e.g. |S^-1 (f_meas - b)| = g), iterated
// to convergence with the linearisation point moved to the adjusted observations. Optional damping in the
// standardised parameters (the paper's EV, eq. 13-14): (N_s + EV I) pulls the solution towards the nominal
// sensor (x = 0) along the directions the data cannot see, at the price of a bias.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ldv::calib {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// One group of conditions that share observations (a pose, or a pair of poses).
struct ConditionBlock {
  VectorXd l;        // observations
  MatrixXd Sigma_l;  // their covariance
  MatrixXd Q_extra;  // covariance of the conditions from noise not carried by l (empty = none)
};

class ConditionModel {
 public:
  virtual ~ConditionModel() = default;
  virtual int num_params() const = 0;
  virtual std::vector<std::string> param_names() const = 0;
  // Size of the parameter each unknown may physically take (for the observability check): a parameter
  // whose sigma exceeds it is not resolved by these data.
  virtual VectorXd param_ranges() const = 0;
  // Misclosure f(l, x) of block k, with A = df/dx and B = df/dl.
  virtual void evaluate(int k, const VectorXd& l, const VectorXd& x, VectorXd& f, MatrixXd& A,
                        MatrixXd& B) const = 0;
};

// Central-difference Jacobians of a misclosure function: used by the models without analytic ones and
// by the tests that check the analytic ones.
template <class F>
void numeric_jacobians(const F& misclosure, const VectorXd& l, const VectorXd& x, const VectorXd& dl,
                       const VectorXd& dx, VectorXd& f, MatrixXd& A, MatrixXd& B) {
  f = misclosure(l, x);
  A.resize(f.size(), x.size());
  B.resize(f.size(), l.size());
  for (int j = 0; j < x.size(); ++j) {
    VectorXd xp = x, xm = x;
    xp[j] += dx[j];
    xm[j] -= dx[j];
    A.col(j) = (misclosure(l, xp) - misclosure(l, xm)) / (2.0 * dx[j]);
  }
  for (int j = 0; j < l.size(); ++j) {
    VectorXd lp = l, lm = l;
    lp[j] += dl[j];
    lm[j] -= dl[j];
    B.col(j) = (misclosure(lp, x) - misclosure(lm, x)) / (2.0 * dl[j]);
  }
}

struct GaussHelmertOptions {
  double ev = 0.0;  // damping constant in standardised parameters (0: none)
  int max_iterations = 50;
  double tolerance = 1e-7;  // largest step, in units of each unknown's a priori sigma
};

struct ObservabilityReport {
  bool rank_deficient = false;  // a direction with (numerically) no information at all
  bool unresolved = false;      // a direction whose sigma exceeds the physical range of the parameters
  double condition_number = 0.0;  // of the standardised normal matrix
  std::vector<double> eigenvalues;  // of the standardised normal matrix, ascending
  // Parameter combinations the data cannot determine, e.g. "0.71 accel_bias_x - 0.71 accel_scale_x".
  std::vector<std::string> weak_directions;
  std::vector<std::string> unresolved_parameters;  // name: sigma vs range
};

struct GaussHelmertResult {
  bool converged = false;
  int iterations = 0;
  VectorXd x;                    // estimated unknowns
  MatrixXd N;                    // normal matrix (a priori weights) at the solution
  MatrixXd cov_x;                // a posteriori covariance (sigma0^2 scaled, includes damping)
  MatrixXd cov_x_apriori;        // from the observation covariances alone
  double weighted_ssr = 0.0;     // v' P v
  int redundancy = 0;            // conditions - unknowns
  double sigma0 = 0.0;           // sqrt(weighted_ssr / redundancy): a posteriori standard deviation of unit weight
  std::vector<VectorXd> misclosure;  // f(l_observed, x) per block: the residual in the condition's own units
  std::vector<VectorXd> normalised_misclosure;  // divided by its a priori sigma
  ObservabilityReport observability;
  VectorXd sigma() const { return cov_x.diagonal().cwiseSqrt(); }
  MatrixXd correlation() const;
};

GaussHelmertResult solve_gauss_helmert(const ConditionModel& model, const std::vector<ConditionBlock>& blocks,
                                       const VectorXd& x0, const GaussHelmertOptions& opt = {});

// Eigen-analysis of a normal matrix: rank and resolution against the parameter ranges.
ObservabilityReport analyse_observability(const MatrixXd& N, const std::vector<std::string>& names,
                                          const VectorXd& ranges);

}  // namespace ldv::calib
