#include "toolbox/allan/noise_id.hpp"

#include <cmath>

namespace ldv::allan {
namespace {

// Removes the least-squares polynomial of degree 1 or 2 (orthogonal basis on a uniform grid).
void detrend(std::vector<double>& z, int degree) {
  const size_t n = z.size();
  if (n < 3) return;
  const double c = 0.5 * (n - 1.0);
  // Orthogonal polynomials on t = i - c: p0 = 1, p1 = t, p2 = t^2 - (n^2-1)/12.
  const double q = (static_cast<double>(n) * n - 1.0) / 12.0;
  double s0 = 0, s1 = 0, s2 = 0, n1 = 0, n2 = 0;
  for (size_t i = 0; i < n; ++i) {
    const double t = i - c, p2 = t * t - q;
    s0 += z[i];
    s1 += z[i] * t;
    s2 += z[i] * p2;
    n1 += t * t;
    n2 += p2 * p2;
  }
  const double b0 = s0 / n, b1 = s1 / n1, b2 = (degree >= 2 && n2 > 0) ? s2 / n2 : 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double t = i - c;
    z[i] -= b0 + b1 * t + b2 * (t * t - q);
  }
}

// B1 = (sample variance of the m-averaged frequency) / (Allan variance at m), expected value for
// power-law exponent mu of the Allan variance (sigma^2 ~ tau^mu) and Nf averaged points.
double b1_expected(double nf, int mu) {
  switch (mu) {
    case 2: return nf * (nf + 1.0) / 6.0;
    case 1: return nf / 2.0;
    case 0: return nf * std::log(nf) / (2.0 * (nf - 1.0) * std::log(2.0));
    case -1: return 1.0;
    case -2: return (nf * nf - 1.0) / (1.5 * nf * (nf - 1.0));
    default: return nf * (1.0 - std::pow(nf, mu)) / (2.0 * (nf - 1.0) * (1.0 - std::pow(2.0, mu)));
  }
}

int mu_of_alpha(int alpha) {  // sigma^2 ~ tau^mu, mu = -alpha - 1, with both PM types at -2
  return alpha >= 1 ? -2 : -alpha - 1;
}

NoiseId identify_by_b1(const PhaseSeries& s, long m) {
  NoiseId id;
  id.by_acf = false;
  const long nf = (static_cast<long>(s.x.size()) - 1) / m;  // averaged frequency points
  if (nf < 3 || analysis_points(Deviation::kAdev, s.x.size(), m) < 1) {
    id.valid = false;
    return id;
  }
  std::vector<double> y(nf);
  double mean = 0.0;
  for (long k = 0; k < nf; ++k) {
    y[k] = s.x[(k + 1) * m] - s.x[k * m];
    mean += y[k];
  }
  mean /= nf;
  double var = 0.0;
  for (double v : y) var += (v - mean) * (v - mean);
  var /= (nf - 1.0);
  double avar = 0.0;
  for (long k = 0; k + 1 < nf; ++k) avar += (y[k + 1] - y[k]) * (y[k + 1] - y[k]);
  avar /= 2.0 * (nf - 1.0);
  if (!(avar > 0.0)) {
    id.valid = false;
    return id;
  }
  const double b1 = var / avar;
  // Walk from white PM towards random-walk FM; pick the first type whose boundary with the next
  // (geometric mean of the expected ratios) lies above the observed ratio.
  int alpha = 1;  // alpha 2 and 1 share mu = -2 and are split below by R(n)
  for (int a = 1; a >= -2; --a) {
    alpha = a;
    if (a == -2) break;
    const double here = b1_expected(nf, mu_of_alpha(a)), next = b1_expected(nf, mu_of_alpha(a - 1));
    if (b1 < std::sqrt(here * next)) break;
  }
  if (alpha == 1 && analysis_points(Deviation::kMdev, static_cast<long>(s.x.size()), m) > 0) {
    // R(n) = Mod var / Allan var: 1/m for white PM, larger for flicker PM.
    const double mvar = std::pow(deviation_at(s.x, s.tau0_s, Deviation::kMdev, m).dev, 2);
    const double ovar = std::pow(deviation_at(s.x, s.tau0_s, Deviation::kOadev, m).dev, 2);
    const double rn_white = 1.0 / m;
    const double af = static_cast<double>(m);
    const double avar_fpm = (1.038 + 3.0 * std::log(2.0 * M_PI * 0.5 * af)) / (4.0 * M_PI * M_PI);
    const double mvar_fpm = 3.0 * std::log(256.0 / 27.0) / (8.0 * M_PI * M_PI);
    const double rn_flicker = mvar_fpm / avar_fpm;
    alpha = (ovar > 0 && mvar / ovar < std::sqrt(rn_white * rn_flicker)) ? 2 : 1;
  }
  id.alpha = alpha;
  id.alpha_est = alpha;
  return id;
}

}  // namespace

double lag1_autocorrelation(const std::vector<double>& z) {
  const size_t n = z.size();
  double mean = 0.0;
  for (double v : z) mean += v;
  mean /= static_cast<double>(n);
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double a = z[i] - mean;
    den += a * a;
    if (i + 1 < n) num += a * (z[i + 1] - mean);
  }
  return den > 0.0 ? num / den : 0.0;
}

NoiseId identify_noise(const PhaseSeries& s, long m, Deviation dev) {
  const long n_phase = static_cast<long>(s.x.size());
  const int dmax = (dev == Deviation::kHdev || dev == Deviation::kOhdev) ? 3 : 2;
  // Averaged series: every m-th phase point (identical to averaging the frequency over m samples).
  std::vector<double> z;
  if (s.source == DataKind::kPhase) {
    for (long i = 0; i < n_phase; i += m) z.push_back(s.x[i]);
    detrend(z, 2);
  } else {
    for (long i = 0; i + m < n_phase; i += m) z.push_back(s.x[i + m] - s.x[i]);
    detrend(z, 1);
  }
  if (z.size() < 30) return identify_by_b1(s, m);
  NoiseId id;
  for (int d = 0;; ++d) {
    const double r1 = lag1_autocorrelation(z);
    const double rho = r1 / (1.0 + r1);
    if (rho < 0.25 || d >= dmax) {
      const double shift = s.source == DataKind::kPhase ? 2.0 : 0.0;
      id.alpha_est = -2.0 * (rho + d) + shift;
      id.alpha = static_cast<int>(-std::lround(2.0 * rho) - 2 * d + static_cast<int>(shift));
      return id;
    }
    for (size_t i = 0; i + 1 < z.size(); ++i) z[i] = z[i + 1] - z[i];
    z.pop_back();
  }
}

}  // namespace ldv::allan
