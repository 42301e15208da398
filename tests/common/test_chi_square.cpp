// The one chi-square implementation (common/math) against closed forms and published table values.
#include <gtest/gtest.h>

#include <cmath>

#include "common/math/chi_square.hpp"

using namespace ldv::math;

TEST(ChiSquare, GivenTwoDegreesOfFreedom_ThenCdfAndQuantileMatchTheClosedForm) {
  // dof 2 is the exponential distribution with mean 2: F(x) = 1 - exp(-x/2).
  for (double x : {0.1, 1.0, 4.0, 20.0}) EXPECT_NEAR(chi_square_cdf(x, 2.0), 1.0 - std::exp(-x / 2), 1e-14);
  for (double p : {0.01, 0.5, 0.9, 0.999}) EXPECT_NEAR(chi_square_quantile(p, 2.0), -2.0 * std::log(1.0 - p), 1e-10);
}

TEST(ChiSquare, GivenTheInnovationGateProbabilities_ThenTheQuantilesAreTheTableValues) {
  // NIST/SEMATECH e-Handbook, table 1.3.6.7.4 (upper critical values of the chi-square distribution).
  EXPECT_NEAR(chi_square_quantile(0.95, 3), 7.815, 5e-4);
  EXPECT_NEAR(chi_square_quantile(0.99, 3), 11.345, 5e-4);
  EXPECT_NEAR(chi_square_quantile(0.999, 3), 16.266, 5e-4);
  EXPECT_NEAR(chi_square_quantile(0.05, 10), 3.940, 5e-4);
}

TEST(ChiSquare, GivenFractionalDegreesOfFreedom_ThenQuantileInvertsTheCdf) {
  for (double dof : {0.7, 2.5, 13.3, 250.0})
    for (double p : {0.025, 0.5, 0.975}) EXPECT_NEAR(chi_square_cdf(chi_square_quantile(p, dof), dof), p, 1e-11);
}

TEST(ChiSquare, GivenAProbabilityOutsideTheOpenInterval_ThenItThrows) {
  EXPECT_THROW(chi_square_quantile(1.0, 3), std::invalid_argument);
  EXPECT_THROW(chi_square_quantile(0.0, 3), std::invalid_argument);
}
