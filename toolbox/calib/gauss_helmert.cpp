#include "toolbox/calib/gauss_helmert.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace ldv::calib {

MatrixXd GaussHelmertResult::correlation() const {
  const VectorXd s = sigma();
  MatrixXd c = cov_x;
  for (int i = 0; i < c.rows(); ++i)
    for (int j = 0; j < c.cols(); ++j) c(i, j) = (s[i] > 0 && s[j] > 0) ? c(i, j) / (s[i] * s[j]) : 0.0;
  return c;
}

namespace {

// Scaling that makes the normal matrix unit-diagonal; parameters without any information keep unit scale.
VectorXd standardising_scale(const MatrixXd& N) {
  VectorXd d = N.diagonal();
  for (int i = 0; i < d.size(); ++i) d[i] = d[i] > 0.0 ? d[i] : 1.0;
  return d;
}

MatrixXd pseudo_inverse(const MatrixXd& A) {
  Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod(A);
  cod.setThreshold(1e-13);
  return cod.pseudoInverse();
}

std::string describe_direction(const VectorXd& q, const std::vector<std::string>& names) {
  std::string s;
  char buf[96];
  for (int i = 0; i < q.size(); ++i) {
    if (std::abs(q[i]) < 0.1) continue;
    std::snprintf(buf, sizeof buf, "%s%.2f %s", s.empty() ? "" : (q[i] >= 0 ? " + " : " - "),
                  s.empty() ? q[i] : std::abs(q[i]), names[i].c_str());
    s += buf;
  }
  return s;
}

}  // namespace

ObservabilityReport analyse_observability(const MatrixXd& N, const std::vector<std::string>& names,
                                          const VectorXd& ranges) {
  ObservabilityReport rep;
  const VectorXd d = standardising_scale(N).cwiseSqrt().cwiseInverse();
  const MatrixXd Ns = d.asDiagonal() * N * d.asDiagonal();
  Eigen::SelfAdjointEigenSolver<MatrixXd> es_s(Ns);
  const double lmax_s = es_s.eigenvalues().maxCoeff();
  const double lmin_s = std::max(es_s.eigenvalues().minCoeff(), 0.0);
  rep.condition_number = lmin_s > 0.0 ? lmax_s / lmin_s : INFINITY;
  for (int i = 0; i < es_s.eigenvalues().size(); ++i) rep.eigenvalues.push_back(es_s.eigenvalues()[i]);
  // In units of each parameter's physical range, an eigenvalue below 1 is a direction whose sigma is larger
  // than anything the sensor could plausibly have: the data say nothing about it. Below a relative 1e-12 of
  // the largest it is a true rank deficiency (not enough poses or the wrong kind of motion).
  const MatrixXd Nr = ranges.asDiagonal() * N * ranges.asDiagonal();
  Eigen::SelfAdjointEigenSolver<MatrixXd> es(Nr);
  const double lmax = es.eigenvalues().maxCoeff();
  for (int i = 0; i < es.eigenvalues().size(); ++i) {
    const double lambda = es.eigenvalues()[i];
    const bool null = lambda <= 1e-12 * lmax;
    if (null) rep.rank_deficient = true;
    if (lambda < 1.0) {
      rep.unresolved = true;
      char head[96];
      if (null)
        std::snprintf(head, sizeof head, "no information: ");
      else
        std::snprintf(head, sizeof head, "sigma %.3g ranges: ", 1.0 / std::sqrt(lambda));
      rep.weak_directions.push_back(std::string(head) + describe_direction(es.eigenvectors().col(i), names));
    }
  }
  const MatrixXd Ninv = pseudo_inverse(N);
  for (int i = 0; i < N.rows(); ++i) {
    const double s = std::sqrt(std::max(Ninv(i, i), 0.0));
    if (rep.rank_deficient || s > ranges[i]) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "%s: sigma %.3g > range %.3g", names[i].c_str(), s, ranges[i]);
      if (s > ranges[i]) rep.unresolved_parameters.push_back(buf);
    }
  }
  return rep;
}

GaussHelmertResult solve_gauss_helmert(const ConditionModel& model, const std::vector<ConditionBlock>& blocks,
                                       const VectorXd& x0, const GaussHelmertOptions& opt) {
  const int p = model.num_params();
  if (x0.size() != p) throw std::invalid_argument("solve_gauss_helmert: x0 has the wrong size");
  const size_t K = blocks.size();
  GaussHelmertResult res;
  res.x = x0;
  std::vector<VectorXd> v(K);
  for (size_t k = 0; k < K; ++k) v[k] = VectorXd::Zero(blocks[k].l.size());

  VectorXd f;
  MatrixXd A, B;
  std::vector<MatrixXd> As(K), Bs(K), Minvs(K);
  std::vector<VectorXd> ws(K);
  int n_conditions = 0;
  // Builds the normal equations at the current x and adjusted observations l + v.
  auto linearise = [&](MatrixXd& N, VectorXd& u) {
    N = MatrixXd::Zero(p, p);
    u = VectorXd::Zero(p);
    n_conditions = 0;
    for (size_t k = 0; k < K; ++k) {
      const ConditionBlock& b = blocks[k];
      model.evaluate(static_cast<int>(k), b.l + v[k], res.x, f, A, B);
      ws[k] = f - B * v[k];  // misclosure referred to the original observations
      MatrixXd M = B * b.Sigma_l * B.transpose();
      if (b.Q_extra.size() > 0) M += b.Q_extra;
      Minvs[k] = M.inverse();
      As[k] = A;
      Bs[k] = B;
      N.noalias() += A.transpose() * Minvs[k] * A;
      u.noalias() += A.transpose() * Minvs[k] * ws[k];
      n_conditions += static_cast<int>(f.size());
    }
  };

  MatrixXd N;
  VectorXd u;
  for (res.iterations = 1; res.iterations <= opt.max_iterations; ++res.iterations) {
    linearise(N, u);
    const VectorXd D = standardising_scale(N);
    // (N + EV D) x_new = N x - u: the damping acts on the total unknowns, not on the step, so it is a ridge
    // towards the nominal sensor (x = 0) whose bias is visible in the sweep.
    MatrixXd Nd = N;
    Nd.diagonal() += opt.ev * D;
    const VectorXd x_new = pseudo_inverse(Nd) * (N * res.x - u);
    const VectorXd dx = x_new - res.x;
    // Converged when neither the unknowns nor the observation corrections move (the corrections change the
    // linearisation point, so a zero step with fresh corrections is not yet the solution).
    double dv_max = 0.0;
    for (size_t k = 0; k < K; ++k) {
      const VectorXd v_new = -blocks[k].Sigma_l * Bs[k].transpose() * Minvs[k] * (As[k] * dx + ws[k]);
      const VectorXd sigma_l = blocks[k].Sigma_l.diagonal().cwiseSqrt().cwiseMax(1e-300);
      dv_max = std::max(dv_max, (v_new - v[k]).cwiseQuotient(sigma_l).cwiseAbs().maxCoeff());
      v[k] = v_new;
    }
    res.x = x_new;
    if ((dx.cwiseProduct(D.cwiseSqrt())).cwiseAbs().maxCoeff() < opt.tolerance && dv_max < 1e3 * opt.tolerance) {
      res.converged = true;
      break;
    }
  }
  res.iterations = std::min(res.iterations, opt.max_iterations);

  // Final linearisation at the solution: statistics and covariances.
  linearise(N, u);
  res.N = N;
  res.weighted_ssr = 0.0;
  res.misclosure.resize(K);
  res.normalised_misclosure.resize(K);
  for (size_t k = 0; k < K; ++k) {
    res.weighted_ssr += ws[k].dot(Minvs[k] * ws[k]);
    model.evaluate(static_cast<int>(k), blocks[k].l, res.x, f, A, B);
    res.misclosure[k] = f;
    res.normalised_misclosure[k] = f.cwiseQuotient(Minvs[k].diagonal().cwiseInverse().cwiseSqrt());
  }
  res.redundancy = n_conditions - p;
  res.sigma0 = res.redundancy > 0 ? std::sqrt(res.weighted_ssr / res.redundancy) : NAN;
  const VectorXd D = standardising_scale(N);
  MatrixXd Nd = N;
  Nd.diagonal() += opt.ev * D;
  const MatrixXd Ndinv = pseudo_inverse(Nd);
  res.cov_x_apriori = Ndinv * N * Ndinv;
  const double s0 = std::isfinite(res.sigma0) ? res.sigma0 : 1.0;
  res.cov_x = s0 * s0 * res.cov_x_apriori;
  res.observability = analyse_observability(N, model.param_names(), model.param_ranges());
  return res;
}

}  // namespace ldv::calib
