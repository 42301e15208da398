#pragma once
// Chi-square distribution (our own: no Boost dependency): the estimator's innovation gate, the Allan
// confidence intervals and the diagnosis's tests all use this one.
namespace ldv::math {

// Regularized lower incomplete gamma P(a, x), a > 0, x >= 0.
double regularized_gamma_p(double a, double x);

// Cumulative chi-square probability for `dof` (> 0, may be fractional) degrees of freedom.
double chi_square_cdf(double x, double dof);

// The x with chi_square_cdf(x, dof) = p, 0 < p < 1: Wilson-Hilferty start, then safeguarded
// Newton steps on the incomplete gamma (relative accuracy ~1e-12).
double chi_square_quantile(double p, double dof);

// Inverse standard normal CDF (Acklam's rational approximation refined by one Halley step).
double normal_quantile(double p);

}  // namespace ldv::math
