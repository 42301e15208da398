// The adjustment engine: analytic Jacobians of the gravity condition against central differences, and a
// linear Gauss-Helmert problem whose answer is known in closed form.
#include <gtest/gtest.h>

#include "toolbox/calib/accel_gravity_model.hpp"

namespace ldv::calib {
namespace {

TEST(AccelGravityModel, AnalyticJacobiansMatchNumericalDerivatives) {
  const AccelGravityModel model(9.8);
  VectorXd x(9), l(3);
  x << 0.1, -0.2, 0.3, 0.01, -0.02, 0.015, 0.004, -0.003, 0.002;
  l << 3.0, -5.0, 7.5;
  VectorXd f, fn;
  MatrixXd A, B, An, Bn;
  model.evaluate(0, l, x, f, A, B);
  numeric_jacobians(
      [&](const VectorXd& ll, const VectorXd& xx) {
        VectorXd ff;
        MatrixXd a, b;
        model.evaluate(0, ll, xx, ff, a, b);
        return ff;
      },
      l, x, VectorXd::Constant(3, 1e-6), VectorXd::Constant(9, 1e-7), fn, An, Bn);
  EXPECT_NEAR(f[0], fn[0], 1e-15);
  EXPECT_LT((A - An).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_LT((B - Bn).cwiseAbs().maxCoeff(), 1e-7);
}

// Straight line through points with errors in both coordinates: y_i - (a + b x_i) = 0. For equal, isotropic
// weights the Gauss-Helmert answer is the orthogonal (total least squares) fit.
class LineModel : public ConditionModel {
 public:
  int num_params() const override { return 2; }
  std::vector<std::string> param_names() const override { return {"a", "b"}; }
  VectorXd param_ranges() const override { return VectorXd::Constant(2, 10.0); }
  void evaluate(int, const VectorXd& l, const VectorXd& x, VectorXd& f, MatrixXd& A, MatrixXd& B) const override {
    f.resize(1);
    f[0] = l[1] - x[0] - x[1] * l[0];
    A.resize(1, 2);
    A << -1.0, -l[0];
    B.resize(1, 2);
    B << -x[1], 1.0;
  }
};

TEST(GaussHelmert, GivenErrorsInBothCoordinatesThenOrthogonalRegression) {
  const std::vector<std::pair<double, double>> pts = {{0, 0.1}, {1, 0.9}, {2, 2.2}, {3, 2.8}, {4, 4.1}, {5, 5.0}};
  std::vector<ConditionBlock> blocks;
  for (auto [x, y] : pts) blocks.push_back({Eigen::Vector2d(x, y), MatrixXd::Identity(2, 2) * 0.01, MatrixXd()});
  const GaussHelmertResult r = solve_gauss_helmert(LineModel(), blocks, VectorXd::Zero(2));
  ASSERT_TRUE(r.converged);
  // Total least squares: slope from the principal axis of the centred scatter.
  double mx = 0, my = 0;
  for (auto [x, y] : pts) mx += x / pts.size(), my += y / pts.size();
  double sxx = 0, syy = 0, sxy = 0;
  for (auto [x, y] : pts) sxx += (x - mx) * (x - mx), syy += (y - my) * (y - my), sxy += (x - mx) * (y - my);
  const double b = (syy - sxx + std::sqrt((syy - sxx) * (syy - sxx) + 4 * sxy * sxy)) / (2 * sxy);
  EXPECT_NEAR(r.x[1], b, 1e-9);
  EXPECT_NEAR(r.x[0], my - b * mx, 1e-9);
  EXPECT_EQ(r.redundancy, 4);
}

TEST(GaussHelmert, GivenOnePointThenRankDeficientDirectionIsNamed) {
  std::vector<ConditionBlock> blocks = {{Eigen::Vector2d(2.0, 1.0), MatrixXd::Identity(2, 2) * 0.01, MatrixXd()}};
  const GaussHelmertResult r = solve_gauss_helmert(LineModel(), blocks, VectorXd::Zero(2));
  EXPECT_TRUE(r.observability.rank_deficient);
  ASSERT_EQ(r.observability.weak_directions.size(), 1u);
  // a + 2 b is fixed by the point; a - 2 b (normalised) is free.
  EXPECT_NE(r.observability.weak_directions[0].find("a"), std::string::npos);
  EXPECT_NE(r.observability.weak_directions[0].find("b"), std::string::npos);
}

}  // namespace
}  // namespace ldv::calib
