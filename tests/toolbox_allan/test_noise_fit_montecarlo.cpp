// The full study of issue 5 (LABEL montecarlo, about 3 min): 20 seeds per case of simulated gyros
// with known truth; the criteria: N within 3 %, B within 10 %, K within 30 % and the truth inside
// the 95 % interval in >= 90 % of seeds, absent terms never resolved.
// Besides: the likelihood fit must be efficient, its RMS error within 1.35x the Cramer-Rao bound
// of the raw data (whittle_cramer_rao; 20 seeds estimate an RMS to about 16 %).
#include <gtest/gtest.h>

#include "tests/toolbox_allan/noise_study.hpp"

using namespace ldv::allan::test;

namespace {

void expect_efficient(const StudyResult& s) {
  EXPECT_LE(std::sqrt(s.k_err_sq / s.seeds), 1.35 * s.crb_k);
  EXPECT_LE(std::sqrt(s.b_err_sq / s.seeds), 1.35 * s.crb_b);
}

}  // namespace

TEST(NoiseFitMonteCarlo, Gx2TwentySeeds) {
  const StudyResult s = study(gx2_gyro(), 3.0, 200.0, 20);
  expect_study(s, 0.9);
  expect_efficient(s);
}

// The tactical gyro over 3 h: K dominates only from about 500 s to the end, and the raw data's
// Cramer-Rao bound is 30 % on K and 8 % on the GM sigma. "Within 30 % / 10 % in 90 % of seeds"
// needs 18 % / 6 %: no estimator reaches it on this record, so those two are reported, not
// asserted; everything else is.
TEST(NoiseFitMonteCarlo, Hg1700ThreeHoursTwentySeeds) {
  const StudyResult s = study(hg1700_gyro(), 3.0, 200.0, 20);
  EXPECT_GT(s.crb_k, 0.30 / 1.645);  // the claim above: K's criterion is beyond the information
  const double need = 0.9 * s.seeds;
  EXPECT_GE(s.n_ok, need);
  EXPECT_GE(s.n_cover, need);
  EXPECT_GE(s.b_cover, need);
  EXPECT_GE(s.k_cover, need);
  EXPECT_EQ(s.absent_ok, s.seeds);
  expect_efficient(s);
}

// The same gyro recorded for 10 h (bound 15.5 % on K, 4.4 % on the GM sigma): every criterion.
TEST(NoiseFitMonteCarlo, Hg1700TenHoursTwentySeeds) {
  const StudyResult s = study(hg1700_gyro(), 10.0, 100.0, 20);
  expect_study(s, 0.9);
  expect_efficient(s);
}
