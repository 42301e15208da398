// NoiseAdaptation (estimator/filter/noise_adaptation.hpp) against closed-form truth: innovations drawn from a
// known covariance alpha A + beta R give back alpha and beta when A and R differ in shape; a white excess of the
// same shape (the NIS cannot tell the parts apart) goes to the GNSS noise, since a prediction too confident
// would make the innovations correlated; white innovations show a lag-1 correlation within its band, an AR(1)
// sequence its coefficient. The filter's S follows both factors (A_used, R_used), the draws do not.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <random>

#include "estimator/filter/noise_adaptation.hpp"

namespace ldv::est {
namespace {

Eigen::VectorXd draw(std::mt19937& rng, const Eigen::MatrixXd& C) {
  std::normal_distribution<double> n;
  Eigen::VectorXd z(C.rows());
  for (int i = 0; i < z.size(); ++i) z(i) = n(rng);
  return Eigen::LLT<Eigen::MatrixXd>(C).matrixL() * z;
}

TEST(NoiseAdaptationClosedForm, GivenPredictionAndGnssOfDifferentShapes_ThenBothFactorsAreFound) {
  // The prediction uncertain along the track (north), the receiver vertically: a 5 Hz drive of 20 min whose
  // GNSS noise is twice the stated std (beta 4) and whose IMU noise is as configured (alpha 1).
  const Eigen::MatrixXd A = Eigen::Vector3d(4e-4, 0.5e-4, 0.5e-4).asDiagonal();
  const Eigen::MatrixXd R = Eigen::Vector3d(1e-4, 1e-4, 4e-4).asDiagonal();
  std::mt19937 rng(7);
  NoiseAdaptation a;
  for (int k = 0; k < 6000; ++k) {
    const Eigen::MatrixXd A_used = a.imu_scale() * A, R_used = a.gnss_scale() * R;  // the filter's S follows both
    a.add_fix(0.2 * k, A_used, R_used, draw(rng, A + 4.0 * R));
  }
  EXPECT_NEAR(a.imu_scale(), 1.0, 0.25);
  EXPECT_NEAR(a.gnss_scale(), 4.0, 0.6);
}

TEST(NoiseAdaptationClosedForm, GivenAWhiteExcessOfTheSameShape_ThenTheGnssNoiseTakesItAll) {
  // A = R / 4, white innovations at 4 (A + R): the NIS alone cannot tell the parts apart, their whiteness can (a
  // prediction too confident makes them correlated). All of it goes to beta: beta R = 4 (A + R) - A, beta 4.75.
  const Eigen::MatrixXd R = Eigen::Matrix3d::Identity() * 1e-4, A = R / 4.0;
  std::mt19937 rng(8);
  NoiseAdaptation a;
  for (int k = 0; k < 6000; ++k) {
    const Eigen::MatrixXd A_used = a.imu_scale() * A, R_used = a.gnss_scale() * R;
    a.add_fix(0.2 * k, A_used, R_used, draw(rng, 4.0 * (A + R)));
  }
  EXPECT_LT(a.imu_scale(), 1.2);
  EXPECT_NEAR(a.gnss_scale(), 4.75, 0.5);
}

TEST(NoiseAdaptationClosedForm, GivenInnovationsAtTheirCovariance_ThenNothingMovesAndTheyAreWhite) {
  const Eigen::MatrixXd A = Eigen::Vector3d(2e-4, 1e-4, 1e-4).asDiagonal(), R = Eigen::Matrix3d::Identity() * 1e-4;
  std::mt19937 rng(9);
  NoiseAdaptation a;
  for (int k = 0; k < 6000; ++k) a.add_fix(0.2 * k, a.imu_scale() * A, a.gnss_scale() * R, draw(rng, A + R));
  // Each factor's own sigma over the 120 s window is about 0.07 in ln (Fisher information 0.3 per fix, 600 fixes)
  // and a factor at its floor can only wander up: within 3 sigma.
  EXPECT_LT(a.imu_scale(), std::exp(3 * 0.07));
  EXPECT_LT(a.gnss_scale(), std::exp(3 * 0.07));
  EXPECT_LT(std::fabs(a.lag1_correlation()), 3.0 / std::sqrt(static_cast<double>(a.lag1_products())));
}

TEST(NoiseAdaptationClosedForm, GivenOnlyGnssNoise_ThenEachFactorsSigmaIsItsWindowedFisherInformation) {
  // No prediction part (A = 0): a fix pair's difference has covariance R_k + R_k-1, so the Fisher information on
  // ln beta is tr(I) / 2 = 1.5 per pair; over the 120 s window at 5 Hz (weights e^(-0.2 k / 120)) it sums to
  // 1.5 / (1 - e^(-0.2 / 120)) = 900.7, plus the prior's 1: sigma of ln beta 1 / sqrt(901.7). The IMU factor has
  // no information at all: its prior's sigma, 1.
  const Eigen::MatrixXd R = Eigen::Matrix3d::Identity() * 1e-4, A = Eigen::Matrix3d::Zero();
  std::mt19937 rng(11);
  NoiseAdaptation a;
  for (int k = 0; k < 6000; ++k) a.add_fix(0.2 * k, A, a.gnss_scale() * R, draw(rng, R));
  const double window_information = 1.5 / (1.0 - std::exp(-0.2 / 120.0));
  EXPECT_NEAR(a.gnss_scale_sigma() / a.gnss_scale(), 1.0 / std::sqrt(window_information + 1.0), 1e-3);
  EXPECT_NEAR(a.imu_scale_sigma() / a.imu_scale(), 1.0, 1e-9);
}

TEST(NoiseAdaptationClosedForm, GivenAnAr1InnovationSequence_ThenTheLag1CorrelationIsItsCoefficient) {
  const Eigen::MatrixXd A = Eigen::Matrix3d::Identity() * 1e-4, R = A;
  std::mt19937 rng(10);
  NoiseAdaptation a;
  const double phi = 0.6;
  Eigen::VectorXd y = draw(rng, A + R);
  for (int k = 0; k < 6000; ++k) {
    a.add_fix(0.2 * k, A, R, y);
    y = phi * y + std::sqrt(1.0 - phi * phi) * draw(rng, A + R);
  }
  EXPECT_NEAR(a.lag1_correlation(), phi, 0.03);
}

}  // namespace
}  // namespace ldv::est
