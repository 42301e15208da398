// gnss_position_bias: the Gauss-Markov part of the GNSS position error as a state.
// Given its definition z = r_ant + b + white noise (docs/effects.md), the H column is +I (checked against a
// numerical derivative of the predicted measurement written here), the white noise is what remains of the
// reported variance, the estimate decays with tau. And on the simulator's RTK (white + Gauss-Markov tau 60 s),
// kfgins21 + gnss_position_bias has a consistent position NEES where plain kfgins21 is ~3x optimistic.
#include <gtest/gtest.h>

#include "common/geo/earth_model.hpp"
#include "estimator/effects/registry.hpp"
#include "estimator/run/run_navigation.hpp"
#include "estimator/state/state_layout.hpp"
#include "estimator/update/gnss_position.hpp"
#include "sim_run.hpp"

namespace ldv::est {
namespace {

TEST(GnssPositionBias, HColumnIsIdentityAndNoiseIsTheWhitePart) {
  FilterOptions opt;
  opt.lever_arm.init = Vec3(0.5, -0.2, -1.0);
  opt.gnss_position_bias.sigma = Vec3(0.01, 0.02, 0.03);
  const StateLayout layout({"gyro_bias", "gnss_position_bias"}, opt);
  NavState s;
  s.pos = {40.0 * kDegToRad, -105.0 * kDegToRad, 1600.0};
  s.q_b_n = quat_from_euler(Vec3(0.1, -0.05, 2.0));
  LinearizationPoint lp;
  lp.C_b_n = s.C_b_n();
  lp.lever_arm_b_m = opt.lever_arm.init;
  // Truth: the receiver reports the antenna position plus a bias b.
  const Vec3 b(0.012, -0.007, 0.02);
  const Geodetic ant = earth::offset_ned(s.pos, s.C_b_n() * opt.lever_arm.init);
  GnssFix fix;
  fix.pos = earth::offset_ned(ant, b);
  fix.pos_std_ned_m = Vec3(0.02, 0.02, 0.05);
  // Predicted measurement z_hat(b_hat) = r_ant + b_hat; innovation = z_hat - z.
  auto innovation = [&](const Vec3& b_hat) { return Vec3(earth::ned_between(fix.pos, ant) + b_hat); };
  lp.gnss_position_bias_n_m = b;
  const Measurement m = gnss_position_measurement(s, lp, layout, fix);
  EXPECT_LT(m.y.norm(), 1e-6) << "the true bias explains the measurement";
  const int o = layout.find("gnss_position_bias")->offset;
  const double eps = 1e-4;
  for (int j = 0; j < 3; ++j) {
    Vec3 bp = b;
    bp(j) += eps;
    const Vec3 col = (innovation(bp) - innovation(b)) / eps;
    EXPECT_LT((col - m.H.col(o + j)).norm(), 1e-6) << "column " << j;
  }
  // White variance = reported^2 - sigma^2, floored at reported^2 / 4.
  EXPECT_NEAR(m.R(0, 0), 0.02 * 0.02 - 0.01 * 0.01, 1e-12);
  EXPECT_NEAR(m.R(1, 1), 0.02 * 0.02 / 4.0, 1e-12);
  EXPECT_NEAR(m.R(2, 2), 0.05 * 0.05 - 0.03 * 0.03, 1e-12);

  // Dynamics: F = -1/tau, q = 2 sigma^2 / tau; the estimate decays as exp(-dt / tau).
  const auto eff = effect_registry().make("gnss_position_bias", opt);
  const auto F = eff->dynamics();
  ASSERT_EQ(F.size(), 3u);
  EXPECT_DOUBLE_EQ(F[0].value, -1.0 / opt.gnss_position_bias.corr_time_s);
  Eigen::VectorXd x = Eigen::Vector3d(1.0, 2.0, 3.0);
  eff->propagate_nominal(x, opt.gnss_position_bias.corr_time_s);
  EXPECT_NEAR(x(2), 3.0 * std::exp(-1.0), 1e-12);
}

TEST(GnssPositionBias, PositionNeesConsistentOnCorrelatedRtk) {
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.seed = 21;
  req.duration_s = 480.0;
  req.scenario = "drive";
  req.gnss_rate_hz = 5.0;
  const sim::SimResult sim = sim::simulate(req);
  FilterOptions plain = options_from_kfgins(sim.kfgins);
  plain.model = "kfgins21";
  FilterOptions with = plain;
  with.add = {"gnss_position_bias"};
  const auto a = test::evaluate(sim, plain);
  const auto b = test::evaluate(sim, with);
  std::printf("hg1700-typical 5 Hz RTK (white 8 mm + Gauss-Markov 8 mm / 60 s): position NEES kfgins21 %.2f, "
              "+gnss_position_bias %.2f (3 expected); horizontal RMS %.4f -> %.4f m; vel NEES %.2f -> %.2f\n",
              a.nees_pos, b.nees_pos, a.horiz_rms_m, b.horiz_rms_m, a.nees_vel, b.nees_vel);
  // Time-averaged NEES of errors correlated over ~60 s: 480 s hold ~8 independent samples of 3 dof,
  // so the mean has a relative std of ~1/sqrt(12): a band [1, 6] around 3 is 2-3 sigma.
  EXPECT_GT(b.nees_pos, 1.0);
  EXPECT_LT(b.nees_pos, 6.0);
  EXPECT_LT(b.nees_pos, a.nees_pos);
  EXPECT_LT(b.horiz_rms_m, 0.03);
}

}  // namespace
}  // namespace ldv::est
