#include "toolbox/allan/edf.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ldv::allan {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Greenhall's eq. (7): the generalized autocovariance shape of the phase for each noise type. A
// sign per alpha is irrelevant (sz appears only squared and in ratios).
double sw(double t, int alpha) {
  const double a = std::fabs(t);
  switch (alpha) {
    case 2: return -a;
    case 1: return a == 0 ? 0.0 : t * t * std::log(a);
    case 0: return a * a * a;
    case -1: return a == 0 ? 0.0 : -std::pow(t, 4) * std::log(a);
    case -2: return -std::pow(a, 5);
    case -3: return a == 0 ? 0.0 : std::pow(t, 6) * std::log(a);
    case -4: return std::pow(a, 7);
    default: return 0.0;  // alpha + 4 < 0 never reaches here (alpha + 2 for F = inf is <= 4)
  }
}

// Eq. (8): the filter of length 1/F (F = inf: no filter, F = 1: modified, F = m: unmodified).
double sx(double t, double F, int alpha) {
  if (F == kInf) return sw(t, alpha + 2);
  return F * F * (2.0 * sw(t, alpha) - sw(t - 1.0 / F, alpha) - sw(t + 1.0 / F, alpha));
}

// Eq. (9): the d-th difference.
double sz(double t, double F, int alpha, int d) {
  switch (d) {
    case 1: return 2 * sx(t, F, alpha) - sx(t - 1, F, alpha) - sx(t + 1, F, alpha);
    case 2:
      return 6 * sx(t, F, alpha) - 4 * (sx(t - 1, F, alpha) + sx(t + 1, F, alpha)) + sx(t - 2, F, alpha) +
             sx(t + 2, F, alpha);
    default:
      return 20 * sx(t, F, alpha) - 15 * (sx(t - 1, F, alpha) + sx(t + 1, F, alpha)) +
             6 * (sx(t - 2, F, alpha) + sx(t + 2, F, alpha)) - sx(t - 3, F, alpha) - sx(t + 3, F, alpha);
  }
}

// Eq. (10).
double basic_sum(double J, double M, double S, double F, int alpha, int d) {
  const double s0 = sz(0, F, alpha, d);
  double sum = s0 * s0;
  const double sJ = sz(J / S, F, alpha, d);
  sum += (1.0 - J / M) * sJ * sJ;
  for (long j = 1; j < static_cast<long>(J); ++j) {
    const double s = sz(j / S, F, alpha, d);
    sum += 2.0 * (1.0 - j / M) * s * s;
  }
  return sum;
}

struct Coeffs {
  double c0, c1;
};

// Table 1 (modified variances) and Table 2 (unmodified), rows alpha = +2 ... -4, columns d = 1..3.
Coeffs table1(int alpha, int d) {
  static const Coeffs t[7][3] = {{{2.0 / 3, 1.0 / 3}, {7.0 / 9, 1.0 / 2}, {22.0 / 25, 2.0 / 3}},
                                 {{0.840, 0.345}, {0.997, 0.616}, {1.141, 0.843}},
                                 {{1.079, 0.368}, {1.033, 0.607}, {1.184, 0.848}},
                                 {{0, 0}, {1.048, 0.534}, {1.180, 0.816}},
                                 {{0, 0}, {1.302, 0.535}, {1.175, 0.777}},
                                 {{0, 0}, {0, 0}, {1.194, 0.703}},
                                 {{0, 0}, {0, 0}, {1.489, 0.702}}};
  return t[2 - alpha][d - 1];
}
Coeffs table2(int alpha, int d) {
  static const Coeffs t[7][3] = {{{3.0 / 2, 1.0 / 2}, {35.0 / 18, 1.0}, {231.0 / 100, 3.0 / 2}},
                                 {{78.6, 25.2}, {790.0, 410.0}, {9950.0, 6520.0}},
                                 {{2.0 / 3, 1.0 / 6}, {2.0 / 3, 1.0 / 3}, {7.0 / 9, 1.0 / 2}},
                                 {{0, 0}, {0.852, 0.375}, {0.997, 0.617}},
                                 {{0, 0}, {1.079, 0.368}, {1.033, 0.607}},
                                 {{0, 0}, {0, 0}, {1.053, 0.553}},
                                 {{0, 0}, {0, 0}, {1.302, 0.535}}};
  return t[2 - alpha][d - 1];
}
// Table 3: flicker PM (alpha = 1) normalisation b0 + b1 ln m.
Coeffs table3(int d) {
  static const Coeffs t[3] = {{6.0, 4.0}, {15.23, 12.0}, {47.8, 40.0}};
  return t[d - 1];
}

double binomial(int n, int k) { return std::round(std::exp(std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0))); }

}  // namespace

int min_convergent_alpha(Deviation dev) {
  return (dev == Deviation::kHdev || dev == Deviation::kOhdev) ? -4 : -2;
}

double greenhall_edf(Deviation dev, int alpha, long m_int, long n_phase) {
  const bool hadamard = dev == Deviation::kHdev || dev == Deviation::kOhdev;
  const bool modified = dev == Deviation::kMdev || dev == Deviation::kTdev;
  const bool overlapping = dev != Deviation::kAdev && dev != Deviation::kHdev;
  const int d = hadamard ? 3 : 2;
  alpha = std::clamp(alpha, min_convergent_alpha(dev), 2);
  const double m = static_cast<double>(m_int);
  const double N = static_cast<double>(n_phase);
  const double F = modified ? 1.0 : m;
  const double S = overlapping ? m : 1.0;
  const double L = m / F + m * d;  // span of the filter in phase samples
  if (N < L) return 0.0;
  const double M = 1.0 + std::floor(S * (N - L) / m);
  const double J = std::min(M, (d + 1) * S);
  const double r = M / S;
  const double Jmax = 100.0;
  double inv_edf = 0.0;
  if (modified) {
    if (J <= Jmax) {
      const double s0 = sz(0, 1.0, alpha, d);
      inv_edf = basic_sum(J, M, S, 1.0, alpha, d) / (s0 * s0 * M);
    } else if (r > d + 1) {
      const Coeffs a = table1(alpha, d);
      inv_edf = (a.c0 - a.c1 / r) / r;
    } else {
      const double s0 = sz(0, 1.0, alpha, d);
      inv_edf = basic_sum(Jmax, Jmax, Jmax / r, 1.0, alpha, d) / (s0 * s0 * Jmax);
    }
  } else if (alpha <= 0) {
    if (J <= Jmax) {
      const double Fp = m * (d + 1) <= Jmax ? m : kInf;
      const double s0 = sz(0, Fp, alpha, d);
      inv_edf = basic_sum(J, M, S, Fp, alpha, d) / (s0 * s0 * M);
    } else if (r > d + 1) {
      const Coeffs a = table2(alpha, d);
      inv_edf = (a.c0 - a.c1 / r) / r;
    } else {
      const double s0 = sz(0, kInf, alpha, d);
      inv_edf = basic_sum(Jmax, Jmax, Jmax / r, kInf, alpha, d) / (s0 * s0 * Jmax);
    }
  } else if (alpha == 1) {
    const Coeffs b = table3(d);
    const double norm = b.c0 + b.c1 * std::log(m);
    if (J <= Jmax) {
      const double s0 = sz(0, m, alpha, d);
      inv_edf = basic_sum(J, M, S, m, alpha, d) / (s0 * s0 * M);
    } else if (r > d + 1) {
      const Coeffs a = table2(alpha, d);
      inv_edf = (a.c0 - a.c1 / r) / (norm * norm * r);
    } else {
      const double mp = Jmax / r;
      inv_edf = basic_sum(Jmax, Jmax, mp, mp, alpha, d) / (norm * norm * Jmax);
    }
  } else {  // alpha == 2, unmodified
    if (std::ceil(r) > d) {
      const double a0 = binomial(4 * d, 2 * d) / std::pow(binomial(2 * d, d), 2);
      const double a1 = d / 2.0;
      inv_edf = (a0 - a1 / r) / M;
    } else {  // very few terms: the exact basic sum
      const double s0 = sz(0, m, alpha, d);
      inv_edf = basic_sum(J, M, S, m, alpha, d) / (s0 * s0 * M);
    }
  }
  return inv_edf > 0.0 ? 1.0 / inv_edf : 0.0;
}

}  // namespace ldv::allan
