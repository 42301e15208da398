// Issue 14: where `ldv allan`'s Gauss-Markov fit misses the record's Cramer-Rao bound at the paper's 16 h (its
// HG1900 gyro Y, and the accelerometer Y whose GM sits 4x below K), is the estimator at fault or the record?
// (LABEL montecarlo, about 3 min.) The likelihood is not regular there: a GM with T near the record's length is a
// random walk over the record, so sigma, T and K trade along a ridge. Most records give T near the truth, a few
// run T up to thousands of seconds with K low, and those few make the RMS *relative* error several times the
// bound (the 20-seed study's 612 % on the accelerometer Y's sigma against a bound of 56 %). A relative error
// cannot go below -100 % but can reach +3000 %; the bound is a first-order one, the same for ln(estimate),
// and where it is tens of percent only the log is a fair scale to compare it with. So each term is judged by
// the RMS of ln(estimate / truth) against its relative bound; the relative RMS is printed beside it.
// Here: 16 h and a longer record (4x for the gyro, 16x for the accelerometer's weak GM), 20 seeds each, the GM
// forced. On the longer record the log RMS must be within 1.35x the bound (20 seeds estimate an RMS to about
// 16 %, as test_noise_fit_montecarlo.cpp) and the truth inside the 95 % interval in 18 of 20. At 16 h the
// relative RMS of some term must be beyond 1.5x its bound (the case this is about); the rest is printed.
//
// The rate is 10 Hz, which keeps 256 h of samples at 9.2 million. These terms live below 0.01 Hz: on the same
// realisation at 100 Hz and averaged to 10 Hz (the HG1900 gyro Y, 10 seeds), sigma and K agreed within 1.3 %,
// and T within 10 % where its interval spans decades (within 2 % where it is resolved).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "tests/toolbox_allan/sensor_sim.hpp"
#include "toolbox/allan/analysis.hpp"
#include "toolbox/allan/whittle_fit.hpp"

using namespace ldv::allan;
using namespace ldv::allan::test;

namespace {

struct GrowthRow {
  double rms_sigma = 0, rms_t = 0, rms_k = 0;           // relative
  double rms_ln_sigma = 0, rms_ln_t = 0, rms_ln_k = 0;  // of ln(estimate / truth)
  double bound_sigma = 0, bound_t = 0, bound_k = 0;     // relative Cramer-Rao bounds
  int inside_sigma = 0, inside_t = 0, inside_k = 0, seeds = 0;
  double median_t_ratio = 0;
};

// q: the paper's Q, an additive white error of std q on the integrated quantity.
GrowthRow forced_gm_study(const SensorTruth& t, double q, double hours, double rate_hz, int seeds, unsigned seed0) {
  const double dt = 1.0 / rate_hz;
  const long samples = std::lround(hours * 3600.0 * rate_hz);
  GrowthRow row;
  std::vector<double> t_ratios;
  for (int seed = 1; seed <= seeds; ++seed) {
    std::vector<double> y = simulate_rate(t, dt, samples, seed0 + seed);
    if (q > 0) add_quantisation(y, dt, q, seed0 + 1000 + seed);
    AnalysisOptions opt;
    opt.fit_options.gauss_markov = true;
    const ChannelResult r = analyze({phase_from_rates(std::move(y), dt, "x", "unit")}, opt).front();
    EXPECT_TRUE(r.fit && r.fit->method == "whittle") << r.likelihood_error;
    if (!r.fit) continue;
    const TermEstimate& gm = (*r.fit)[ModelTerm::kGaussMarkov];
    const TermEstimate& k = (*r.fit)[ModelTerm::kK];
    row.rms_sigma += std::pow(gm.value / t.gm_sigma - 1.0, 2);
    row.rms_t += std::pow(gm.shape / t.gm_t_s - 1.0, 2);
    row.rms_k += std::pow(k.value / t.k - 1.0, 2);
    const double floor = 1e-3;  // an estimate of 0 counts as 1/1000 of the truth in the log
    row.rms_ln_sigma += std::pow(std::log(std::max(gm.value / t.gm_sigma, floor)), 2);
    row.rms_ln_t += std::pow(std::log(std::max(gm.shape / t.gm_t_s, floor)), 2);
    row.rms_ln_k += std::pow(std::log(std::max(k.value / t.k, floor)), 2);
    row.inside_sigma += gm.lo <= t.gm_sigma && t.gm_sigma <= gm.hi;
    row.inside_t += gm.shape_lo <= t.gm_t_s && t.gm_t_s <= gm.shape_hi;
    row.inside_k += k.lo <= t.k && t.k <= k.hi;
    t_ratios.push_back(gm.shape / t.gm_t_s);
    ++row.seeds;
  }
  row.rms_sigma = std::sqrt(row.rms_sigma / row.seeds);
  row.rms_t = std::sqrt(row.rms_t / row.seeds);
  row.rms_k = std::sqrt(row.rms_k / row.seeds);
  row.rms_ln_sigma = std::sqrt(row.rms_ln_sigma / row.seeds);
  row.rms_ln_t = std::sqrt(row.rms_ln_t / row.seeds);
  row.rms_ln_k = std::sqrt(row.rms_ln_k / row.seeds);
  std::sort(t_ratios.begin(), t_ratios.end());
  row.median_t_ratio = t_ratios[t_ratios.size() / 2];
  NoiseLevels levels;
  levels.q = q, levels.n = t.n, levels.k = t.k, levels.gm_sigma = t.gm_sigma, levels.gm_t_s = t.gm_t_s;
  const RelativeBounds b = whittle_cramer_rao(levels, dt, samples, FitOptions{}.likelihood_block_s);
  row.bound_sigma = b.gm_sigma, row.bound_t = b.gm_t, row.bound_k = b.k;
  std::printf(
      "%4.0f h: GM sigma RMS %6.1f %% (bound %5.1f %%, inside %2d) | T RMS %7.1f %% (bound %5.1f %%, inside %2d, "
      "median T/true %.2f) | K RMS %5.1f %% (bound %5.1f %%, inside %2d) | of %d\n",
      hours, 100 * row.rms_sigma, 100 * row.bound_sigma, row.inside_sigma, 100 * row.rms_t, 100 * row.bound_t,
      row.inside_t, row.median_t_ratio, 100 * row.rms_k, 100 * row.bound_k, row.inside_k, row.seeds);
  std::printf("        in the log: GM sigma %.3f, T %.3f, K %.3f\n", row.rms_ln_sigma, row.rms_ln_t, row.rms_ln_k);
  return row;
}

void expect_bound_reached_on_the_longer_record(const char* name, const SensorTruth& t, double q, double longer_h,
                                               unsigned seed0) {
  std::printf("%s, GM forced, 20 seeds:\n", name);
  const GrowthRow paper = forced_gm_study(t, q, 16.0, 10.0, 20, seed0);
  const GrowthRow longer = forced_gm_study(t, q, longer_h, 10.0, 20, seed0 + 100);
  // The case this test is about: at 16 h some term's RMS is well beyond its bound.
  EXPECT_GT(std::max({paper.rms_sigma / paper.bound_sigma, paper.rms_t / paper.bound_t, paper.rms_k / paper.bound_k}),
            1.5);
  EXPECT_LE(longer.rms_ln_sigma, 1.35 * longer.bound_sigma);
  EXPECT_LE(longer.rms_ln_t, 1.35 * longer.bound_t);
  EXPECT_LE(longer.rms_ln_k, 1.35 * longer.bound_k);
  EXPECT_GE(longer.inside_sigma, 18);
  EXPECT_GE(longer.inside_t, 18);
  EXPECT_GE(longer.inside_k, 18);
}

}  // namespace

TEST(RecordLengthMonteCarlo, TheHg1900GyroYsGaussMarkovReachesItsBoundAtFourTimesThePapersRecord) {
  const double deg = M_PI / 180.0;
  SensorTruth t;  // Table 7, Y: N + B + K
  t.n = 0.054 * deg / 60.0;
  t.gm_sigma = 0.551 * deg / 3600.0;
  t.gm_t_s = 192.0;
  t.k = 3.126 * deg / 3600.0 / 60.0;
  expect_bound_reached_on_the_longer_record("HG1900 gyro Y", t, 0.0, 64.0, 7000);
}

// The weak GM needs a longer record for the ridge to close: at 64 h its relative RMS errors were still
// 1.6-2.5x the bound (two sets of 20 seeds).
TEST(RecordLengthMonteCarlo, TheHg1900AccelerometerYsWeakGaussMarkovReachesItsBoundAtSixteenTimesThePapersRecord) {
  SensorTruth t;  // Table 6, Y: Q + B + K (no N, no R)
  t.gm_sigma = 0.027 / 3600.0;
  t.gm_t_s = 28.0;
  t.k = 0.951 / 3600.0 / 60.0;
  expect_bound_reached_on_the_longer_record("HG1900 accelerometer Y", t, 0.315 / 3600.0, 256.0, 7500);
}
