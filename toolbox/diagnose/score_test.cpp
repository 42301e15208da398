#include "toolbox/diagnose/score_test.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "toolbox/diagnose/statistics.hpp"

namespace ldv::diag {
namespace {

// One measurement epoch's score contribution and information, over all candidate columns.
struct EpochScore {
  double t_s = 0.0;
  Segment segment = Segment::kStraight;
  std::vector<int> records;
};

Eigen::MatrixXd select(const Eigen::MatrixXd& M, const std::vector<int>& rows, const std::vector<int>& cols) {
  Eigen::MatrixXd out(rows.size(), cols.size());
  for (size_t i = 0; i < rows.size(); ++i)
    for (size_t j = 0; j < cols.size(); ++j) out(i, j) = M(rows[i], cols[j]);
  return out;
}

// Largest canonical correlation between two groups of columns, from the joint information matrix.
double canonical_correlation(const Eigen::MatrixXd& J, const std::vector<int>& a, const std::vector<int>& b) {
  if (a.empty() || b.empty()) return 0.0;
  const Eigen::MatrixXd Jaa = select(J, a, a), Jbb = select(J, b, b), Jab = select(J, a, b);
  const Eigen::LLT<Eigen::MatrixXd> la(Jaa), lb(Jbb);
  if (la.info() != Eigen::Success || lb.info() != Eigen::Success) return 0.0;
  const Eigen::MatrixXd X = la.matrixL().solve(Jab);
  const Eigen::MatrixXd Y = lb.matrixL().solve(X.transpose());  // (Lb^-1 Jba La^-T)
  return std::min(1.0, Eigen::JacobiSVD<Eigen::MatrixXd>(Y).singularValues()(0));
}

// Newey-West (Bartlett) long-run covariance of a zero-mean series of vectors (columns).
Eigen::MatrixXd newey_west(const Eigen::MatrixXd& U, int bandwidth) {
  const int n = static_cast<int>(U.cols());
  Eigen::MatrixXd V = U * U.transpose();
  for (int l = 1; l < bandwidth && l < n; ++l) {
    const double w = 1.0 - static_cast<double>(l) / bandwidth;
    const Eigen::MatrixXd G = U.leftCols(n - l) * U.rightCols(n - l).transpose();
    V += w * (G + G.transpose());
  }
  return V;
}

}  // namespace

ScreeningResult screen(const CandidateSet& set, const std::vector<SensitivityRecord>& records,
                       const std::vector<Segment>& record_segments, const ScreeningOptions& opt) {
  ScreeningResult res;
  const int P = set.columns;
  // Group the records into measurement epochs (position and velocity of one fix share their errors).
  std::vector<EpochScore> epochs;
  for (size_t i = 0; i < records.size(); ++i) {
    if (!std::isfinite(records[i].nis) || records[i].s.cols() != P) continue;
    if (epochs.empty() || std::abs(epochs.back().t_s - records[i].t_s) > 1e-6)
      epochs.push_back({records[i].t_s, record_segments[i], {}});
    epochs.back().records.push_back(static_cast<int>(i));
  }
  const int n = static_cast<int>(epochs.size());
  res.epochs = n;
  // Per-epoch whitened sensitivity and innovation: S^-1/2 s, S^-1/2 nu (the record's rows per record).
  std::vector<Eigen::MatrixXd> A(n);  // rows: whitened measurement components, cols: P
  std::vector<Eigen::VectorXd> y(n);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(P, P);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(P);
  std::array<Eigen::MatrixXd, kSegmentCount> J_seg;
  for (auto& Js : J_seg) Js = Eigen::MatrixXd::Zero(P, P);
  for (int k = 0; k < n; ++k) {
    int m = 0;
    for (int ri : epochs[k].records) m += static_cast<int>(records[ri].innovation.size());
    A[k].resize(m, P);
    y[k].resize(m);
    int row = 0;
    for (int ri : epochs[k].records) {
      const SensitivityRecord& r = records[ri];
      const int rows = static_cast<int>(r.innovation.size());
      const Eigen::LLT<Eigen::MatrixXd> llt(r.S);
      A[k].middleRows(row, rows) = llt.matrixL().solve(r.s);
      y[k].segment(row, rows) = llt.matrixL().solve(r.innovation);
      row += rows;
    }
    const Eigen::MatrixXd Jk = A[k].transpose() * A[k];
    J += Jk;
    J_seg[static_cast<int>(epochs[k].segment)] += Jk;
    g += A[k].transpose() * y[k];
  }
  double interval_s = 1.0;
  if (n > 1) interval_s = (epochs.back().t_s - epochs.front().t_s) / (n - 1);
  res.bandwidth_epochs = std::clamp(static_cast<int>(std::lround(opt.bandwidth_s / interval_s)), 1, std::max(1, n / 4));
  res.nu_eff = 1.5 * n / res.bandwidth_epochs;

  // Testable components: the minimal detectable size (model information inflated by the long-run
  // factor of the innovations) must be below the plausible size.
  const int n_candidates = static_cast<int>(set.candidates.size());
  const double alpha_each = opt.alpha / std::max(1, n_candidates);
  const double lambda1 = noncentrality_for_power(alpha_each, opt.power, 1.0);

  for (const Candidate& c : set.candidates) {
    CandidateScore cs;
    cs.name = c.name;
    cs.dim = c.dim;
    cs.state_names = c.state_names;
    cs.unit = c.unit;
    cs.estimate_si = Eigen::VectorXd::Constant(c.dim, std::numeric_limits<double>::quiet_NaN());
    cs.sigma_si = cs.estimate_si;
    cs.mds_si = Eigen::VectorXd::Constant(c.dim, std::numeric_limits<double>::infinity());
    std::vector<int> comps;
    for (int i = 0; i < c.dim; ++i)
      if (J(c.column + i, c.column + i) * c.plausible_si(i) * c.plausible_si(i) > lambda1) comps.push_back(i);
    // Drop, one at a time, the component whose conditional information is too low.
    Eigen::VectorXd e_hat, sigma;
    Eigen::MatrixXd Jc, V;
    for (;;) {
      if (comps.empty()) break;
      std::vector<int> cols;
      for (int i : comps) cols.push_back(c.column + i);
      Jc = select(J, cols, cols);
      const Eigen::LDLT<Eigen::MatrixXd> ldlt(Jc);
      const Eigen::MatrixXd Jinv = ldlt.solve(Eigen::MatrixXd::Identity(cols.size(), cols.size()));
      Eigen::VectorXd gc(cols.size());
      for (size_t i = 0; i < cols.size(); ++i) gc(i) = g(cols[i]);
      e_hat = Jinv * gc;
      // Robust covariance of the score from the residual contributions u_k = A_k^T (y_k - A_k e_hat).
      Eigen::MatrixXd U(cols.size(), n);
      for (int k = 0; k < n; ++k) {
        Eigen::MatrixXd Ak(A[k].rows(), cols.size());
        for (size_t i = 0; i < cols.size(); ++i) Ak.col(i) = A[k].col(cols[i]);
        U.col(k) = Ak.transpose() * (y[k] - Ak * e_hat);
      }
      V = newey_west(U, res.bandwidth_epochs);
      const Eigen::MatrixXd cov = Jinv * V * Jinv;  // sandwich
      sigma = cov.diagonal().cwiseMax(0.0).cwiseSqrt();
      int worst = -1;
      double worst_ratio = 1.0;
      for (size_t i = 0; i < comps.size(); ++i) {
        const double mds = std::sqrt(lambda1) * sigma(i);
        const double ratio = mds / c.plausible_si(comps[i]);
        if (!(ratio <= worst_ratio)) {
          worst_ratio = std::isfinite(ratio) ? ratio : 1e300;
          worst = static_cast<int>(i);
        }
      }
      if (worst < 0) {
        // Robust statistic: g^T V^-1 g with the score of the tested components.
        const Eigen::LDLT<Eigen::MatrixXd> vl(V);
        cs.statistic = gc.dot(vl.solve(gc)) / opt.statistic_scale;
        cs.statistic_model = gc.dot(Jinv * gc);
        break;
      }
      comps.erase(comps.begin() + worst);
    }
    cs.tested = comps;
    cs.testable = !comps.empty();
    if (cs.testable) {
      const int p = static_cast<int>(comps.size());
      cs.p_value = hotelling_sf(cs.statistic, p, res.nu_eff);
      cs.rank_z = chi_square_z(cs.statistic, p);
      for (int i = 0; i < p; ++i) {
        cs.estimate_si(comps[i]) = c.assumed_si(comps[i]) - e_hat(i);
        cs.sigma_si(comps[i]) = sigma(i);
        cs.mds_si(comps[i]) = std::sqrt(lambda1) * sigma(i);
      }
      ++res.testable;
    }
    res.ranked.push_back(std::move(cs));
  }
  res.threshold_p = opt.alpha / std::max(1, res.testable);
  for (CandidateScore& cs : res.ranked) cs.significant = cs.testable && cs.p_value < res.threshold_p;

  // Correlation between candidates (tested components), and the groups.
  const int nc = static_cast<int>(set.candidates.size());
  std::vector<std::vector<int>> cols(nc);
  for (int i = 0; i < nc; ++i)
    for (int comp : res.ranked[i].tested) cols[i].push_back(set.candidates[i].column + comp);
  res.correlation = Eigen::MatrixXd::Identity(nc, nc);
  for (int i = 0; i < nc; ++i) {
    res.candidate_names.push_back(set.candidates[i].name);
    for (int j = i + 1; j < nc; ++j) res.correlation(i, j) = res.correlation(j, i) = canonical_correlation(J, cols[i], cols[j]);
  }
  std::vector<int> order(nc);
  for (int i = 0; i < nc; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    if (res.ranked[a].testable != res.ranked[b].testable) return res.ranked[a].testable;
    return res.ranked[a].rank_z > res.ranked[b].rank_z;
  });
  for (int i : order) {
    CandidateScore& cs = res.ranked[i];
    if (!cs.testable) continue;
    for (int j : order)
      if (j == i || (res.ranked[j].testable && res.correlation(i, j) > opt.group_correlation))
        cs.group.push_back(res.ranked[j].name);
    if (cs.group.size() < 2) continue;
    // Which manoeuvre separates the group best on this drive: the segment with the lowest correlation.
    std::string best;
    double best_corr = 1.0;
    for (int s = 0; s < kSegmentCount; ++s) {
      double worst = 0.0;
      for (int j : order)
        if (j != i && res.ranked[j].testable && res.correlation(i, j) > opt.group_correlation)
          worst = std::max(worst, canonical_correlation(J_seg[s], cols[i], cols[j]));
      if (J_seg[s].trace() > 0.0 && worst < best_corr) {
        best_corr = worst;
        best = segment_name(static_cast<Segment>(s));
      }
    }
    const auto excitation = [&](const std::string& name) {
      for (const Candidate& c : set.candidates)
        if (c.name == name) return c.excitation;
      return std::string("?");
    };
    cs.separate_by = "more " + excitation(cs.name);
    for (const std::string& other : cs.group)
      if (other != cs.name) cs.separate_by += "; " + other + " needs " + excitation(other);
    if (!best.empty() && best_corr < opt.group_correlation)
      cs.separate_by += "; on this drive the '" + best + "' segments separate them best (correlation " +
                        std::to_string(best_corr).substr(0, 4) + ")";
  }
  std::vector<CandidateScore> ranked;
  for (int i : order) ranked.push_back(std::move(res.ranked[i]));
  res.ranked = std::move(ranked);
  return res;
}

}  // namespace ldv::diag
