#include "toolbox/allan/avar_covariance.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ldv::allan {
namespace {

using real = double;

// Generalized autocovariance of the phase at lag `lag` samples (see the header); the white-PM
// delta only where the lag is exactly zero (at integer kinks, `delta`).
struct PhaseGcov {
  real q2, n2, b2, k2, g2, t_samples, tau0;
  real operator()(real lag, bool delta) const {
    const real a = std::fabs(lag) * tau0;
    real v = -0.5 * n2 * a + k2 * a * a * a / 12.0;
    if (a == 0.0) {
      if (delta) v += q2;
    } else if (b2 > 0) {
      v += b2 * a * a * std::log(a) / (2.0 * static_cast<real>(M_PI));
    }
    if (g2 > 0) {
      const real u = std::fabs(lag) / t_samples;
      v -= g2 * t_samples * t_samples * tau0 * tau0 * (u + std::expm1(-u));
    }
    return v;
  }
};

struct Pair {
  const PhaseGcov* g;
  long m1, m2, n1, n2;
  real norm;  // 1 / (2 tau1 tau2)

  real r12(real k, bool delta) const {
    static constexpr real a[3] = {1.0, -2.0, 1.0};
    real s = 0.0;
    for (int p = 0; p < 3; ++p) {
      for (int q = 0; q < 3; ++q) {
        const real lag = static_cast<real>(p * m1 - q * m2) - k;
        s += a[p] * a[q] * (*g)(lag, delta && lag == 0.0);
      }
    }
    return s * norm;
  }
  real cnt(real k) const {
    return std::max<real>(0.0, std::min<real>(n1, n2 - k) - std::max<real>(0.0, -k));
  }
  int power = 2;  // sum cnt r^2 (Gaussian part) or cnt r (cross term with a deterministic ramp)
  real f(real k, bool delta) const {
    const real r = r12(k, delta);
    return cnt(k) * (power == 2 ? r * r : r);
  }
};

constexpr real kGlX[4] = {0.1834346424956498049, 0.5255324099163289858, 0.7966664774136267396,
                          0.9602898564975362317};
constexpr real kGlW[4] = {0.3626837833783619830, 0.3137066458778872873, 0.2223810344533744706,
                          0.1012285362903762592};

real gauss_legendre(const Pair& pr, real a, real b) {
  const real c = 0.5 * (a + b), h = 0.5 * (b - a);
  real s = 0.0;
  for (int i = 0; i < 4; ++i) s += kGlW[i] * (pr.f(c - h * kGlX[i], false) + pr.f(c + h * kGlX[i], false));
  return s * h;
}

// sum of f(k) for integer k in [a, b): exact when short, else integral with the end correction.
real segment_sum(const Pair& pr, long a, long b, real smooth_scale) {
  if (b - a <= 48) {
    real s = 0.0;
    for (long k = a; k < b; ++k) s += pr.f(static_cast<real>(k), true);
    return s;
  }
  const real fa = static_cast<real>(a), fb = static_cast<real>(b), mid = 0.5 * (fa + fb);
  const real h0 = std::max<real>(2.0, std::min<real>((fb - fa) / 16.0, smooth_scale / 4.0));
  real integral = 0.0;
  for (int side = 0; side < 2; ++side) {  // geometrically graded from each end to the middle
    real x = side == 0 ? fa : fb, h = h0;
    while (side == 0 ? x < mid : x > mid) {
      const real nx = side == 0 ? std::min(mid, x + h) : std::max(mid, x - h);
      integral += side == 0 ? gauss_legendre(pr, x, nx) : gauss_legendre(pr, nx, x);
      x = nx;
      h *= 2.0;
    }
  }
  // sum_{k=a}^{b-1} f = f(a) + sum_{a<k<b} f,  sum_{a<k<b} f ~ integral - (f(a) + f(b)) / 2.
  return pr.f(fa, true) + integral - 0.5 * (pr.f(fa, false) + pr.f(fb, false));
}

}  // namespace

std::vector<double> oavar_covariance(const NoiseLevels& lv, const std::vector<long>& ms, double tau0_s,
                                     long n_phase) {
  const size_t p = ms.size();
  std::vector<double> cov(p * p, 0.0);
  for (long m : ms) {
    if (m < 1 || n_phase - 2 * m < 1) throw std::invalid_argument("oavar_covariance: averaging factor beyond the data");
  }
  const bool gm = lv.gm_sigma > 0 && lv.gm_t_s > 0;
  PhaseGcov g{static_cast<real>(lv.q) * lv.q,
              static_cast<real>(lv.n) * lv.n,
              static_cast<real>(lv.b) * lv.b,
              static_cast<real>(lv.k) * lv.k,
              gm ? static_cast<real>(lv.gm_sigma) * lv.gm_sigma : 0.0,
              gm ? static_cast<real>(lv.gm_t_s / tau0_s) : 1.0,
              static_cast<real>(tau0_s)};
  for (size_t i = 0; i < p; ++i) {
    for (size_t j = i; j < p; ++j) {
      Pair pr{&g, ms[i], ms[j], n_phase - 2 * ms[i], n_phase - 2 * ms[j], 0.0};
      pr.norm = 1.0 / (2.0 * ms[i] * ms[j] * g.tau0 * g.tau0);
      // Lags where the sum is not zero: the difference windows overlap, plus the decay of the
      // Gauss-Markov and flicker correlations beyond.
      long ext = 0;
      if (gm) ext = std::max(ext, static_cast<long>(std::ceil(12.0 * g.t_samples)));
      if (lv.b > 0) ext = std::max(ext, 16 * (ms[i] + ms[j]));
      const long lo = std::max(-(pr.n1 - 1), -2 * ms[j] - ext), hi = std::min(pr.n2 - 1, 2 * ms[i] + ext);
      if (lo > hi) continue;
      std::vector<long> br = {lo, hi + 1, 0, pr.n2 - pr.n1};
      for (long a = 0; a < 3; ++a) for (long b = 0; b < 3; ++b) br.push_back(a * ms[i] - b * ms[j]);
      std::sort(br.begin(), br.end());
      br.erase(std::unique(br.begin(), br.end()), br.end());
      const real smooth = gm ? g.t_samples : static_cast<real>(hi - lo);
      auto lag_sum = [&] {
        real s = 0.0;
        for (size_t b = 0; b + 1 < br.size(); ++b) {
          const long a0 = std::max(br[b], lo), a1 = std::min(br[b + 1], hi + 1);
          if (a1 > a0) s += segment_sum(pr, a0, a1, smooth);
        }
        return s;
      };
      real s = 2.0 * lag_sum();
      if (lv.r > 0) {
        // A ramp R t in the rate shifts every D_i by mu = R tau / sqrt(2); the estimate then
        // carries 2 mu D_i as well: + 4 mu1 mu2 sum_k cnt(k) r12(k) (n1 n2 divided out below).
        pr.power = 1;
        s += 2.0 * static_cast<real>(lv.r) * lv.r * ms[i] * ms[j] * g.tau0 * g.tau0 * lag_sum();
      }
      const double c = static_cast<double>(s / (static_cast<real>(pr.n1) * pr.n2));
      cov[i * p + j] = cov[j * p + i] = c;
    }
  }
  return cov;
}

}  // namespace ldv::allan
