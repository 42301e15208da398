#pragma once
// Chi-square quantile for the innovation gate (no external statistics library needed).
namespace ldv::est {
// Regularised lower incomplete gamma P(k/2, x/2): the chi-square CDF with k degrees of freedom.
double chi_square_cdf(double x, int dof);
// x such that chi_square_cdf(x, dof) = p (bisection; p in (0, 1)).
double chi_square_quantile(double p, int dof);
}  // namespace ldv::est
