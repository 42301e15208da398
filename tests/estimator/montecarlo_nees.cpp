// Monte Carlo NEES study (ctest label `montecarlo`; not in the default suite):
//   ctest -L montecarlo   or   build/bin/test_estimator_montecarlo  (LDV_MC_SEEDS=N, default 4)
// Given simulated drives over several seeds (tactical hg1700-typical and MEMS 3dm-gx2-typical; RTK at 1, 10 and
// 20 Hz; a 60 s outage during the manoeuvres at 300 s of 600 s), when kfgins21 runs with and without the
// gnss_position_bias block, then the seed-averaged NEES of position, velocity and attitude is consistent
// (about 3 per 3-dof block) with the block, and position NEES is optimistic without it.
#include <gtest/gtest.h>

#include <cstdlib>

#include "estimator/run/run_navigation.hpp"
#include "sim_run.hpp"

namespace ldv::est {
namespace {

struct Case {
  const char* grade;
  double gnss_hz;
};

class NeesStudy : public ::testing::TestWithParam<Case> {};

TEST_P(NeesStudy, SeedAveragedNeesIsConsistentWithGnssPositionBias) {
  const Case c = GetParam();
  const char* env = std::getenv("LDV_MC_SEEDS");
  const int seeds = env ? std::max(1, std::atoi(env)) : 4;
  double pos_plain = 0, pos = 0, vel = 0, att = 0, drift = 0, hrms = 0;
  for (int k = 0; k < seeds; ++k) {
    sim::SimRequest req;
    req.grade = c.grade;
    req.seed = 1000 + k;
    req.duration_s = 600.0;
    req.scenario = "drive";
    req.gnss_rate_hz = c.gnss_hz;
    req.outages = {{300.0, 60.0}};
    const sim::SimResult sim = sim::simulate(req);
    FilterOptions o = options_from_kfgins(sim.kfgins);
    o.model = "kfgins21";
    const auto a = test::evaluate(sim, o);
    o.add = {"gnss_position_bias"};
    const auto b = test::evaluate(sim, o);
    pos_plain += a.nees_pos / seeds;
    pos += b.nees_pos / seeds;
    vel += b.nees_vel / seeds;
    att += b.nees_att / seeds;
    drift += b.outage_drift_m / seeds;
    hrms += b.horiz_rms_m / seeds;
  }
  std::printf("NEES %s RTK %.0f Hz, %d seeds: position kfgins21 %.2f, +gnss_position_bias %.2f; velocity %.2f, "
              "attitude %.2f (3 expected); horizontal RMS %.4f m, 60 s outage drift %.2f m\n",
              c.grade, c.gnss_hz, seeds, pos_plain, pos, vel, att, hrms, drift);
  EXPECT_GT(pos, 1.5);
  EXPECT_LT(pos, 4.5);
  EXPECT_GT(vel, 0.5);
  EXPECT_LT(vel, 6.0);
  EXPECT_GT(att, 0.5);
  EXPECT_LT(att, 6.0);
}

INSTANTIATE_TEST_SUITE_P(Grades, NeesStudy,
                         ::testing::Values(Case{"hg1700-typical", 1.0}, Case{"hg1700-typical", 10.0},
                                           Case{"hg1700-typical", 20.0}, Case{"3dm-gx2-typical", 1.0},
                                           Case{"3dm-gx2-typical", 10.0}, Case{"3dm-gx2-typical", 20.0}),
                         [](const auto& info) {
                           return std::string(info.param.grade[0] == 'h' ? "tactical" : "mems") + "_" +
                                  std::to_string(static_cast<int>(info.param.gnss_hz)) + "hz";
                         });

}  // namespace
}  // namespace ldv::est
