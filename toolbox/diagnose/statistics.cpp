#include "toolbox/diagnose/statistics.hpp"

#include <algorithm>
#include <cmath>

#include "common/math/chi_square.hpp"

namespace ldv::diag {
namespace {

// Continued fraction of I_x(a, b) (modified Lentz), converges for x < (a + 1) / (a + b + 2).
double beta_continued_fraction(double x, double a, double b) {
  const double tiny = 1e-300;
  double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::fabs(d) < tiny) d = tiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m < 10000; ++m) {
    const double m2 = 2.0 * m;
    // even step
    double num = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
    d = 1.0 + num * d;
    c = 1.0 + num / c;
    if (std::fabs(d) < tiny) d = tiny;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    h *= d * c;
    // odd step
    num = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
    d = 1.0 + num * d;
    c = 1.0 + num / c;
    if (std::fabs(d) < tiny) d = tiny;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1.0) < 1e-15) break;
  }
  return h;
}

double poisson_weight(int j, double mu) { return std::exp(-mu + j * std::log(mu) - std::lgamma(j + 1.0)); }

// P(noncentral chi-square(dof, lambda) > x) as a Poisson mixture of central tails.
double noncentral_sf(double x, double dof, double lambda) {
  if (lambda <= 0.0) return chi_square_sf(x, dof);
  const double mu = 0.5 * lambda;
  const int j_max = static_cast<int>(mu + 12.0 * std::sqrt(mu) + 30.0);
  double sum = 0.0;
  for (int j = 0; j <= j_max; ++j) sum += poisson_weight(j, mu) * chi_square_sf(x, dof + 2.0 * j);
  return std::min(1.0, sum);
}

}  // namespace

double chi_square_sf(double x, double dof) {
  if (x <= 0.0) return 1.0;
  return std::max(0.0, 1.0 - math::chi_square_cdf(x, dof));
}

double incomplete_beta(double x, double a, double b) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double front = std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) +
                                b * std::log1p(-x));
  if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_continued_fraction(x, a, b) / a;
  return 1.0 - front * beta_continued_fraction(1.0 - x, b, a) / b;
}

double f_sf(double x, double d1, double d2) {
  if (x <= 0.0) return 1.0;
  return incomplete_beta(d2 / (d2 + d1 * x), 0.5 * d2, 0.5 * d1);
}

double hotelling_sf(double t2, double p, double nu) {
  const double d2 = nu - p + 1.0;
  if (d2 <= 0.5) return chi_square_sf(t2, p);  // no usable dof estimate: asymptotic
  return f_sf(t2 * d2 / (p * nu), p, d2);
}

double noncentrality_for_power(double alpha, double power, double dof) {
  const double c = math::chi_square_quantile(1.0 - alpha, dof);
  double lo = 0.0, hi = 1.0;
  while (noncentral_sf(c, dof, hi) < power) hi *= 2.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (noncentral_sf(c, dof, mid) < power ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double chi_square_z(double x, double dof) {
  const double v = 2.0 / (9.0 * dof);
  return (std::cbrt(std::max(x, 0.0) / dof) - (1.0 - v)) / std::sqrt(v);
}

}  // namespace ldv::diag
