#include "toolbox/allan/noise_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include "toolbox/allan/avar_covariance.hpp"
#include "common/math/chi_square.hpp"
#include "toolbox/allan/nonnegative_lsq.hpp"

namespace ldv::allan {
namespace {

struct Data {
  std::vector<double> tau, avar, edf;
  std::vector<long> m;   // averaging factors (for the overlapping-estimate covariance)
  double tau0 = 0.0;
  long n_phase = 0;      // > 0 when the points are one overlapping Allan deviation (GLS possible)
};

struct Basis {
  std::vector<ModelTerm> terms;
  std::vector<double> shapes;  // per term (GM T, sine f0)
};

struct LinearFit {
  std::vector<double> c;  // per basis term
  double chi2 = std::numeric_limits<double>::infinity();
  Eigen::MatrixXd wh;  // final metric: chi2 = |wh (data - model)|^2
};

double model_at(const Basis& b, const std::vector<double>& c, double tau) {
  double m = 0.0;
  for (size_t k = 0; k < b.terms.size(); ++k) m += c[k] * term_avar(b.terms[k], tau, b.shapes[k]);
  return m;
}

Eigen::MatrixXd design(const Basis& b, const Data& d) {
  const int n = static_cast<int>(d.tau.size()), p = static_cast<int>(b.terms.size());
  Eigen::MatrixXd A(n, p);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < p; ++k) A(i, k) = term_avar(b.terms[k], d.tau[i], b.shapes[k]);
  }
  return A;
}

// Non-negative least squares in the metric chi2 = |Wh (y - A c)|^2 (Wh = diag(sqrt(w)) for
// independent points, L^-1 of the covariance C = L L^T for GLS), by enumerating the passive sets
// (at most 2^6 for our handful of terms): the optimum is the best subset solution that is
// non-negative.
LinearFit nnls(const Basis& b, const Data& d, const Eigen::MatrixXd& Wh) {
  const int n = static_cast<int>(d.tau.size());
  const Eigen::MatrixXd A = Wh * design(b, d);
  const Eigen::VectorXd y = Wh * Eigen::Map<const Eigen::VectorXd>(d.avar.data(), n);
  LinearFit best;
  const Eigen::VectorXd c = nonnegative_least_squares(A, y, &best.chi2);
  best.c.assign(c.data(), c.data() + c.size());
  return best;
}

// Iteratively re-weighted, points taken as independent: var(avar_i) = 2 model_i^2 / edf_i.
LinearFit irls(const Basis& b, const Data& d) {
  const int n = static_cast<int>(d.tau.size());
  Eigen::VectorXd w(n);
  for (int i = 0; i < n; ++i) w(i) = d.edf[i] / (2.0 * d.avar[i] * d.avar[i]);
  LinearFit fit;
  for (int it = 0; it < 8; ++it) {
    fit = nnls(b, d, Eigen::MatrixXd(w.cwiseSqrt().asDiagonal()));
    for (int i = 0; i < n; ++i) {
      // Floor the model at a tenth of the data so a momentarily absent term cannot blow a weight up.
      const double m = std::max(model_at(b, fit.c, d.tau[i]), 0.1 * d.avar[i]);
      w(i) = d.edf[i] / (2.0 * m * m);
    }
  }
  fit.chi2 = 0.0;
  for (int i = 0; i < n; ++i) fit.chi2 += w(i) * std::pow(d.avar[i] - model_at(b, fit.c, d.tau[i]), 2);
  fit.wh = w.cwiseSqrt().asDiagonal();
  return fit;
}

using Solver = std::function<LinearFit(const Basis&)>;

// Best fit over a log grid of the shape parameter of `t` (GM time constant or sine frequency),
// refined by golden-section search in log(shape).
LinearFit fit_with_shape(Basis b, int shaped, const Solver& solve, double lo, double hi) {
  auto chi2_at = [&](double log_s) {
    b.shapes[shaped] = std::exp(log_s);
    return solve(b).chi2;
  };
  const int grid = 16;
  double best_ls = std::log(lo), best_chi2 = std::numeric_limits<double>::infinity();
  const double step = (std::log(hi) - std::log(lo)) / (grid - 1);
  for (int g = 0; g < grid; ++g) {
    const double ls = std::log(lo) + g * step, c2 = chi2_at(ls);
    if (c2 < best_chi2) best_chi2 = c2, best_ls = ls;
  }
  double a = std::max(best_ls - step, std::log(lo)), z = std::min(best_ls + step, std::log(hi));
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = z - phi * (z - a), x2 = a + phi * (z - a), f1 = chi2_at(x1), f2 = chi2_at(x2);
  for (int it = 0; it < 20; ++it) {
    if (f1 < f2) z = x2, x2 = x1, f2 = f1, x1 = z - phi * (z - a), f1 = chi2_at(x1);
    else a = x1, x1 = x2, f1 = f2, x2 = a + phi * (z - a), f2 = chi2_at(x2);
  }
  b.shapes[shaped] = std::exp(f1 < f2 ? x1 : x2);
  LinearFit f = solve(b);
  if (f.chi2 > best_chi2) {  // the grid point was better (multi-modal chi2)
    b.shapes[shaped] = std::exp(best_ls);
    f = solve(b);
  }
  f.c.push_back(b.shapes[shaped]);  // the shape rides along at the end
  return f;
}

struct Model {
  Basis basis;
  LinearFit fit;
};

int shaped_index(const std::vector<ModelTerm>& terms) {
  int shaped = -1;
  for (size_t k = 0; k < terms.size(); ++k) {
    if (terms[k] == ModelTerm::kGaussMarkov || terms[k] == ModelTerm::kSinusoid) shaped = static_cast<int>(k);
  }
  return shaped;
}

Model fit_model(std::vector<ModelTerm> terms, const Data& d, const Solver& solve) {
  Model m;
  m.basis.terms = terms;
  m.basis.shapes.assign(terms.size(), 0.0);
  const double tmin = d.tau.front(), tmax = d.tau.back();
  const int shaped = shaped_index(terms);
  if (shaped < 0) {
    m.fit = solve(m.basis);
    return m;
  }
  // GM: the hump sits at 1.89 T, so T up to tau_max/2 covers every visible hump. From below, T is
  // bounded at kGaussMarkovMinResolution shortest taus (gm_min_time_constant).
  // Sinusoid: the first peak of its Allan deviation is at tau = 0.371 / f0.
  const bool gm = terms[shaped] == ModelTerm::kGaussMarkov;
  const double lo = gm ? gm_min_time_constant(tmin) : 0.371 / tmax, hi = gm ? std::max(0.5 * tmax, lo) : 0.371 / tmin;
  m.fit = fit_with_shape(m.basis, shaped, solve, lo, hi);
  m.basis.shapes[shaped] = m.fit.c.back();
  m.fit.c.pop_back();
  if (gm && m.fit.c[shaped] > 0 && gm_time_constant_at_bound(m.basis.shapes[shaped], tmin)) {
    // Still pulled to the shortest T: the term is white at this resolution, i.e. white noise of
    // density 2 sigma^2 T. Fold it into N: refit without it, the GM absent (coefficient 0).
    Basis without = m.basis;
    without.terms.erase(without.terms.begin() + shaped);
    without.shapes.erase(without.shapes.begin() + shaped);
    LinearFit f = solve(without);
    f.c.insert(f.c.begin() + shaped, 0.0);
    m.fit = std::move(f);
    m.basis.shapes[shaped] = lo;
  }
  return m;
}

Model fit_model(std::vector<ModelTerm> terms, const Data& d) {
  return fit_model(std::move(terms), d, [&](const Basis& b) { return irls(b, d); });
}

// The noise levels of a fitted model, for the covariance of the Allan variance estimates.
NoiseLevels levels_of(const Model& m) {
  NoiseLevels lv;
  for (size_t k = 0; k < m.basis.terms.size(); ++k) {
    const double v = std::sqrt(std::max(0.0, m.fit.c[k]));
    switch (m.basis.terms[k]) {
      case ModelTerm::kQ: lv.q = v; break;
      case ModelTerm::kN: lv.n = v; break;
      case ModelTerm::kB: lv.b = v; break;
      case ModelTerm::kK: lv.k = v; break;
      case ModelTerm::kGaussMarkov: lv.gm_sigma = v, lv.gm_t_s = m.basis.shapes[k]; break;
      case ModelTerm::kR: lv.r = v; break;
      default: break;  // sinusoid: not in the covariance
    }
  }
  return lv;
}

// Whitening matrix L^-1 of the covariance C = L L^T of the overlapping Allan variance estimates
// under the model `m`. Where the model explains less than a tenth of the data (a term momentarily
// absent), the variance is scaled up to that of a tenth of the data, as the IRLS weights do.
bool gls_whitener(const Model& m, const Data& d, Eigen::MatrixXd& wh) {
  const int n = static_cast<int>(d.tau.size());
  const std::vector<double> cv = oavar_covariance(levels_of(m), d.m, d.tau0, d.n_phase);
  Eigen::MatrixXd C = Eigen::Map<const Eigen::MatrixXd>(cv.data(), n, n);
  Eigen::VectorXd s(n);
  for (int i = 0; i < n; ++i) {
    const double mod = model_at(m.basis, m.fit.c, d.tau[i]);
    s(i) = mod > 0 ? std::max(1.0, 0.1 * d.avar[i] / mod) : 1.0;
    if (!(C(i, i) > 0)) return false;
  }
  C = s.asDiagonal() * C * s.asDiagonal();
  // A relative jitter guards the factorization of strongly correlated neighbouring taus.
  for (double jitter : {1e-10, 1e-8, 1e-6, 1e-4}) {
    Eigen::MatrixXd Cj = C;
    Cj.diagonal() *= 1.0 + jitter;
    Eigen::LLT<Eigen::MatrixXd> llt(Cj);
    if (llt.info() != Eigen::Success) continue;
    wh = llt.matrixL().solve(Eigen::MatrixXd::Identity(n, n));
    return wh.allFinite();
  }
  return false;
}

// Generalized least squares: the metric is the full covariance of the overlapping estimates,
// evaluated at the model being fitted (re-evaluated a few times, like the IRLS weights).
Model fit_model_gls(const std::vector<ModelTerm>& terms, const Data& d, const Model& start, bool* ok) {
  Model m = start;
  *ok = false;
  for (int it = 0; it < 4; ++it) {
    Eigen::MatrixXd wh;
    if (!gls_whitener(m, d, wh)) break;
    Model next = fit_model(terms, d, [&](const Basis& b) {
      LinearFit f = nnls(b, d, wh);
      f.wh = wh;
      return f;
    });
    double change = 0.0;
    for (size_t k = 0; k < terms.size(); ++k) {
      const double a = std::sqrt(std::max(0.0, m.fit.c[k])), b = std::sqrt(std::max(0.0, next.fit.c[k]));
      if (a + b > 0) change = std::max(change, std::fabs(a - b) / (a + b));
    }
    m = std::move(next);
    *ok = true;
    if (change < 1e-3 && it > 0) break;
  }
  if (*ok) {  // the metric at the final model
    Eigen::MatrixXd wh;
    if (gls_whitener(m, d, wh)) {
      m.fit.wh = wh;
      const Eigen::VectorXd r = Eigen::Map<const Eigen::VectorXd>(d.avar.data(), d.tau.size()) -
                                design(m.basis, d) * Eigen::Map<const Eigen::VectorXd>(m.fit.c.data(), m.fit.c.size());
      m.fit.chi2 = (wh * r).squaredNorm();
    }
  }
  return m;
}

std::vector<ModelTerm> terms_of(const FitOptions& o) {
  std::vector<ModelTerm> t;
  if (o.q) t.push_back(ModelTerm::kQ);
  if (o.n) t.push_back(ModelTerm::kN);
  if (o.b && !o.gauss_markov) t.push_back(ModelTerm::kB);
  if (o.k) t.push_back(ModelTerm::kK);
  if (o.r) t.push_back(ModelTerm::kR);
  if (o.gauss_markov) t.push_back(ModelTerm::kGaussMarkov);
  if (o.sinusoid && !o.gauss_markov) t.push_back(ModelTerm::kSinusoid);  // one shaped term at a time
  return t;
}

// Covariance of the coefficients of the terms in `idx` (weighted LS normal matrix inverse).
// A shaped term (GM, sinusoid) with a non-zero coefficient adds its shape parameter as a last
// column (Gauss-Newton linearisation, central difference in log(shape)), so the uncertainty of T
// spreads into the coefficients it trades off against.
Eigen::MatrixXd covariance(const Basis& b, const std::vector<int>& idx, const Data& d, const Eigen::MatrixXd& wh,
                           const std::vector<double>& c) {
  const int n = static_cast<int>(d.tau.size());
  int shaped = -1;
  for (int j : idx) {
    if ((b.terms[j] == ModelTerm::kGaussMarkov || b.terms[j] == ModelTerm::kSinusoid) && c[j] > 0) shaped = j;
  }
  const int q = static_cast<int>(idx.size()) + (shaped >= 0 ? 1 : 0);
  if (q == 0) return Eigen::MatrixXd();  // no free term (every coefficient at its bound)
  Eigen::MatrixXd A(n, q);
  for (int i = 0; i < n; ++i) {
    for (size_t j = 0; j < idx.size(); ++j) A(i, j) = term_avar(b.terms[idx[j]], d.tau[i], b.shapes[idx[j]]);
    if (shaped >= 0) {
      const double s = b.shapes[shaped], h = 1e-4;
      A(i, q - 1) = c[shaped] * (term_avar(b.terms[shaped], d.tau[i], s * (1 + h)) -
                                 term_avar(b.terms[shaped], d.tau[i], s * (1 - h))) / (2 * h);
    }
  }
  A = wh * A;
  Eigen::VectorXd scale(q);
  for (int j = 0; j < q; ++j) {
    scale(j) = A.col(j).norm();
    if (scale(j) > 0) A.col(j) /= scale(j);
  }
  const Eigen::MatrixXd N = A.transpose() * A;
  Eigen::MatrixXd C = N.completeOrthogonalDecomposition().pseudoInverse();
  return scale.cwiseInverse().asDiagonal() * C * scale.cwiseInverse().asDiagonal();
}

double decade_chi2(const Model& m, const Data& d, double lo, double hi, int* count) {
  double s = 0.0;
  int c = 0;
  for (size_t i = 0; i < d.tau.size(); ++i) {
    if (d.tau[i] < lo || d.tau[i] >= hi) continue;
    const double mod = std::max(model_at(m.basis, m.fit.c, d.tau[i]), 1e-300);
    s += d.edf[i] / 2.0 * std::pow(d.avar[i] / mod - 1.0, 2);
    ++c;
  }
  if (count) *count = c;
  return s;
}

}  // namespace

double NoiseFit::model_avar(double tau) const {
  double m = 0.0;
  for (int k = 0; k < kModelTermCount; ++k) {
    const TermEstimate& t = terms[k];
    if (t.in_model && t.value > 0) m += t.value * t.value * term_avar(static_cast<ModelTerm>(k), tau, t.shape);
  }
  return m;
}

double gm_min_time_constant(double resolution_s) { return kGaussMarkovMinResolution * resolution_s; }

bool gm_time_constant_at_bound(double t_s, double resolution_s) {
  return t_s <= 1.02 * gm_min_time_constant(resolution_s);
}

void set_term_interval(TermEstimate& t, double c, double sigma_c, double z) {
  t.value = std::sqrt(c);
  // The coefficient enters squared: intervals are taken on c and mapped through the square root,
  // which stays meaningful at c = 0 (where the delta method would divide by zero).
  t.sigma = 0.5 * (std::sqrt(c + sigma_c) - std::sqrt(std::max(0.0, c - sigma_c)));
  if (c > 2.0 * sigma_c) {
    // A clearly present term: its variance-like coefficient has a spread proportional to itself
    // (a chi-square-like estimate), so the interval is symmetric in ln c, not in c; a low
    // estimate then still reaches up to the truth (a Wald interval in c would not).
    const double s_ln = sigma_c / c;
    t.lo = std::sqrt(c * std::exp(-z * s_ln));
    t.hi = std::sqrt(c * std::exp(z * s_ln));
  } else {
    t.lo = std::sqrt(std::max(0.0, c - z * sigma_c));
    t.hi = std::sqrt(c + z * sigma_c);
  }
}

namespace {

// The fit proper, on deviations of order 1 (see fit_noise_model).
NoiseFit fit_unit_scale(const std::vector<StabilityPoint>& pts, const FitOptions& opt) {
  Data d;
  for (const auto& p : pts) {
    if (p.edf > 0 && p.point.dev > 0) {
      d.tau.push_back(p.point.tau_s);
      d.avar.push_back(p.point.dev * p.point.dev);
      d.edf.push_back(p.edf);
      d.m.push_back(p.point.m);
    }
  }
  if (d.tau.size() < 3) throw std::invalid_argument("noise fit needs at least 3 deviation points with degrees of freedom");
  NoiseFit out;
  out.points = static_cast<int>(d.tau.size());
  const std::vector<ModelTerm> terms = terms_of(opt);
  Model model = fit_model(terms, d);
  const Model base_irls = model;

  // Generalized least squares when the points are one overlapping Allan deviation (N - 2m terms
  // at every m of one series): the full covariance of the estimates across tau replaces the
  // independent-points weights, so neighbouring taus that share their data count once.
  bool gls = opt.gls;
  for (size_t i = 0; gls && i < pts.size(); ++i) {
    const DeviationPoint& q = pts[i].point;
    const long n_phase = q.n_terms + 2 * q.m;
    if (q.m < 1 || q.n_terms < 1 || (d.n_phase > 0 && n_phase != d.n_phase)) gls = false;
    d.n_phase = n_phase;
  }
  if (gls) {
    d.tau0 = d.tau.front() / static_cast<double>(d.m.front());
    bool ok = false;
    Model g = fit_model_gls(terms, d, model, &ok);
    if (ok) model = std::move(g);
    gls = ok;
  }
  out.chi2 = model.fit.chi2;
  out.gls = gls;
  out.method = gls ? "allan_gls" : "allan_wls";

  // Without GLS (points of another kind): the weighted LS covariance assumes independent points,
  // which is optimistic for overlapping estimates; about one independent point per octave of tau
  // is counted, i.e. the covariance is inflated by the number of points per octave.
  if (!gls) {
    const double octaves = std::max(1.0, std::log2(d.tau.back() / d.tau.front()));
    out.covariance_inflation = std::max(1.0, d.tau.size() / octaves);
  }

  const double z = math::normal_quantile(0.5 + 0.5 * opt.interval_confidence);
  std::vector<int> active;
  for (size_t k = 0; k < terms.size(); ++k) if (model.fit.c[k] > 0) active.push_back(static_cast<int>(k));
  const Eigen::MatrixXd cov_active = covariance(model.basis, active, d, model.fit.wh, model.fit.c) * out.covariance_inflation;
  std::vector<int> all_terms(terms.size());
  for (size_t k = 0; k < terms.size(); ++k) all_terms[k] = static_cast<int>(k);
  const Eigen::MatrixXd cov_all = covariance(model.basis, all_terms, d, model.fit.wh, model.fit.c) * out.covariance_inflation;
  for (size_t k = 0; k < terms.size(); ++k) {
    TermEstimate& t = out[terms[k]];
    t.in_model = true;
    t.shape = model.basis.shapes[k];
    double var_c;
    const auto it = std::find(active.begin(), active.end(), static_cast<int>(k));
    if (it != active.end()) {
      const int j = static_cast<int>(it - active.begin());
      var_c = cov_active(j, j);
    } else {  // at the bound: its uncertainty as if it were free, next to the active terms
      std::vector<int> with = active;
      with.push_back(static_cast<int>(k));
      var_c = covariance(model.basis, with, d, model.fit.wh, model.fit.c)(with.size() - 1, with.size() - 1) *
              out.covariance_inflation;
    }
    const double c = model.fit.c[k], sc = std::sqrt(std::max(var_c, 0.0));
    set_term_interval(t, c, sc, z);
    bool dominant = false;
    for (double tau : d.tau) {
      const double part = c * term_avar(terms[k], tau, t.shape);
      if (part >= 0.5 * model_at(model.basis, model.fit.c, tau)) dominant = true;
    }
    // Significance with every term of the model free (not only the active ones): a term that
    // trades off against one at its bound (a ramp R against a random walk K that came out 0) is
    // not called resolved on the strength of the other being held at zero.
    const double sc_free = std::sqrt(std::max(0.0, cov_all(k, k)));
    t.resolved = c > 2.0 * std::max(sc, sc_free) && dominant;
    if ((terms[k] == ModelTerm::kGaussMarkov || terms[k] == ModelTerm::kSinusoid) && c > 0 &&
        cov_active.rows() > static_cast<long>(active.size())) {
      // The last row/column is ln(shape): sigma(T) = T sigma(ln T).
      t.shape_sigma = t.shape * std::sqrt(std::max(0.0, cov_active(active.size(), active.size())));
    }
  }

  // B_tau_s: where the measured deviation is flattest, i.e. its minimum.
  const size_t imin = std::min_element(d.avar.begin(), d.avar.end()) - d.avar.begin();
  out.b_tau_s = d.tau[imin];

  // Slope lines: the line of each slope that touches the curve from below (IEEE Std 952 reads N at
  // tau = 1 s on the -1/2 line, K at 3 s on the +1/2 line, ...: the same numbers).
  const ModelTerm line_terms[5] = {ModelTerm::kQ, ModelTerm::kN, ModelTerm::kB, ModelTerm::kK, ModelTerm::kR};
  for (int l = 0; l < 5; ++l) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < d.tau.size(); ++i) {
      const double c = d.avar[i] / term_avar(line_terms[l], d.tau[i]);
      if (c < best) best = c, out.slope_lines[l].tau_s = d.tau[i];
    }
    out.slope_lines[l].value = std::sqrt(best);
  }

  // Misfit per decade, and the excluded term that would close it.
  std::vector<ModelTerm> candidates;
  for (ModelTerm t : {ModelTerm::kQ, ModelTerm::kN, ModelTerm::kB, ModelTerm::kK, ModelTerm::kR,
                      ModelTerm::kGaussMarkov}) {
    if (std::find(terms.begin(), terms.end(), t) == terms.end()) candidates.push_back(t);
  }
  std::vector<Model> extended;
  for (ModelTerm t : candidates) {
    std::vector<ModelTerm> with = terms;
    if (t == ModelTerm::kGaussMarkov) with.erase(std::remove(with.begin(), with.end(), ModelTerm::kSinusoid), with.end());
    with.push_back(t);
    extended.push_back(fit_model(with, d));
  }
  // The misfit compares the model with and without each excluded term fitted the same way
  // (independent points, IRLS), so the base is the IRLS model too.
  const Model& model_ir = base_irls;
  const double first_decade = std::floor(std::log10(d.tau.front()));
  for (double e = first_decade; std::pow(10.0, e) <= d.tau.back(); e += 1.0) {
    DecadeMisfit dm;
    dm.tau_lo_s = std::pow(10.0, e);
    dm.tau_hi_s = std::pow(10.0, e + 1.0);
    const double chi2 = decade_chi2(model_ir, d, dm.tau_lo_s, dm.tau_hi_s, &dm.points);
    if (dm.points == 0) continue;
    dm.chi2_per_point = chi2 / dm.points;
    for (size_t i = 0; i < d.tau.size(); ++i) {
      if (d.tau[i] >= dm.tau_lo_s && d.tau[i] < dm.tau_hi_s) {
        dm.log_ratio += std::log(d.avar[i] / std::max(model_at(model_ir.basis, model_ir.fit.c, d.tau[i]), 1e-300)) / dm.points;
      }
    }
    dm.chi2_per_point_with_term = dm.chi2_per_point;
    for (size_t c = 0; c < candidates.size(); ++c) {
      const double after = decade_chi2(extended[c], d, dm.tau_lo_s, dm.tau_hi_s, nullptr) / dm.points;
      // A term "closes" the misfit when it at least halves it (a clear, not a marginal, gain).
      if (after < 0.5 * dm.chi2_per_point && after < dm.chi2_per_point_with_term) {
        dm.closing_term = model_term_name(candidates[c]);
        dm.chi2_per_point_with_term = after;
      }
    }
    out.misfit.push_back(dm);
  }
  return out;
}

}  // namespace

// The generalized LS fit costs O(n^3) in the number of taus (its covariance is n x n): `--taus all` on a
// 2-minute record (3000 taus) took minutes and GBs. Neighbouring overlapping estimates at dense taus are
// almost perfectly correlated, so a log-spaced subset of a few hundred carries the same information.
constexpr size_t kMaxFitPoints = 240;

std::vector<StabilityPoint> thinned_log_spaced(const std::vector<StabilityPoint>& pts, size_t max_points) {
  if (pts.size() <= max_points) return pts;
  std::vector<StabilityPoint> sorted = pts;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const StabilityPoint& a, const StabilityPoint& b) { return a.point.tau_s < b.point.tau_s; });
  std::vector<StabilityPoint> out;
  const double lo = std::log(sorted.front().point.tau_s), hi = std::log(sorted.back().point.tau_s);
  double next = lo;
  const double step = (hi - lo) / static_cast<double>(max_points - 1);
  for (size_t i = 0; i < sorted.size(); ++i) {
    if (std::log(sorted[i].point.tau_s) + 1e-12 >= next || i + 1 == sorted.size()) {
      out.push_back(sorted[i]);
      next = std::log(sorted[i].point.tau_s) + step;
    }
  }
  return out;
}

NoiseFit fit_noise_model(const std::vector<StabilityPoint>& pts, const FitOptions& opt) {
  if (terms_of(opt).empty()) throw std::invalid_argument("noise fit: no noise term to fit (the term list is empty)");
  // The fit squares the deviations and squares them again in its normal matrix, so data of 1e100 or
  // 1e-100 would overflow or underflow. Every term is linear in the Allan variance: fit deviations
  // scaled to a peak of 1 and scale the coefficients back.
  constexpr double kTauMin_s = 1e-9, kTauMax_s = 1e12;  // ns sampling to decades of data
  double peak = 0.0;
  for (const StabilityPoint& p : pts) {
    if (!std::isfinite(p.point.dev) || !std::isfinite(p.point.tau_s))
      throw std::invalid_argument("noise fit: the deviation at tau = " + std::to_string(p.point.tau_s) +
                                  " s is not finite (the data overflow double precision: rescale the input)");
    if (p.edf > 0 && p.point.dev > 0) {
      if (p.point.tau_s < kTauMin_s || p.point.tau_s > kTauMax_s)
        throw std::invalid_argument("noise fit: tau = " + std::to_string(p.point.tau_s) + " s is outside [1e-9, 1e12] s");
      peak = std::max(peak, p.point.dev);
    }
  }
  if (peak == 0.0) return fit_unit_scale(pts, opt);  // throws: no usable point
  std::vector<StabilityPoint> scaled = thinned_log_spaced(pts, kMaxFitPoints);
  for (StabilityPoint& p : scaled) {
    p.point.dev /= peak;
    p.interval.lo /= peak;
    p.interval.hi /= peak;
  }
  NoiseFit f = fit_unit_scale(scaled, opt);
  for (TermEstimate& t : f.terms) {
    t.value *= peak;
    t.sigma *= peak;
    t.lo *= peak;
    t.hi *= peak;
  }
  for (SlopeLine& l : f.slope_lines) l.value *= peak;
  return f;
}

}  // namespace ldv::allan
