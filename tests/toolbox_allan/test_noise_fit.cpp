// Noise identification on simulated sensors with known truth (paper-like HG1700 and 3DM-GX2
// levels): accuracy of N, B, K, coverage of the reported 95 % intervals, absent terms absent, and
// the misfit report pointing at a missing term.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/toolbox_allan/noise_study.hpp"
#include "tests/toolbox_allan/sensor_sim.hpp"
#include "toolbox/allan/analysis.hpp"

using namespace ldv::allan;
using namespace ldv::allan::test;

// Default suite: the same study, 3 seeds of 3 h at 50 Hz (the long tau end, which decides B and K,
// is the same as at 200 Hz; the rate only sharpens N).
// Three seeds cannot show a 90 % rate: at least two of three must meet every criterion.
// Tactical gyro: N is sharp, but 3 h of data hold too little information on K and the Gauss-Markov
// sigma for the issue's 30 % / 10 % precision: the likelihood fit of the raw data (efficient, its
// Fisher sd 24-34 % on K per seed) is at about the Allan-curve fit's Cramer-Rao bound (28 %, 7.6 %;
// toolbox/allan/README.md). The precision criteria stay in the montecarlo study, where they are
// reported unmet; here: N precise, and the reported intervals honest (truth inside).
TEST(NoiseFitStudy, Hg1700ThreeSeeds) {
  const StudyResult s = study(hg1700_gyro(), 3.0, 50.0, 3);
  EXPECT_EQ(s.n_ok, s.seeds);
  EXPECT_GE(s.n_cover, 2);
  EXPECT_GE(s.b_cover, 2);
  EXPECT_GE(s.k_cover, 2);
}
TEST(NoiseFitStudy, Gx2ThreeSeeds) { expect_study(study(gx2_gyro(), 3.0, 50.0, 3), 2.0 / 3.0); }

TEST(NoiseFit, AbsentTermsAreAbsentNeverNan) {
  SensorTruth t;
  t.n = 1e-4;
  auto y = simulate_rate(t, 0.01, 200000, 7);
  AnalysisOptions opt;
  const auto r = analyze({phase_from_rates(std::move(y), 0.01, "x", "rad/s")}, opt).front();
  ASSERT_TRUE(r.fit);
  EXPECT_TRUE((*r.fit)[ModelTerm::kN].resolved);
  EXPECT_NEAR((*r.fit)[ModelTerm::kN].value / t.n, 1.0, 0.03);
  for (ModelTerm m : {ModelTerm::kQ, ModelTerm::kB, ModelTerm::kK, ModelTerm::kR}) {
    const TermEstimate& e = (*r.fit)[m];
    EXPECT_FALSE(e.resolved) << model_term_name(m);
    EXPECT_TRUE(std::isfinite(e.value) && std::isfinite(e.sigma) && std::isfinite(e.lo) && std::isfinite(e.hi));
  }
}

TEST(NoiseFit, MisfitPointsAtTheMissingRamp) {
  // White noise plus a rate ramp, fitted without R: the last decade misses and R closes it.
  SensorTruth t;
  t.n = 1e-3;
  t.r = 2e-7;
  auto y = simulate_rate(t, 0.1, 200000, 3);
  AnalysisOptions opt;
  opt.fit_options.r = false;
  const auto r = analyze({phase_from_rates(std::move(y), 0.1, "x", "rad/s")}, opt).front();
  ASSERT_TRUE(r.fit);
  const DecadeMisfit& last = r.fit->misfit.back();
  EXPECT_GT(last.chi2_per_point, 4.0);
  EXPECT_EQ(last.closing_term, "R");
  EXPECT_LT(last.chi2_per_point_with_term, 0.5 * last.chi2_per_point);
  // With R in the model the misfit is gone and R is resolved near the truth.
  opt.fit_options.r = true;
  auto y2 = simulate_rate(t, 0.1, 200000, 3);
  const auto r2 = analyze({phase_from_rates(std::move(y2), 0.1, "x", "rad/s")}, opt).front();
  EXPECT_LT(r2.fit->misfit.back().chi2_per_point, 3.0);
  EXPECT_TRUE((*r2.fit)[ModelTerm::kR].resolved);
  EXPECT_NEAR((*r2.fit)[ModelTerm::kR].value / t.r, 1.0, 0.3);
}
