// GNSS velocities fused only where they agree with the positions (estimator/calibrate/gnss_velocity_check.hpp):
// given simulated RTK with honest velocities, they pass; given the same velocities 0.1 s late with three
// times their stated scatter (RTKLIB's .pos as seen on a real car), they are refused and the lag is found.
#include <gtest/gtest.h>

#include <random>

#include "estimator/calibrate/gnss_velocity_check.hpp"
#include "sim/simulator.hpp"

namespace ldv::est {
namespace {

sim::SimResult figure8_with_velocity() {
  sim::SimRequest r;
  r.grade = "hg1700-typical";
  r.seed = 8;
  r.duration_s = 200.0;
  r.scenario = "figure8";
  r.gnss_rate_hz = 10.0;
  r.gnss_velocity = true;
  return sim::simulate(r);
}

TEST(GnssVelocityCheck, HonestVelocitiesPassLaggedNoisyOnesAreRefused) {
  const sim::SimResult sim = figure8_with_velocity();
  const GnssVelocityCheck honest = check_gnss_velocity(sim.gnss);
  EXPECT_GT(honest.compared, 1000);
  EXPECT_TRUE(honest.consistent()) << "misfit " << honest.normalised_mse;
  EXPECT_LT(honest.normalised_mse, 2.0);
  EXPECT_FALSE(honest.lagged()) << honest.best_lag_s << " s, statistic " << honest.lag_statistic;

  std::vector<GnssFix> lagged = sim.gnss;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n01;
  for (size_t k = lagged.size() - 1; k > 0; --k) {
    lagged[k].vel_n_mps = sim.gnss[k - 1].vel_n_mps;  // 0.1 s late at 10 Hz
    for (int a = 0; a < 3; ++a) lagged[k].vel_n_mps(a) += 2.0 * sim.gnss[k].vel_std_n_mps(a) * n01(rng);
  }
  const GnssVelocityCheck bad = check_gnss_velocity(lagged);
  EXPECT_FALSE(bad.consistent()) << "misfit " << bad.normalised_mse << ", lag statistic " << bad.lag_statistic;
  EXPECT_TRUE(bad.lagged());
  EXPECT_NEAR(bad.best_lag_s, 0.1, 0.02);
}

}  // namespace
}  // namespace ldv::est
