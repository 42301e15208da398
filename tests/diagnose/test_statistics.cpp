// The distributions behind the p-values and detectable sizes, against closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "toolbox/diagnose/statistics.hpp"

namespace ldv::diag {

TEST(DiagnoseStatistics, IncompleteBetaMatchesClosedForm) {
  // I_x(2, 3) = 6x^2 - 8x^3 + 3x^4 (integral of 12 t (1-t)^2).
  for (double x : {0.1, 0.5, 0.9}) EXPECT_NEAR(incomplete_beta(x, 2, 3), 6 * x * x - 8 * x * x * x + 3 * x * x * x * x, 1e-12);
}

TEST(DiagnoseStatistics, FTailIsTheTwoSidedStudentTail) {
  // F(1, 10) at t^2 = 4: two-sided Student t(10) p-value of 2.0 is 0.07339.
  EXPECT_NEAR(f_sf(4.0, 1, 10), 0.07339, 2e-5);
  // Large dof: F(p, inf) * p -> chi-square(p).
  EXPECT_NEAR(f_sf(7.815 / 3.0, 3, 1e7), 0.05, 1e-3);
}

TEST(DiagnoseStatistics, HotellingTendsToChiSquare) {
  EXPECT_NEAR(hotelling_sf(7.815, 3, 1e7), chi_square_sf(7.815, 3), 1e-4);
  EXPECT_GT(hotelling_sf(7.815, 3, 20), 0.05);  // a small-sample covariance has heavier tails
}

TEST(DiagnoseStatistics, NoncentralityForPowerOfOneDof) {
  // 1 dof: lambda = (z_{1-alpha/2} + z_power)^2 (the other tail is negligible).
  EXPECT_NEAR(noncentrality_for_power(0.05, 0.8, 1), std::pow(1.959964 + 0.841621, 2), 0.02);
}

}  // namespace ldv::diag
