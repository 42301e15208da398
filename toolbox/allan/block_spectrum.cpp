#include "toolbox/allan/block_spectrum.hpp"

#include <cmath>

namespace ldv::allan {
namespace {

// sum over all integers k of |nu + k|^-3, nu in (0, 1): the alias sum of a 1/f rate after block
// averaging (two Hurwitz zeta functions). Eight terms each side, then the Euler-Maclaurin tail
// (next correction ~1e-9 relative).
double alias_sum_cubed(double nu) {
  auto side = [](double a) {  // sum_{k >= 0} (k + a)^-3
    constexpr int kDirect = 8;
    double s = 0.0;
    for (int k = 0; k < kDirect; ++k) s += std::pow(k + a, -3.0);
    const double x = kDirect + a;
    return s + 1.0 / (2.0 * x * x) + 1.0 / (2.0 * x * x * x) + 1.0 / (4.0 * std::pow(x, 4)) -
           1.0 / (12.0 * std::pow(x, 6));
  };
  return side(nu) + side(1.0 - nu);
}

// Gauss-Markov rate of unit variance, time constant T: spectrum of the block means ybar_j. Their
// autocovariance is c0 at lag 0 and A r^l at lag l >= 1 (r = e^{-tau_b/T}; non-overlapping blocks
// of an exponential correlation factorise), summed in closed form.
double gauss_markov_block_mean_density(double nu, double tau_b_s, double t_s) {
  const double x = tau_b_s / t_s, r = std::exp(-x), one_minus_r = -std::expm1(-x);
  // c0 = 2 (x - 1 + e^-x) / x^2, by its series where the difference would cancel.
  const double c0 = x < 1e-4 ? 1.0 - x / 3.0 + x * x / 12.0 : 2.0 * (x - one_minus_r) / (x * x);
  const double a = one_minus_r * one_minus_r / (x * x * r);
  const double c = std::cos(2.0 * M_PI * nu);
  return c0 + 2.0 * a * (r * c - r * r) / (1.0 - 2.0 * r * c + r * r);
}

}  // namespace

double block_difference_density(ModelTerm t, double nu, double tau_b_s, double shape) {
  const double s = std::sin(M_PI * nu), s2 = s * s;
  switch (t) {
    case ModelTerm::kQ:
      return 16.0 * s2 * s2 / (tau_b_s * tau_b_s);
    case ModelTerm::kN:
      return 4.0 * s2 / tau_b_s;
    case ModelTerm::kB:
      return 2.0 * s2 * s2 / (M_PI * M_PI * M_PI) * alias_sum_cubed(nu);
    case ModelTerm::kK:
      return tau_b_s / 3.0 * (2.0 + std::cos(2.0 * M_PI * nu));
    case ModelTerm::kGaussMarkov:
      return 4.0 * s2 * gauss_markov_block_mean_density(nu, tau_b_s, shape);
    case ModelTerm::kR:
    case ModelTerm::kSinusoid:
      return 0.0;
  }
  return 0.0;
}

}  // namespace ldv::allan
