// Issue 14: what `ldv allan`'s intervals carry beyond the likelihood fit's own Fisher information
// (analysis.cpp). Against simulated truth, over seeds:
//  - N's interval carries the uncertainty of Q, which the likelihood fit estimates with N: where Q dominates the
//    short taus, N's sigma is the scatter of N over the records and its interval holds the true N as often as
//    its confidence says;
//  - K's interval spans both bias models when BIC's choice is close: a Gauss-Markov bias below the rate random
//    walk (the paper's HG1900) is taken for a flat B, whose K runs high; the spanned interval holds the true K.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "tests/toolbox_allan/sensor_sim.hpp"
#include "toolbox/allan/analysis.hpp"
#include "toolbox/allan/whittle_fit.hpp"

using namespace ldv::allan;
using namespace ldv::allan::test;

namespace {

ChannelResult analyse_intervals(std::vector<double> y, double dt) {
  AnalysisOptions opt;
  return analyze({phase_from_rates(std::move(y), dt, "gyro_x", "rad/s")}, opt).front();
}

}  // namespace

TEST(AllanIntervals, GivenAQuantisationOverTheWhiteNoise_ThenNsIntervalCarriesQsUncertainty) {
  SensorTruth t;
  t.n = 3.5 * M_PI / 180.0 / 60.0;                        // the 3DM-GX2 datasheet's ARW
  const double dt = 0.05, q = 4.0 * t.n * std::sqrt(dt);  // Q's Allan deviation 7x N's at tau0
  const long samples = 72000;                             // 1 h at 20 Hz
  // Q should matter to N here: the bound on N with Q estimated beside it, against the bound with no Q at all.
  NoiseLevels with_q, without_q;
  with_q.n = without_q.n = t.n;
  with_q.q = q;
  const double bound_with_q = whittle_cramer_rao(with_q, dt, samples, dt).n;
  const double bound_without_q = whittle_cramer_rao(without_q, dt, samples, dt).n;
  std::printf("N's Cramer-Rao bound %.4f with Q, %.4f without\n", bound_with_q, bound_without_q);
  ASSERT_GT(bound_with_q, 1.15 * bound_without_q) << "Q should matter to N here";
  const int seeds = 12;
  int carried = 0;
  double sum_sigma = 0.0, sum_n = 0.0, sum_n2 = 0.0;
  for (int seed = 1; seed <= seeds; ++seed) {
    std::vector<double> y = simulate_rate(t, dt, samples, seed);
    add_quantisation(y, dt, q, 1000 + seed);
    const ChannelResult r = analyse_intervals(std::move(y), dt);
    ASSERT_TRUE(r.fit);
    ASSERT_EQ(r.fit->method, "whittle") << r.likelihood_error;
    const TermEstimate& n = (*r.fit)[ModelTerm::kN];
    carried += t.n >= n.lo && t.n <= n.hi;
    sum_sigma += n.sigma / t.n;
    sum_n += n.value / t.n;
    sum_n2 += std::pow(n.value / t.n, 2);
    std::printf("seed %2d: N/true %.4f, interval [%.4f, %.4f], Q/true %.3f\n", seed, n.value / t.n, n.lo / t.n,
                n.hi / t.n, (*r.fit)[ModelTerm::kQ].value / q);
  }
  const double scatter = std::sqrt((sum_n2 - sum_n * sum_n / seeds) / (seeds - 1)), sigma = sum_sigma / seeds;
  std::printf(
      "N's 95 %% interval holds the truth in %d of %d records; N's sigma %.4f of the truth against its scatter "
      "over the records %.4f\n",
      carried, seeds, sigma, scatter);
  EXPECT_GE(carried, seeds - 2);  // P(>= 3 misses | 95 %, 12) = 2 %
  // The scatter of 12 records: within [0.6, 1.5] of the true sigma at 95 %.
  EXPECT_GT(sigma, 0.6 * scatter);
  EXPECT_LT(sigma, 1.6 * scatter);
}

TEST(AllanIntervals, GivenAGaussMarkovBiasBelowTheRateRandomWalk_ThenNsAndKsIntervalsSpanBothBiasModels) {
  // Like the paper's HG1900 accelerometer Y: K's Allan deviation above the GM's even at the GM's peak.
  SensorTruth t;
  t.n = 1e-4;
  t.gm_t_s = 300.0;
  t.gm_sigma = 2e-5;
  t.k = 2.0 * t.gm_sigma / std::sqrt(t.gm_t_s);
  const int seeds = 8;
  int spanned = 0, held = 0, n_held = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    const ChannelResult r = analyse_intervals(simulate_rate(t, 0.02, 360000, 77 + seed), 0.02);  // 2 h at 50 Hz
    ASSERT_TRUE(r.fit && r.bias_model);
    const TermEstimate& k = (*r.fit)[ModelTerm::kK];
    const BiasModelChoice& c = *r.bias_model;
    const double margin = c.flat.bic - c.gauss_markov.bic;
    spanned += r.k_interval_spans_both_bias_models;
    held += t.k >= k.lo && t.k <= k.hi;
    std::printf("seed %d: %s (dBIC %.1f), K/true %.3f, interval [%.3f, %.3f]%s\n", seed, c.chosen.c_str(), margin,
                k.value / t.k, k.lo / t.k, k.hi / t.k, r.k_interval_spans_both_bias_models ? " spans both models" : "");
    EXPECT_EQ(r.k_interval_spans_both_bias_models, std::abs(margin) < close_bias_model_bic(c.observations));
    // N's interval spans both models' on the same close calls, and the union still holds the true N.
    const TermEstimate& n = (*r.fit)[ModelTerm::kN];
    EXPECT_EQ(r.n_interval_spans_both_bias_models, r.k_interval_spans_both_bias_models);
    n_held += t.n >= n.lo && t.n <= n.hi;
  }
  std::printf("K's interval holds the truth in %d of %d records, %d spanning both bias models; N's in %d\n", held,
              seeds, spanned, n_held);
  EXPECT_GT(spanned, 0) << "the case this test is about";
  EXPECT_GE(held, seeds - 1);
  EXPECT_GE(n_held, seeds - 1);
}

TEST(AllanIntervals, GivenAGaussMarkovForcedWhereThereIsNone_ThenKsIntervalIsItsProfilesEvenAtAnEstimateOfZero) {
  // The paper's HG1900 accelerometer Y without its Gauss-Markov (Q 0.315 m/h, K 0.951 m/s/h/sqrt(h)), 16 h at
  // 100 Hz, the GM forced (--gauss-markov). In some records the GM goes to the longest T the search allows,
  // where it is a random walk over the record, and takes all of K: K's estimate is 0. Its interval's upper
  // end must still be where the profile likelihood falls off: the record measures K's level to about 2 %
  // (the GM can stand in for K, not exceed it). Before, an estimate of 0 took its Fisher sigma as inside,
  // unchecked, and the interval reached several times the true K. (Seed 4 here shows the other face of a
  // forced GM nobody has: at T 1129 s it takes half of K, and K's interval, [0.14, 0.97], misses the truth;
  // issue 14's Monte Carlo counts such misses.)
  SensorTruth t;
  t.k = 0.951 / 3600.0 / 60.0;
  const double dt = 0.01, q = 0.315 / 3600.0;
  FitOptions forced;
  forced.gauss_markov = true;
  int estimate_zero = 0;
  for (int seed = 1; seed <= 6; ++seed) {
    std::vector<double> y = simulate_rate(t, dt, 5760000, 300 + seed);
    add_quantisation(y, dt, q, 400 + seed);
    AnalysisOptions opt;
    opt.fit_options = forced;
    const ChannelResult r = analyze({phase_from_rates(std::move(y), dt, "accel_y", "m/s^2")}, opt).front();
    ASSERT_TRUE(r.fit);
    ASSERT_EQ(r.fit->method, "whittle") << r.likelihood_error;
    const TermEstimate& k = (*r.fit)[ModelTerm::kK];
    const TermEstimate& gm = (*r.fit)[ModelTerm::kGaussMarkov];
    std::printf("seed %d: K/true %.3f, interval [%.3f, %.3f]; GM T %.0f s\n", seed, k.value / t.k, k.lo / t.k,
                k.hi / t.k, gm.shape);
    EXPECT_LT(k.hi, 1.15 * t.k) << "seed " << seed;
    if (k.value == 0.0) {
      ++estimate_zero;
      EXPECT_GE(k.hi, t.k) << "seed " << seed << ": the GM that took K's place leaves K's truth as likely";
    }
  }
  EXPECT_GT(estimate_zero, 0) << "the case this test is about";
}
