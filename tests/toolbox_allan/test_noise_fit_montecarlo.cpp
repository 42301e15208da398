// The full study of issue 5: 3 h at 200 Hz, 20 seeds, per sensor grade (LABEL montecarlo):
// N within 3 %, B within 10 %, K within 30 % and the truth inside the 95 % interval in >= 90 % of
// seeds; absent terms never resolved.
#include <gtest/gtest.h>

#include "tests/toolbox_allan/noise_study.hpp"

using namespace ldv::allan::test;

TEST(NoiseFitMonteCarlo, Hg1700TwentySeeds) { expect_study(study(hg1700_gyro(), 3.0, 200.0, 20), 0.9); }
TEST(NoiseFitMonteCarlo, Gx2TwentySeeds) { expect_study(study(gx2_gyro(), 3.0, 200.0, 20), 0.9); }
