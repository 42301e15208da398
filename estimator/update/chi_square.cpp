#include "estimator/update/chi_square.hpp"

#include <cmath>

namespace ldv::est {

double chi_square_cdf(double x, int dof) {
  if (x <= 0) return 0.0;
  const double a = 0.5 * dof, z = 0.5 * x;
  // Series for z < a + 1, continued fraction otherwise (Numerical Recipes' split).
  if (z < a + 1.0) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 500; ++n) {
      term *= z / (a + n);
      sum += term;
      if (std::abs(term) < 1e-15 * std::abs(sum)) break;
    }
    return sum * std::exp(-z + a * std::log(z) - std::lgamma(a));
  }
  double b = z + 1.0 - a, c = 1e300, d = 1.0 / b, h = d;
  for (int i = 1; i < 500; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::abs(c) < 1e-300) c = 1e-300;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-15) break;
  }
  return 1.0 - std::exp(-z + a * std::log(z) - std::lgamma(a)) * h;
}

double chi_square_quantile(double p, int dof) {
  double lo = 0.0, hi = 10.0 * dof + 100.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (chi_square_cdf(mid, dof) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace ldv::est
