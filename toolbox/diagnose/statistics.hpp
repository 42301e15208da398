#pragma once
// Distributions the diagnosis needs (no external statistics library).
namespace ldv::diag {

// Upper tail of chi-square with `dof` degrees of freedom.
double chi_square_sf(double x, double dof);
// Regularised incomplete beta I_x(a, b).
double incomplete_beta(double x, double a, double b);
// Upper tail of Fisher's F(d1, d2).
double f_sf(double x, double d1, double d2);
// Hotelling T^2(p, nu) upper tail: (nu - p + 1) / (p nu) T ~ F(p, nu - p + 1). nu = degrees of freedom of
// the covariance estimate (here: the equivalent dof of the long-run variance of the score).
double hotelling_sf(double t2, double p, double nu);
// Noncentrality lambda at which a chi-square(dof) test of size alpha has this power.
double noncentrality_for_power(double alpha, double power, double dof);
// Wilson-Hilferty z of a chi-square(dof) value: one scale to rank statistics of different dof
// without p-values underflowing.
double chi_square_z(double x, double dof);

}  // namespace ldv::diag
