#include "toolbox/allan/whittle_fit.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/FFT>
#include <utility>
#include <vector>

#include "common/math/chi_square.hpp"
#include "toolbox/allan/block_spectrum.hpp"
#include "toolbox/allan/nonnegative_lsq.hpp"

namespace ldv::allan {
namespace {

// The periodogram, ordinate by ordinate at the low frequencies where the slow terms live, then in
// bins 1 % wide (the densities are smooth there; a bin counts as `count` ordinates at its mean).
// The split cosine bell over 10 % of n at each end (see the taper comment in
// periodogram_of_block_differences), and its sums.
struct TaperSums {
  long edge = 1;
  double sum_h = 0.0, sum_h2 = 0.0, sum_dh2 = 0.0;
  double variance_factor = 1.0;  // n sum h^4 / (sum h^2)^2: what the taper costs in variance
};

long taper_edge(long n) { return std::max(1L, n / 10); }

double split_cosine_bell(long j, long n, long edge) {
  const long from_end = std::min(j, n - 1 - j);
  return from_end < edge ? 0.5 * (1.0 - std::cos(M_PI * (from_end + 0.5) / edge)) : 1.0;
}

TaperSums split_cosine_bell_sums(long n) {
  TaperSums t;
  t.edge = taper_edge(n);
  double h4 = 0.0, previous = 0.0;
  for (long j = 0; j < n; ++j) {
    const double h = split_cosine_bell(j, n, t.edge);
    t.sum_h += h, t.sum_h2 += h * h, h4 += h * h * h * h;
    if (j > 0) t.sum_dh2 += (h - previous) * (h - previous);
    previous = h;
  }
  t.variance_factor = n * h4 / (t.sum_h2 * t.sum_h2);
  return t;
}

// The periodogram, ordinate by ordinate at the low frequencies where the slow terms live, then in
// bins 1 % wide (the densities are smooth there; a bin counts as `count` ordinates at its mean).
struct Periodogram {
  std::vector<double> nu, mean_ordinate, count;
  double tau_b = 0.0;
  long ordinates = 0, blocks = 0;
  TaperSums taper;
  double weighted_mean = 0.0;  // taper-weighted mean of d (the ramp's R tau_b plus noise)
};

// Largest 2^a 3^b 5^c <= n: the FFT stays O(n log n) without padding (padding would taper the
// series and change the ordinates' distribution).
long smooth_length(long n) {
  for (long l = n; l > 1; --l) {
    long r = l;
    for (long p : {2L, 3L, 5L})
      while (r % p == 0) r /= p;
    if (r == 1) return l;
  }
  return n;
}

// Frequencies of a record of n blocks: ordinates one by one up to k = 200 (the slow terms live
// there), then bins 1 % wide. `ordinate(k_lo, k_hi)`: the sum of the ordinates in [k_lo, k_hi).
template <typename OrdinateSum>
void bin_frequencies(long n, Periodogram& p, OrdinateSum ordinate) {
  constexpr long kSingleUpTo = 200;
  const long k_max = (n - 1) / 2;  // frequency 0 and Nyquist excluded
  for (long k = 1; k <= k_max;) {
    const long width = k <= kSingleUpTo ? 1 : std::max(1L, k / 100);
    const long k_end = std::min(k_max + 1, k + width);
    const double c = static_cast<double>(k_end - k);
    p.nu.push_back(0.5 * static_cast<double>(k + k_end - 1) / n);  // the bin's mean frequency
    p.mean_ordinate.push_back(ordinate(k, k_end) / c);
    p.count.push_back(c);
    p.ordinates += k_end - k;
    k = k_end;
  }
}

long blocks_of(const PhaseSeries& s, long m, double tau_b) {
  const long blocks = (static_cast<long>(s.x.size()) - 1) / m;
  if (blocks < 65) {
    throw std::invalid_argument("likelihood fit: " + std::to_string(blocks) + " blocks of " + std::to_string(tau_b) +
                                " s; at least 65 are needed");
  }
  return blocks;
}

Periodogram periodogram_of_block_differences(const PhaseSeries& s, long m) {
  Periodogram p;
  p.tau_b = m * s.tau0_s;
  const long n = smooth_length(blocks_of(s, m, p.tau_b) - 1);
  p.blocks = n;
  // Taper: a split cosine bell over 10 % of the record at each end. Without it, d's sum telescopes
  // to its end values (ybar_n - ybar_0), which then sit in every ordinate as a flat floor of about
  // 2 N^2 / (tau_b n): exactly the signature of a rate random walk, read as a K several times the
  // truth on pure white noise. Normalised by sum h^2, so the ordinates keep the mean S(nu).
  // The mean removed is the taper-weighted one: it takes out a rate ramp R (a constant R tau_b in
  // d) and, unlike the plain mean (ybar_n - ybar_0) / n, carries almost no noise of the end
  // values, so it does not leak that floor back in through the taper.
  p.taper = split_cosine_bell_sums(n);
  std::vector<double> d(n), h(n);
  double sum_hd = 0.0;
  for (long j = 0; j < n; ++j) {
    // ybar_{j+1} - ybar_j from the phase: the second difference over a block, / tau_b.
    d[j] = (s.x[(j + 2) * m] - 2.0 * s.x[(j + 1) * m] + s.x[j * m]) / p.tau_b;
    h[j] = split_cosine_bell(j, n, p.taper.edge);
    sum_hd += h[j] * d[j];
  }
  p.weighted_mean = sum_hd / p.taper.sum_h;
  for (long j = 0; j < n; ++j) d[j] = (d[j] - p.weighted_mean) * h[j];
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spec;
  fft.fwd(spec, d);
  bin_frequencies(n, p, [&](long lo, long hi) {
    double sum = 0.0;
    for (long i = lo; i < hi; ++i) sum += std::norm(spec[i]) / p.taper.sum_h2;
    return sum;
  });
  double total = 0.0;
  for (double v : p.mean_ordinate) total += v;
  if (!(total > 0.0) || !std::isfinite(total)) {
    throw std::invalid_argument("likelihood fit: the block differences are constant or not finite");
  }
  return p;
}

struct WhittleModel {
  std::vector<ModelTerm> terms;  // estimated
  double gm_t_s = 0.0;
  // The finest time scale at which a GM's shape can be told from white noise (gm_resolution); its T is
  // searched from kGaussMarkovMinResolution times this.
  double gm_resolution_s = 0.0;
  Eigen::MatrixXd density;  // bins x terms, unit coefficients
  Eigen::VectorXd fixed;    // density of held terms: none in the fit; a profile holds its term here
};

void set_densities(WhittleModel& mod, const Periodogram& p) {
  const long nb = static_cast<long>(p.nu.size());
  mod.density.resize(nb, mod.terms.size());
  for (long b = 0; b < nb; ++b) {
    for (size_t j = 0; j < mod.terms.size(); ++j) {
      mod.density(b, j) = block_difference_density(mod.terms[j], p.nu[b], p.tau_b, mod.gm_t_s);
    }
  }
}

struct Solution {
  Eigen::VectorXd c;  // squared coefficients of WhittleModel::terms
  double log_likelihood = -std::numeric_limits<double>::infinity();
  int iterations = 0;
};

Eigen::VectorXd model_density(const WhittleModel& mod, const Eigen::VectorXd& c) {
  Eigen::VectorXd s = mod.fixed + mod.density * c;
  const double floor = std::max(1e-12 * s.maxCoeff(), std::numeric_limits<double>::min());
  return s.cwiseMax(floor);
}

double whittle_log_likelihood(const Periodogram& p, const Eigen::VectorXd& s) {
  double l = 0.0;
  for (size_t b = 0; b < p.nu.size(); ++b) l -= p.count[b] * (std::log(s(b)) + p.mean_ordinate[b] / s(b));
  return l;
}

// Fisher scoring at a fixed Gauss-Markov time constant. The Whittle score, sum count (I - S) dS/dc
// / S^2 = 0, is the normal equation of least squares of I on the densities with weights count/S^2
// at the current S; re-weighting until it settles is Fisher scoring, kept non-negative exactly.
// A step that lowers the likelihood is halved (a convex combination stays non-negative): undamped, the
// scoring flipped between two points on the paper's HG1900 accelerometers (K at 0, then at 5e-14, and
// back) and ran all 200 iterations in 5 % of the calls of a 16 h record.
Solution maximise_at_fixed_shape(const WhittleModel& mod, const Periodogram& p, Eigen::VectorXd c) {
  Solution sol;
  const Eigen::VectorXd ordinates = Eigen::Map<const Eigen::VectorXd>(p.mean_ordinate.data(), p.nu.size());
  const Eigen::VectorXd counts = Eigen::Map<const Eigen::VectorXd>(p.count.data(), p.nu.size());
  Eigen::VectorXd s = model_density(mod, c);
  double l = whittle_log_likelihood(p, s);
  for (int it = 0; it < 200; ++it) {
    const Eigen::VectorXd w = counts.cwiseSqrt().cwiseQuotient(s);
    const Eigen::MatrixXd A = w.asDiagonal() * mod.density;
    const Eigen::VectorXd y = w.cwiseProduct(ordinates - mod.fixed);
    const Eigen::VectorXd step = nonnegative_least_squares(A, y) - c;
    // Settled when no term moves the model density by more than 1e-8 of itself in any bin. (Per term relative to
    // its own size, a term far too small to matter, like an absent Q on its way to 0, never settles.)
    const Eigen::VectorXd reach = (mod.density.array().colwise() / s.array()).colwise().maxCoeff();
    const double change = (step.cwiseAbs().array() * reach.array()).maxCoeff();
    sol.iterations = it + 1;
    if (!(change >= 1e-8)) break;
    double h = 1.0;
    Eigen::VectorXd next = c + step, s_next = model_density(mod, next);
    double l_next = whittle_log_likelihood(p, s_next);
    while (!(l_next >= l) && h > 1e-3) {
      h *= 0.5;
      next = c + h * step;
      s_next = model_density(mod, next);
      l_next = whittle_log_likelihood(p, s_next);
    }
    if (!(l_next >= l)) break;  // no step up: at the maximum to the precision of the likelihood
    c = next, s = s_next, l = l_next;
  }
  sol.c = c;
  sol.log_likelihood = l;
  return sol;
}

// Golden-section search for the maximum of f on [a, z]; returns the best abscissa, *f_best its value.
template <typename F>
double golden_section_max(const F& f, double a, double z, int iterations, double* f_best) {
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = z - phi * (z - a), x2 = a + phi * (z - a), f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < iterations; ++it) {
    if (f1 > f2) {
      z = x2, x2 = x1, f2 = f1, x1 = z - phi * (z - a), f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + phi * (z - a), f2 = f(x2);
    }
  }
  *f_best = std::max(f1, f2);
  return f1 > f2 ? x1 : x2;
}

// The range of ln T searched. The Gauss-Markov hump sits at 1.89 T: T up to a third of the record; from
// below, T is bounded at a few steps of the model's GM resolution (gm_min_time_constant, noise_fit.hpp:
// shorter, the term is white where N can be seen).
struct LnTRange {
  double lo = 0.0, hi = 0.0;
};
LnTRange gm_search_range(const WhittleModel& mod, const Periodogram& p) {
  const double lo = std::log(gm_min_time_constant(mod.gm_resolution_s));
  return {lo, std::max(lo, std::log(p.blocks * p.tau_b / 3.0))};
}

// The maximum of f over ln T in `range`: `grid` points evenly spaced (and the `start` point already evaluated),
// then golden section within one grid step of the best. The profile in T can have two humps; the grid finds
// the higher one.
struct LnTMaximum {
  double ln_t = 0.0, value = -std::numeric_limits<double>::infinity();
};
template <typename F>
LnTMaximum grid_then_golden_max(const F& f, LnTRange range, int grid, int iterations, LnTMaximum start) {
  const double step = (range.hi - range.lo) / (grid - 1);
  for (int g = 0; g < grid; ++g) {
    const double x = range.lo + g * step, l = f(x);
    if (l > start.value) start = {x, l};
  }
  double refined_l = 0.0;
  const double refined_ln = golden_section_max(f, std::max(range.lo, start.ln_t - step),
                                               std::min(range.hi, start.ln_t + step), iterations, &refined_l);
  return refined_l >= start.value ? LnTMaximum{refined_ln, refined_l} : start;
}

// Profile likelihood over ln T: a log grid, then golden section around its best point.
Solution maximise(WhittleModel& mod, const Periodogram& p, const Eigen::VectorXd& start, int gm_index) {
  if (gm_index < 0) {
    set_densities(mod, p);
    return maximise_at_fixed_shape(mod, p, start);
  }
  auto at = [&](double ln_t) {
    mod.gm_t_s = std::exp(ln_t);
    set_densities(mod, p);
    return maximise_at_fixed_shape(mod, p, start);
  };
  const LnTRange range = gm_search_range(mod, p);
  const LnTMaximum best = grid_then_golden_max([&](double x) { return at(x).log_likelihood; }, range, 24, 30,
                                               {range.lo, -std::numeric_limits<double>::infinity()});
  return at(best.ln_t);
}

// Inverse Fisher information of the squared coefficients in `idx` (and ln T last when the
// Gauss-Markov term is among them with c > 0): sum count g g^T / S^2, g = dS/dparameter.
Eigen::MatrixXd fisher_covariance(const WhittleModel& mod, const Periodogram& p, const Eigen::VectorXd& c,
                                  const std::vector<int>& idx, int gm_index) {
  const bool with_shape = gm_index >= 0 && c(gm_index) > 0 && std::find(idx.begin(), idx.end(), gm_index) != idx.end();
  const int q = static_cast<int>(idx.size()) + (with_shape ? 1 : 0);
  const int shape_col = static_cast<int>(idx.size());
  const long nb = static_cast<long>(p.nu.size());
  const Eigen::VectorXd s = model_density(mod, c);
  Eigen::MatrixXd g(nb, q);
  for (size_t j = 0; j < idx.size(); ++j) g.col(j) = mod.density.col(idx[j]);
  if (with_shape) {
    const double h = 1e-4;
    for (long b = 0; b < nb; ++b) {
      const double up = block_difference_density(ModelTerm::kGaussMarkov, p.nu[b], p.tau_b, mod.gm_t_s * std::exp(h));
      const double dn = block_difference_density(ModelTerm::kGaussMarkov, p.nu[b], p.tau_b, mod.gm_t_s * std::exp(-h));
      g(b, shape_col) = c(gm_index) * (up - dn) / (2.0 * h);
    }
  }
  for (long b = 0; b < nb; ++b) g.row(b) *= std::sqrt(p.count[b]) / s(b);
  Eigen::VectorXd scale(q);
  for (int j = 0; j < q; ++j) {
    scale(j) = g.col(j).norm();
    if (scale(j) > 0) g.col(j) /= scale(j);
  }
  const Eigen::MatrixXd info = g.transpose() * g;
  const Eigen::MatrixXd cov = info.completeOrthogonalDecomposition().pseudoInverse();
  // Tapered ordinates carry less information than the count says (about 12 % more variance here).
  return p.taper.variance_factor * scale.cwiseInverse().asDiagonal() * cov * scale.cwiseInverse().asDiagonal();
}

// Likelihood-ratio interval of the Gauss-Markov T (ln T in `range`): the hull of every T whose profile (the
// maximum over the coefficients at that T) is within `drop` of the maximum. A weak GM's profile is flat or has
// two humps; the Fisher sigma at the higher hump then says nothing about the other (the paper's HG1900 gyros:
// T inside T +- 1.96 sigma in 9-13 of 20 records). Ends at the search range when the profile never falls that far.
LnTRange time_constant_interval(const WhittleModel& mod, const Periodogram& p, const Solution& best, double drop,
                                LnTRange range) {
  WhittleModel at_t = mod;
  const double target = best.log_likelihood - drop;
  auto above = [&](double ln_t) {
    at_t.gm_t_s = std::exp(ln_t);
    set_densities(at_t, p);
    return maximise_at_fixed_shape(at_t, p, best.c).log_likelihood >= target;
  };
  const double ln_best = std::log(mod.gm_t_s);
  const int grid = 48;
  const double step = (range.hi - range.lo) / (grid - 1);
  LnTRange hull{ln_best, ln_best};
  for (int g = 0; g < grid; ++g) {
    const double x = range.lo + g * step;
    if (above(x)) hull.lo = std::min(hull.lo, x), hull.hi = std::max(hull.hi, x);
  }
  auto bisect = [&](double inside, double outside) {
    for (int it = 0; it < 12; ++it) {
      const double mid = 0.5 * (inside + outside);
      (above(mid) ? inside : outside) = mid;
    }
    return 0.5 * (inside + outside);
  };
  // From the outermost grid point above the target to the next one out (or to the estimate itself).
  const double lo_out = std::max(range.lo, std::min(hull.lo, ln_best) - step),
               hi_out = std::min(range.hi, std::max(hull.hi, ln_best) + step);
  return {above(lo_out) ? lo_out : bisect(hull.lo, lo_out), above(hi_out) ? hi_out : bisect(hull.hi, hi_out)};
}

// Profile likelihood of term j's squared coefficient: the maximum over the other terms (and the
// Gauss-Markov T, searched over `ln_t`, its own interval a little widened) with c_j held at cj.
double profile_log_likelihood(const WhittleModel& mod, const Periodogram& p, const Solution& best, int j, double cj,
                              LnTRange ln_t) {
  WhittleModel sub;
  std::vector<int> others;
  for (int i = 0; i < static_cast<int>(mod.terms.size()); ++i) {
    if (i != j) sub.terms.push_back(mod.terms[i]), others.push_back(i);
  }
  Eigen::VectorXd start(others.size());
  for (size_t i = 0; i < others.size(); ++i) start(i) = best.c(others[i]);
  const bool has_gm = std::find(mod.terms.begin(), mod.terms.end(), ModelTerm::kGaussMarkov) != mod.terms.end();
  auto at = [&](double ln_t) {
    sub.gm_t_s = std::exp(ln_t);
    set_densities(sub, p);
    sub.fixed = mod.fixed;
    for (size_t b = 0; b < p.nu.size(); ++b) {
      sub.fixed(b) += cj * block_difference_density(mod.terms[j], p.nu[b], p.tau_b, sub.gm_t_s);
    }
    if (sub.terms.empty()) return whittle_log_likelihood(p, model_density(sub, Eigen::VectorXd()));
    return maximise_at_fixed_shape(sub, p, start).log_likelihood;
  };
  const double ln_t0 = std::log(std::max(mod.gm_t_s, 1e-300));
  if (!has_gm || !(ln_t.hi > ln_t.lo)) return at(ln_t0);
  // A coarse grid (steps of at most 0.5 in ln T) from the estimate's own T.
  const int grid = std::clamp(static_cast<int>(std::ceil((ln_t.hi - ln_t.lo) / 0.5)) + 1, 2, 12);
  return grid_then_golden_max(at, ln_t, grid, 10, {ln_t0, at(ln_t0)}).value;
}

// Likelihood-ratio interval of c_j: where the profile falls `drop` (chi2_1 quantile / 2) below
// the maximum. Unlike the Fisher interval, it does not shrink with a low estimate (the
// information about a variance is evaluated at that variance), which matters for a term seen
// in a handful of ordinates, like K in a few hours of a tactical gyro.
std::pair<double, double> profile_interval(const WhittleModel& mod, const Periodogram& p, const Solution& best, int j,
                                           double drop, double sigma_c, LnTRange ln_t) {
  const double target = best.log_likelihood - drop;
  // Not finite counts as below: a failed profile is no evidence for the value.
  auto below = [&](double c) { return !(profile_log_likelihood(mod, p, best, j, c, ln_t) >= target); };
  auto bisect = [&](double inside, double outside) {  // in ln c
    for (int it = 0; it < 14; ++it) {
      const double mid = std::sqrt(inside * outside);
      (below(mid) ? outside : inside) = mid;
    }
    return std::sqrt(inside * outside);
  };
  // The upper end, bracketed between a value inside and one outside. An estimate of 0 has no scale of its
  // own: from its Fisher sigma, halved until inside. (That sigma was once taken as inside unchecked: where
  // another term can stand in for this one, e.g. a Gauss-Markov at the longest T for K, the sigma is huge and
  // the interval reached 8.5x the truth.)
  double inside = best.c(j);
  if (!(inside > 0)) {
    inside = std::max(sigma_c, 1e-300);
    int shrink = 0;
    while (below(inside) && shrink++ < 60) inside /= 2.0;
  }
  double outside = inside * 2.0;
  int grow = 0;
  while (!below(outside) && grow++ < 40) inside = outside, outside *= 2.0;
  const double upper = bisect(inside, outside);
  double lower = 0.0;
  if (best.c(j) > 0 && below(0.0)) {
    double lo = best.c(j) / 2.0;
    int shrink = 0;
    while (!below(lo) && shrink++ < 60) lo /= 2.0;
    lower = bisect(2.0 * lo > best.c(j) ? best.c(j) : 2.0 * lo, lo);
  }
  return {lower, upper};
}

// The rate ramp R from the taper-weighted mean of d (= R tau_b plus noise). Its variance,
// sum h_j h_k gamma(j - k) / (sum h)^2: a random walk's d is white at frequency 0 (K^2 tau_b
// sum h^2); every other term's d is a difference, which summation by parts turns into the block
// means weighted by the taper's steps (S_ybar near frequency 0 times sum (dh)^2).
void ramp_estimate(const WhittleModel& mod, const Periodogram& p, const Eigen::VectorXd& c, double& r,
                   double& sigma_r) {
  const double nu_edge = 1.0 / static_cast<double>(p.taper.edge), s_edge = std::sin(M_PI * nu_edge);
  double var = 0.0;
  for (size_t j = 0; j < mod.terms.size(); ++j) {
    if (mod.terms[j] == ModelTerm::kK) {
      var += c(j) * block_difference_density(ModelTerm::kK, 0.0, p.tau_b) * p.taper.sum_h2;
    } else {
      const double s_ybar =
          block_difference_density(mod.terms[j], nu_edge, p.tau_b, mod.gm_t_s) / (4.0 * s_edge * s_edge);
      var += c(j) * s_ybar * p.taper.sum_dh2;
    }
  }
  r = std::fabs(p.weighted_mean) / p.tau_b;
  sigma_r = std::sqrt(std::max(0.0, var)) / p.taper.sum_h / p.tau_b;
}

// The member of `b` (const or not) that holds the bound of term t: N, B, K or GM sigma; else null.
template <typename Bounds>
decltype(&std::declval<Bounds&>().n) bound_slot(Bounds& b, ModelTerm t) {
  switch (t) {
    case ModelTerm::kQ:
      return &b.q;
    case ModelTerm::kN:
      return &b.n;
    case ModelTerm::kB:
      return &b.b;
    case ModelTerm::kK:
      return &b.k;
    case ModelTerm::kGaussMarkov:
      return &b.gm_sigma;
    default:
      return nullptr;
  }
}

// The finest time scale at which a Gauss-Markov's shape can be told from white noise: the block length,
// or longer where the held Q hides N. Above the frequency nu_c (cycles per block) at which Q's density
// passes N's, the white level is not seen, so a GM whose corner 1/(2 pi T) lies there is N's double in
// the only band where N shows: on the HG1700 gyros (Q 6-17 arcsec, N 0.04 deg/sqrt(h), nu_c 0.19-0.44 Hz
// at 100 Hz) a forced GM with T of 0.3-2 s took N 1-6 % low. Resolution: the period whose Nyquist is
// nu_c, tau_b / (2 nu_c), as tau_b is the block band's. `n_density`: N's squared coefficient (0: no N).
double gm_resolution(const Periodogram& p, const Eigen::VectorXd& q_density, double n_density) {
  if (!(n_density > 0.0)) return p.tau_b;
  for (size_t b = 0; b < p.nu.size(); ++b) {
    if (q_density(static_cast<long>(b)) >= n_density * block_difference_density(ModelTerm::kN, p.nu[b], p.tau_b))
      return p.tau_b / (2.0 * p.nu[b]);
  }
  return p.tau_b;
}

}  // namespace

NoiseFit whittle_fit(const PhaseSeries& s, const NoiseFit& curve, const FitOptions& opt, double block_s,
                     WhittleSummary* summary) {
  if (opt.sinusoid) throw std::invalid_argument("likelihood fit: not with a sinusoid in the model");
  const long m = std::max(1L, std::lround(block_s / s.tau0_s));
  const Periodogram p = periodogram_of_block_differences(s, m);

  WhittleModel mod;
  // Q is estimated with the others, not held at the curve fit's value. Where it is weak against N (3-5 % of N's
  // Allan deviation at tau0, the paper's 3DM-GX2 accelerometer X: the record bounds it to 2.7x its value) any
  // estimate of Q is 0 or several times the truth, and N trades against it. At Q held, N's interval, even widened
  // by the curve fit's sigma of Q (none at Q = 0), held the true N in 17 of 20 records; estimated together, N's
  // profile interval is over Q too: 19 of 20.
  const bool q_in_model = opt.q && curve[ModelTerm::kQ].in_model;
  const int q_index = q_in_model ? 0 : -1;  // Q first among the terms when it is in the model
  if (q_in_model) mod.terms.push_back(ModelTerm::kQ);
  if (opt.n) mod.terms.push_back(ModelTerm::kN);
  if (opt.b && !opt.gauss_markov) mod.terms.push_back(ModelTerm::kB);
  if (opt.k) mod.terms.push_back(ModelTerm::kK);
  int gm_index = -1;
  if (opt.gauss_markov) {
    gm_index = static_cast<int>(mod.terms.size());
    mod.terms.push_back(ModelTerm::kGaussMarkov);
    mod.gm_t_s = curve[ModelTerm::kGaussMarkov].shape;
  }
  if (mod.terms.empty()) throw std::invalid_argument("likelihood fit: none of Q, N, B, K in the model");
  const int parameters = static_cast<int>(mod.terms.size()) + (gm_index >= 0 ? 1 : 0);
  mod.fixed = Eigen::VectorXd::Zero(static_cast<long>(p.nu.size()));
  set_densities(mod, p);
  // Q's density at a squared coefficient c_q (0 without Q in the model), for the frequency where it passes N's.
  auto q_density = [&](double c_q) -> Eigen::VectorXd {
    if (q_index < 0) return Eigen::VectorXd::Zero(static_cast<long>(p.nu.size()));
    return c_q * mod.density.col(q_index);
  };
  const double q_curve = q_in_model ? curve[ModelTerm::kQ].value : 0.0;
  // Only an N the curve fit resolved (significant and dominant at some tau): a sensor without white noise (the
  // paper's HG1900 accelerometers, Q + GM + K) has no N for a GM to double. Ungated, the small curve N that
  // chance leaves there (inside its sigma) put nu_c near 0 and pushed T's floor past the true T (accelerometer X:
  // GM chosen in 8 of 20 records where it was 20, K within 30 % in 8 where it was 20).
  const TermEstimate& n_curve = curve[ModelTerm::kN];
  const bool n_present = opt.n && n_curve.in_model && n_curve.resolved;
  mod.gm_resolution_s = gm_resolution(p, q_density(q_curve * q_curve), n_present ? n_curve.value * n_curve.value : 0.0);

  // Start from the curve fit; a term it left at 0 starts small but positive, so the scoring can
  // still bring it in.
  Eigen::VectorXd start(mod.terms.size());
  for (size_t j = 0; j < mod.terms.size(); ++j) {
    const double v = curve[mod.terms[j]].value;
    double reach = 0.0;  // the coefficient at which this term alone would explain some bin
    for (size_t b = 0; b < p.nu.size(); ++b)
      reach = std::max(reach, p.mean_ordinate[b] / std::max(mod.density(b, j), 1e-300));
    start(j) = std::max(v * v, 1e-4 * reach);
  }
  Solution sol = maximise(mod, p, start, gm_index);
  if (!sol.c.allFinite() || !std::isfinite(sol.log_likelihood)) {
    throw std::invalid_argument("likelihood fit: no finite maximum (the curve fit is kept)");
  }
  // The curve fit did not resolve N (dominant nowhere: Q, then the GM), yet the fit may hold white noise where N
  // shows: N, plus a GM whose corner 1/(2 pi T) lies above the frequency 1 / (2 resolution) at which Q passes
  // that white level, so it is white (density 2 sigma^2 T) wherever N is seen, and the split between the two is
  // all the data cannot tell. That level sets the resolution as a resolved N's would, and the GM is searched
  // again from there (folded into N below if it stays at the floor). Forced GM, T 0.13-0.5 s took N 12-14 % low
  // on the 3DM-GX2 gyro Z and the HG1700 gyro Z (one or two seeds of 20 each). A GM with its corner below that
  // frequency has a shape the data see (the HG1900 accelerometers, T 4-9 s found for 28-33 s) and is kept.
  const auto n_term = std::find(mod.terms.begin(), mod.terms.end(), ModelTerm::kN);
  const bool n_in_model = n_term != mod.terms.end();
  if (!n_present && gm_index >= 0 && n_in_model && sol.c(gm_index) > 0) {
    const double white = sol.c(n_term - mod.terms.begin()) + 2.0 * sol.c(gm_index) * mod.gm_t_s;
    const double resolution = gm_resolution(p, q_density(q_index >= 0 ? sol.c(q_index) : 0.0), white);
    if (resolution > mod.gm_resolution_s && mod.gm_t_s <= resolution / M_PI) {
      WhittleModel refit = mod;  // maximise moves T and the densities: kept only with a finite maximum
      refit.gm_resolution_s = resolution;
      Solution again = maximise(refit, p, start, gm_index);
      if (again.c.allFinite() && std::isfinite(again.log_likelihood)) mod = std::move(refit), sol = std::move(again);
    }
  }
  // A Gauss-Markov term still pulled to its shortest T is white noise where N shows (density
  // 2 sigma^2 T): fold it into N by refitting without it, and report it absent (value 0, T at the
  // bound, the upper end of its interval from its profile over T).
  const double gm_t_min = gm_min_time_constant(mod.gm_resolution_s);
  struct FoldedGm {
    WhittleModel with_gm;  // the model with the GM in it, at the floor's T, for its sigma's profile
    Solution at_zero;      // the folded fit as a solution of that model (GM at 0)
    int index = -1;        // the GM's term in with_gm
    double sigma_c = 0.0;  // the Fisher sigma of its squared coefficient there
  };
  std::optional<FoldedGm> folded_gm;
  if (gm_index >= 0 && sol.c(gm_index) > 0 && gm_time_constant_at_bound(mod.gm_t_s, mod.gm_resolution_s) &&
      n_in_model) {
    WhittleModel without = mod;
    without.terms.erase(without.terms.begin() + gm_index);
    Eigen::VectorXd start_without(without.terms.size());
    for (int j = 0, i = 0; j < static_cast<int>(mod.terms.size()); ++j)
      if (j != gm_index) start_without(i++) = std::max(sol.c(j), start(j));
    Solution folded = maximise(without, p, start_without, -1);
    if (folded.c.allFinite() && std::isfinite(folded.log_likelihood)) {
      mod.gm_t_s = gm_t_min;
      set_densities(mod, p);
      Eigen::VectorXd c_full(mod.terms.size());
      for (int j = 0, i = 0; j < static_cast<int>(mod.terms.size()); ++j) c_full(j) = j == gm_index ? 0.0 : folded.c(i++);
      std::vector<int> with;
      for (int j = 0; j < c_full.size(); ++j)
        if (c_full(j) > 0 && j != gm_index) with.push_back(j);
      with.push_back(gm_index);
      const double sigma_c =
          std::sqrt(std::max(0.0, fisher_covariance(mod, p, c_full, with, gm_index)(with.size() - 1, with.size() - 1)));
      folded_gm = FoldedGm{mod, Solution{c_full, folded.log_likelihood, folded.iterations}, gm_index, sigma_c};
      mod = std::move(without);
      sol = std::move(folded);
      gm_index = -1;
    }
  }

  NoiseFit out = curve;
  out.method = "whittle";
  // Dominant somewhere: the term carries at least half of the whole model's Allan variance at some
  // tau between tau0 and a quarter of the record (`out` holds the other terms' final values).
  const double tau_lo = s.tau0_s, tau_hi = 0.25 * s.tau0_s * (static_cast<double>(s.x.size()) - 1);
  auto dominant_somewhere = [&](ModelTerm term, double c, double shape) {
    for (int i = 0; i <= 60 && tau_hi > tau_lo; ++i) {
      const double tau = tau_lo * std::pow(tau_hi / tau_lo, i / 60.0);
      if (c * term_avar(term, tau, shape) >= 0.5 * out.model_avar(tau)) return true;
    }
    return false;
  };
  const double z = math::normal_quantile(0.5 + 0.5 * opt.interval_confidence);
  // The tapered likelihood is sharper than the information it holds by the taper's variance factor.
  const double drop = 0.5 * z * z * p.taper.variance_factor;
  // T's interval from its profile, and the others' profiles search T over it (widened by a quarter in ln T).
  LnTRange t_interval{std::log(std::max(mod.gm_t_s, 1e-300)), std::log(std::max(mod.gm_t_s, 1e-300))};
  LnTRange t_search = t_interval;
  if (gm_index >= 0 && sol.c(gm_index) > 0) {
    const LnTRange range = gm_search_range(mod, p);
    t_interval = time_constant_interval(mod, p, sol, drop, range);
    t_search = {std::max(range.lo, t_interval.lo - 0.25), std::min(range.hi, t_interval.hi + 0.25)};
  }
  std::vector<int> active, all;
  for (int j = 0; j < sol.c.size(); ++j) {
    all.push_back(j);
    if (sol.c(j) > 0) active.push_back(j);
  }
  const Eigen::MatrixXd cov_active = fisher_covariance(mod, p, sol.c, active, gm_index);
  const Eigen::MatrixXd cov_all = fisher_covariance(mod, p, sol.c, all, gm_index);
  std::vector<double> sigma_c(sol.c.size()), sigma_free(sol.c.size());
  for (int j = 0; j < sol.c.size(); ++j) {
    const auto it = std::find(active.begin(), active.end(), j);
    double var_c;
    if (it != active.end()) {
      var_c = cov_active(it - active.begin(), it - active.begin());
    } else {  // at the bound: its uncertainty as if it were free, next to the active terms
      std::vector<int> with = active;
      with.push_back(j);
      var_c = fisher_covariance(mod, p, sol.c, with, gm_index)(with.size() - 1, with.size() - 1);
    }
    sigma_c[j] = std::sqrt(std::max(0.0, var_c));
    sigma_free[j] = std::sqrt(std::max(0.0, cov_all(j, j)));
    TermEstimate& t = out[mod.terms[j]];
    t.in_model = true;
    t.shape = mod.terms[j] == ModelTerm::kGaussMarkov ? mod.gm_t_s : 0.0;
    t.shape_sigma = 0.0;
    t.shape_lo = t.shape_hi = 0.0;
    set_term_interval(t, sol.c(j), sigma_c[j], z);
    // Q lives at the highest frequencies, a decade and more above any GM corner the search allows: its profile
    // holds T at the estimate (searching it too cost 40 % of `ldv allan`'s time on a 16 h record).
    const double ln_t = std::log(std::max(mod.gm_t_s, 1e-300));
    const LnTRange t_profile = mod.terms[j] == ModelTerm::kQ ? LnTRange{ln_t, ln_t} : t_search;
    const auto [lo, hi] = profile_interval(mod, p, sol, j, drop, sigma_c[j], t_profile);
    t.lo = std::sqrt(lo);
    t.hi = std::sqrt(hi);
  }
  if (gm_index >= 0 && sol.c(gm_index) > 0) {
    const long last = static_cast<long>(active.size());
    TermEstimate& gm = out[ModelTerm::kGaussMarkov];
    gm.shape_sigma = mod.gm_t_s * std::sqrt(std::max(0.0, cov_active(last, last)));
    gm.shape_lo = std::exp(t_interval.lo);
    gm.shape_hi = std::exp(t_interval.hi);
  }
  // The ramp from the same data: a constant in d, judged against the noise the fitted terms put
  // into that constant (a random walk mostly), not against a curve that trades R for K.
  if (opt.r) {
    double r = 0.0, sigma_r = 0.0;
    ramp_estimate(mod, p, sol.c, r, sigma_r);
    TermEstimate& t = out[ModelTerm::kR];
    t.in_model = true;
    t.value = r;
    t.sigma = sigma_r;
    t.lo = std::max(0.0, r - z * sigma_r);
    t.hi = r + z * sigma_r;
    // The walk's own excursion over the record looks like a ramp, and its size is known only as
    // well as K: the ramp counts as resolved when it stands out even at the largest K the data
    // allow (the upper end of K's interval), at 3 sigma, since it is a signed estimate tested
    // two-sided (2 sigma would call a ramp on one of six channels in every fourth run).
    double sigma_r_worst = sigma_r;
    const auto k_it = std::find(mod.terms.begin(), mod.terms.end(), ModelTerm::kK);
    if (k_it != mod.terms.end()) {
      Eigen::VectorXd c_worst = sol.c;
      const double k_hi = out[ModelTerm::kK].hi;
      c_worst(k_it - mod.terms.begin()) = std::max(sol.c(k_it - mod.terms.begin()), k_hi * k_hi);
      double r_unused = 0.0;
      ramp_estimate(mod, p, c_worst, r_unused, sigma_r_worst);
    }
    t.resolved = r > 3.0 * sigma_r_worst && dominant_somewhere(ModelTerm::kR, r * r, 0.0);
  }
  // Resolved: significant with every term free, and dominant somewhere.
  for (int j = 0; j < sol.c.size(); ++j) {
    TermEstimate& t = out[mod.terms[j]];
    t.resolved =
        sol.c(j) > 2.0 * std::max(sigma_c[j], sigma_free[j]) && dominant_somewhere(mod.terms[j], sol.c(j), t.shape);
  }
  if (folded_gm) {  // folded into N: absent, with only an upper end to its interval
    TermEstimate& t = out[ModelTerm::kGaussMarkov];
    t.in_model = true;
    t.shape = gm_t_min;
    t.shape_sigma = 0.0;
    t.shape_lo = t.shape_hi = 0.0;
    set_term_interval(t, 0.0, folded_gm->sigma_c, z);
    // The upper end from the profile over every T the search allows, not from the information at the floor
    // alone: the fold is decided where the GM is white, but a slower GM of some size may stand in for K. Forced
    // GM, 3DM-GX2 gyro Z, seed 7 of the study: folded, and the end at the floor's T missed the true sigma.
    const auto [lo_unused, hi_c] = profile_interval(folded_gm->with_gm, p, folded_gm->at_zero, folded_gm->index, drop,
                                                    folded_gm->sigma_c, gm_search_range(folded_gm->with_gm, p));
    if (std::isfinite(hi_c)) t.hi = std::max(t.hi, std::sqrt(hi_c));
    t.resolved = false;
  }
  for (ModelTerm term : mod.terms) {
    const TermEstimate& t = out[term];
    if (!std::isfinite(t.value + t.sigma + t.lo + t.hi + t.shape + t.shape_sigma)) {
      throw std::invalid_argument(std::string("likelihood fit: ") + model_term_name(term) +
                                  " not finite (the curve fit is kept)");
    }
  }
  if (summary) {
    summary->block_s = p.tau_b;
    summary->gm_resolution_s = mod.gm_resolution_s;  // `without`, if folded, is mod's copy: the same
    summary->ordinates = p.ordinates;
    summary->log_likelihood = sol.log_likelihood;
    summary->iterations = sol.iterations;
    summary->parameters = parameters;
    summary->taper_variance_factor = p.taper.variance_factor;
  }
  return out;
}

RelativeBounds whittle_cramer_rao(const NoiseLevels& truth, double tau0_s, long samples, double block_s) {
  const long m = std::max(1L, std::lround(block_s / tau0_s));
  Periodogram p;
  p.tau_b = m * tau0_s;
  const long blocks = samples / m;
  if (blocks < 65) throw std::invalid_argument("Cramer-Rao bound: fewer than 65 blocks");
  const long n = smooth_length(blocks - 1);
  p.blocks = n;
  // The taper's variance factor depends on its shape only (1.12 beyond a few hundred blocks).
  p.taper.variance_factor = split_cosine_bell_sums(std::min(n, 100000L)).variance_factor;
  bin_frequencies(n, p, [](long, long) { return 0.0; });
  WhittleModel mod;
  std::vector<double> c;
  int gm_index = -1;
  auto add = [&](ModelTerm t, double level) {
    if (level <= 0) return;
    if (t == ModelTerm::kGaussMarkov) gm_index = static_cast<int>(mod.terms.size());
    mod.terms.push_back(t);
    c.push_back(level * level);
  };
  add(ModelTerm::kQ, truth.q);
  add(ModelTerm::kN, truth.n);
  add(ModelTerm::kB, truth.b);
  add(ModelTerm::kK, truth.k);
  add(ModelTerm::kGaussMarkov, truth.gm_sigma);
  mod.gm_t_s = truth.gm_t_s;
  mod.fixed = Eigen::VectorXd::Zero(static_cast<long>(p.nu.size()));
  set_densities(mod, p);
  const Eigen::VectorXd cv = Eigen::Map<const Eigen::VectorXd>(c.data(), c.size());
  std::vector<int> all(c.size());
  for (size_t j = 0; j < c.size(); ++j) all[j] = static_cast<int>(j);
  const Eigen::MatrixXd cov = fisher_covariance(mod, p, cv, all, gm_index);
  RelativeBounds out;
  for (size_t j = 0; j < c.size(); ++j) {
    const double rel = 0.5 * std::sqrt(std::max(0.0, cov(j, j))) / c[j];  // sd(sqrt c)/sqrt c
    if (double* slot = bound_slot(out, mod.terms[j])) *slot = rel;
  }
  if (gm_index >= 0) out.gm_t = std::sqrt(std::max(0.0, cov(c.size(), c.size())));
  return out;
}

RecordInformation record_information(const NoiseFit& fit, double tau0_s, long samples, double block_s, double target) {
  RecordInformation info;
  info.target = target;
  NoiseLevels lv;
  auto level = [&](ModelTerm t) { return fit[t].in_model ? fit[t].value : 0.0; };
  lv.q = level(ModelTerm::kQ), lv.n = level(ModelTerm::kN), lv.b = level(ModelTerm::kB), lv.k = level(ModelTerm::kK);
  lv.gm_sigma = level(ModelTerm::kGaussMarkov), lv.gm_t_s = fit[ModelTerm::kGaussMarkov].shape;
  if (lv.gm_sigma > 0 && !(lv.gm_t_s > 0)) lv.gm_sigma = 0.0;
  info.now = whittle_cramer_rao(lv, tau0_s, samples, block_s);
  const double block = std::max(1L, std::lround(block_s / tau0_s)) * tau0_s;
  // The bound falls with the record (as 1/sqrt(length) once every term has shown itself):
  // bisection in ln(length) between 100 blocks and 1000 h.
  for (ModelTerm t : {ModelTerm::kN, ModelTerm::kB, ModelTerm::kK, ModelTerm::kGaussMarkov}) {
    double& hours = t == ModelTerm::kN ? info.hours_n : t == ModelTerm::kK ? info.hours_k : info.hours_b;
    if (!fit[t].in_model || !fit[t].resolved || !(*bound_slot(info.now, t) > 0)) continue;
    auto sd_at = [&](double seconds) {
      const RelativeBounds b = whittle_cramer_rao(lv, tau0_s, static_cast<long>(seconds / tau0_s), block_s);
      return *bound_slot(b, t);
    };
    double lo = 100.0 * block, hi = 1000.0 * 3600.0;
    if (sd_at(hi) > target) {
      hours = std::numeric_limits<double>::infinity();
      continue;
    }
    if (sd_at(lo) <= target) hi = lo;
    for (int it = 0; it < 30 && hi / lo > 1.01; ++it) {
      const double mid = std::sqrt(lo * hi);
      (sd_at(mid) <= target ? hi : lo) = mid;
    }
    hours = hi / 3600.0;
  }
  return info;
}

}  // namespace ldv::allan
