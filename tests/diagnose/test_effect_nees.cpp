// Issue 48, item 3: an effect state's error against its covariance. Given simulated drives with one hidden effect of a
// realistic size, when the filter estimates that effect from its default prior (the prior an unknown gets when the
// configuration states none), then over seeds the squared error of each component over its variance averages about 1
// (NEES per degree of freedom, chi-square band over the seeds): the sigma the diagnosis and --write-config report is
// the error's. Default suite: 4 seeds per case; LDV_NEES_SEEDS=N for more (label montecarlo runs 20).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "common/math/chi_square.hpp"
#include "tests/diagnose/sim_case.hpp"
#include "toolbox/diagnose/filter_run.hpp"

namespace ldv::diag {
namespace {

int seeds() {
  const char* s = std::getenv("LDV_NEES_SEEDS");
  return s ? std::max(1, std::atoi(s)) : 4;
}

struct NeesCase {
  const char* grade;
  const char* effect;  // as for ldv sim --effect
  const char* model;
};

struct Nees {
  double sum_z2 = 0.0;
  int dof = 0;
  double worst_z = 0.0;
};

Nees effect_nees(const NeesCase& c, int n) {
  Nees out;
  const std::string name = testing::effect_name(c.effect);
  for (int s = 0; s < n; ++s) {
    testing::SimCase sc;
    sc.grade = c.grade;
    sc.effect = c.effect;
    sc.seed = 500 + static_cast<uint64_t>(s);
    sc.duration_s = 600.0;
    sc.gnss_rate_hz = 5.0;
    const sim::SimResult r = testing::simulate(sc);
    est::FilterOptions o = testing::options(r, c.model).model;
    o.add.push_back(name);  // from its default prior
    const FilterRun run = run_filter(testing::inputs(r), o);
    const std::vector<double>& truth = r.injected_effects.at(name);
    for (const EffectEstimate& e : run.estimates) {
      if (e.name != name) continue;
      for (int i = 0; i < e.value_si.size(); ++i) {
        const double z = (e.value_si(i) - truth[static_cast<size_t>(i)]) / e.std_si(i);
        if (std::getenv("LDV_NEES_VERBOSE"))
          std::printf("  seed %d %s[%d]: estimate %.4g truth %.4g sigma %.3g (%.1f sigma)\n", s, name.c_str(), i,
                      e.value_si(i), truth[static_cast<size_t>(i)], e.std_si(i), z);
        out.sum_z2 += z * z;
        ++out.dof;
        out.worst_z = std::max(out.worst_z, std::abs(z));
      }
    }
  }
  return out;
}

class EffectNees : public ::testing::TestWithParam<NeesCase> {};

TEST_P(EffectNees, GivenAHiddenEffectEstimatedFromItsDefaultPrior_ThenItsErrorMatchesItsSigma) {
  const NeesCase c = GetParam();
  const Nees nees = effect_nees(c, seeds());
  ASSERT_GT(nees.dof, 0) << "the run did not estimate " << c.effect;
  // The chi-square band of the summed squares at 99 % (two-sided), per degree of freedom
  const double lo = math::chi_square_quantile(0.005, nees.dof) / nees.dof;
  const double hi = math::chi_square_quantile(0.995, nees.dof) / nees.dof;
  const double per_dof = nees.sum_z2 / nees.dof;
  std::printf("[ info ] %s %s (%s): NEES per dof %.2f over %d (band %.2f..%.2f), worst |error|/sigma %.1f\n", c.grade,
              c.effect, c.model, per_dof, nees.dof, lo, hi, nees.worst_z);
  EXPECT_LE(per_dof, hi) << "the effect's sigma is optimistic";
  EXPECT_GE(per_dof, lo) << "the effect's sigma is pessimistic";
}

// Sizes inside each effect's prior: the configuration's (gsstd, asstd: a hidden scale 10x the datasheet's is a wrong
// configuration, NEES 40, not a wrong filter) or the default of an effect KF-GINS has no key for.
INSTANTIATE_TEST_SUITE_P(RealisticSizes, EffectNees,
                         ::testing::Values(NeesCase{"hg1700-typical", "lever_arm=0.5,-0.3,-1.2", "kfgins21"},
                                           NeesCase{"3dm-gx2-typical", "lever_arm=1.5,-0.6,-1.8", "kfgins21"},
                                           NeesCase{"hg1700-typical", "time_offset=0.05", "kfgins21"},
                                           NeesCase{"3dm-gx2-typical", "time_offset=0.2", "kfgins21"},
                                           NeesCase{"hg1700-typical", "gyro_scale=150,-100,200", "ins15"},
                                           NeesCase{"hg1700-typical", "gyro_misalignment=400,-300,350", "kfgins21"},
                                           NeesCase{"3dm-gx2-typical", "gyro_misalignment=2000,-1500,1800",
                                                    "kfgins21"}));

// A consumer MEMS's in-run bias drifts as a random walk and a ramp besides its Gauss-Markov part (the simulator's
// 3dm-gx2-typical, as geoldv51 models it). kfgins21 and ins15 carry the Gauss-Markov part only: the drift they lack
// goes into an added effect that can absorb it, and that effect's sigma is then optimistic (accel scale 13.9 per dof,
// worst 10.9 sigma; accel misalignment 14, 6.7 sigma; g-sensitivity 50, 18 sigma: its z component and the z gyro
// bias are told apart only by the bias's dynamics). With geoldv51 each is consistent: the effect's sigma is the
// error's once the model holds what the sensor does.
INSTANTIATE_TEST_SUITE_P(MemsWithItsBiasDrift, EffectNees,
                         ::testing::Values(NeesCase{"3dm-gx2-typical", "accel_scale=5000,-3000,4000", "geoldv51"},
                                           NeesCase{"3dm-gx2-typical", "accel_misalignment=2000,-1500,1800",
                                                    "geoldv51"},
                                           NeesCase{"3dm-gx2-typical", "g_sensitivity=600,-400,300", "geoldv51"}));

// The counterpart (the NEES test can fail, and does where the model misses the physics): the same g-sensitivity
// under kfgins21, whose bias lacks the drift, is beyond the band.
TEST(EffectNeesOfAModelMissingTheBiasDrift, GivenMemsGSensitivityUnderKfgins21_ThenItsSigmaIsOptimistic) {
  const Nees nees = effect_nees(NeesCase{"3dm-gx2-typical", "g_sensitivity=600,-400,300", "kfgins21"}, seeds());
  ASSERT_GT(nees.dof, 0);
  const double hi = math::chi_square_quantile(0.995, nees.dof) / nees.dof;
  std::printf("[ info ] kfgins21: NEES per dof %.1f (band up to %.2f), worst %.1f sigma\n", nees.sum_z2 / nees.dof, hi,
              nees.worst_z);
  EXPECT_GT(nees.sum_z2 / nees.dof, hi);
}

}  // namespace
}  // namespace ldv::diag
