// Issue 14: `ldv allan` chooses the bias model (flat B or Gauss-Markov) by the data, not by a flag
// default. Both models are fitted by the likelihood of the raw data and the lower AIC wins when the GM
// stands out (analysis.cpp); a forced model (--bias-model flat | gm, --gauss-markov) is kept as asked.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "tests/toolbox_allan/sensor_sim.hpp"
#include "toolbox/allan/analysis.hpp"

using namespace ldv::allan;
using namespace ldv::allan::test;

namespace {

// A flat-B-like (flicker) rate: equal-variance Gauss-Markov processes with time constants two per
// decade. Each puts its variance sigma_i^2 into the integral of f S(f) over ln f, so the sum has
// f S(f) = sigma_i^2 / ln(spacing) between 1/(2 pi T_max) and 1/(2 pi T_min): the one-sided flicker
// density B^2 / (pi f) (Allan variance 2 ln2 B^2 / pi) for sigma_i^2 = B^2 ln(spacing) / pi.
void add_flicker(std::vector<double>& y, double dt, double b, double t_min, double t_max, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  const double spacing = std::sqrt(10.0);
  const double sigma = b * std::sqrt(std::log(spacing) / M_PI);
  for (double t = t_min; t <= t_max * 1.001; t *= spacing) {
    const double phi = std::exp(-dt / t), drive = sigma * std::sqrt(1.0 - phi * phi);
    double x = sigma * g(rng);
    for (double& v : y) {
      v += x;
      x = phi * x + drive * g(rng);
    }
  }
}

ChannelResult analyse_bias_model(std::vector<double> y, double dt, const FitOptions& fo = {}) {
  AnalysisOptions opt;
  opt.fit_options = fo;
  return analyze({phase_from_rates(std::move(y), dt, "gyro_x", "rad/s")}, opt).front();
}

void print_choice(const char* what, const ChannelResult& r) {
  const BiasModelChoice& c = *r.bias_model;
  std::printf("%s: chose %s by %s; flat lnL %.1f (k %d, AIC %.1f), GM lnL %.1f (k %d, AIC %.1f, %s), LR %.2f\n", what,
              c.chosen.c_str(), c.criterion.c_str(), c.flat.log_likelihood, c.flat.parameters, c.flat.aic,
              c.gauss_markov.log_likelihood, c.gauss_markov.parameters, c.gauss_markov.aic,
              c.gauss_markov_stands_out ? "stands out" : "does not stand out", c.likelihood_ratio);
}

}  // namespace

TEST(BiasModelChoice, TrueGaussMarkovIsChosenAndRecovered) {
  // The GM of WhittleFit.RealGaussMarkovIsStillFound (T = 20 s, sigma 5x the white noise's Allan
  // deviation at T), 1 h at 100 Hz, default options: auto picks the GM and recovers it within that
  // test's tolerances (sigma 10 %, T 20 %, N 3 %).
  SensorTruth t;
  t.n = 0.041 * M_PI / 180.0 / 60.0;
  t.gm_t_s = 20.0;
  t.gm_sigma = 5.0 * t.n / std::sqrt(t.gm_t_s);
  const ChannelResult r = analyse_bias_model(simulate_rate(t, 0.01, 360000, 41), 0.01);
  ASSERT_TRUE(r.fit && r.bias_model);
  ASSERT_EQ(r.fit->method, "whittle") << r.likelihood_error;
  const BiasModelChoice& c = *r.bias_model;
  print_choice("true GM", r);
  EXPECT_EQ(c.requested, "auto");
  EXPECT_EQ(c.criterion, "AIC");
  EXPECT_EQ(c.chosen, "gauss_markov");
  ASSERT_TRUE(c.flat.fitted && c.gauss_markov.fitted);
  EXPECT_EQ(c.gauss_markov.parameters, c.flat.parameters + 1);  // T
  EXPECT_LT(c.gauss_markov.aic, c.flat.aic);
  EXPECT_TRUE(c.gauss_markov_stands_out);
  EXPECT_GT(c.likelihood_ratio, std::log(static_cast<double>(c.observations)));  // beyond the BIC's penalty
  EXPECT_GT(c.observations, 10000);
  const TermEstimate& gm = (*r.fit)[ModelTerm::kGaussMarkov];
  EXPECT_TRUE(gm.in_model);
  EXPECT_FALSE((*r.fit)[ModelTerm::kB].in_model);
  EXPECT_TRUE(gm.resolved);
  EXPECT_NEAR(gm.value / t.gm_sigma, 1.0, 0.10);
  EXPECT_NEAR(gm.shape / t.gm_t_s, 1.0, 0.20);
  EXPECT_NEAR((*r.fit)[ModelTerm::kN].value / t.n, 1.0, 0.03);
  // The curve fit beside it is the GM model's too.
  ASSERT_TRUE(r.curve_fit);
  EXPECT_TRUE((*r.curve_fit)[ModelTerm::kGaussMarkov].in_model);
}

TEST(BiasModelChoice, FlickerBiasKeepsTheFlatB) {
  // A flat-B-like bias (flicker from 3 ms to 3000 s, below the sample interval to beyond the record;
  // B 3e-4 rad/s over white noise of the tactical N), 1 h at 100 Hz: one Gauss-Markov cannot follow a
  // floor flat over every tau; auto keeps the flat B and recovers B (15 %). (With the flicker cut off
  // at 0.1 s, where the white noise does not yet hide it, neither model is the truth and the GM won.)
  SensorTruth t;
  t.n = 4.4e-5;
  for (unsigned seed : {61u, 62u}) {
    std::vector<double> y = simulate_rate(t, 0.01, 360000, seed);
    add_flicker(y, 0.01, 3e-4, 0.00316, 3162.0, seed + 1000);
    const ChannelResult r = analyse_bias_model(std::move(y), 0.01);
    ASSERT_TRUE(r.fit && r.bias_model);
    ASSERT_EQ(r.fit->method, "whittle") << r.likelihood_error;
    print_choice("flicker", r);
    const BiasModelChoice& c = *r.bias_model;
    EXPECT_EQ(c.criterion, "AIC");
    EXPECT_EQ(c.chosen, "flat") << "seed " << seed;
    EXPECT_LT(c.flat.aic, c.gauss_markov.aic) << "seed " << seed;
    EXPECT_TRUE((*r.fit)[ModelTerm::kB].in_model);
    EXPECT_FALSE((*r.fit)[ModelTerm::kGaussMarkov].in_model);
    EXPECT_TRUE((*r.fit)[ModelTerm::kB].resolved) << "seed " << seed;
    EXPECT_NEAR((*r.fit)[ModelTerm::kB].value / 3e-4, 1.0, 0.15) << "seed " << seed;
    // (N is not checked: the flicker's components with T of a block or less are white there and add to it.)
    std::printf("  B %.3g (truth 3e-4), N %.4f of the truth\n", (*r.fit)[ModelTerm::kB].value,
                (*r.fit)[ModelTerm::kN].value / t.n);
  }
}

TEST(BiasModelChoice, NoBiasPicksTheSimplerModel) {
  // White noise + rate random walk, no bias term, 1 h at 100 Hz: no GM is picked that is not there
  // (the flat B, one parameter fewer, wins a tie), and the criterion values are reported.
  SensorTruth t;
  t.n = 1e-3;
  t.k = 1e-4;
  for (unsigned seed : {71u, 72u}) {
    const ChannelResult r = analyse_bias_model(simulate_rate(t, 0.01, 360000, seed), 0.01);
    ASSERT_TRUE(r.fit && r.bias_model);
    print_choice("no bias", r);
    const BiasModelChoice& c = *r.bias_model;
    EXPECT_EQ(c.criterion, "AIC");
    EXPECT_EQ(c.chosen, "flat") << "seed " << seed;
    EXPECT_TRUE(c.flat.fitted && c.gauss_markov.fitted);
    EXPECT_TRUE(std::isfinite(c.flat.aic) && std::isfinite(c.gauss_markov.aic));
    EXPECT_TRUE(c.flat.aic <= c.gauss_markov.aic || !c.gauss_markov_stands_out) << "seed " << seed;
    EXPECT_FALSE((*r.fit)[ModelTerm::kGaussMarkov].in_model);
    EXPECT_FALSE((*r.fit)[ModelTerm::kB].resolved) << "seed " << seed;
    EXPECT_NEAR((*r.fit)[ModelTerm::kK].value / t.k, 1.0, 0.3) << "seed " << seed;
  }
}

TEST(BiasModelChoice, ForcedModelsAreKeptAsAsked) {
  // --bias-model flat on a true GM keeps the flat B; --gauss-markov keeps the GM; neither compares.
  SensorTruth t;
  t.n = 0.041 * M_PI / 180.0 / 60.0;
  t.gm_t_s = 20.0;
  t.gm_sigma = 5.0 * t.n / std::sqrt(t.gm_t_s);
  FitOptions flat;
  flat.choose_bias_model = false;
  const std::vector<double> rate = simulate_rate(t, 0.01, 120000, 43);  // one record, three ways of fitting it
  const ChannelResult rf = analyse_bias_model(rate, 0.01, flat);
  ASSERT_TRUE(rf.fit && rf.bias_model);
  EXPECT_EQ(rf.bias_model->requested, "flat");
  EXPECT_EQ(rf.bias_model->criterion, "none");
  EXPECT_EQ(rf.bias_model->chosen, "flat");
  EXPECT_FALSE(rf.bias_model->gauss_markov.fitted);
  EXPECT_TRUE((*rf.fit)[ModelTerm::kB].in_model);
  FitOptions gm;
  gm.gauss_markov = true;
  const ChannelResult rg = analyse_bias_model(rate, 0.01, gm);
  ASSERT_TRUE(rg.fit && rg.bias_model);
  EXPECT_EQ(rg.bias_model->requested, "gauss_markov");
  EXPECT_EQ(rg.bias_model->chosen, "gauss_markov");
  EXPECT_EQ(rg.bias_model->criterion, "none");
  EXPECT_TRUE((*rg.fit)[ModelTerm::kGaussMarkov].in_model);
  // Without the likelihood fit (curve only) auto falls back to the flat B and says why.
  FitOptions curve;
  curve.likelihood = false;
  const ChannelResult rc = analyse_bias_model(rate, 0.01, curve);
  ASSERT_TRUE(rc.fit && rc.bias_model);
  EXPECT_EQ(rc.bias_model->requested, "auto");
  EXPECT_EQ(rc.bias_model->criterion, "none");
  EXPECT_EQ(rc.bias_model->chosen, "flat");
  EXPECT_FALSE(rc.bias_model->note.empty());
}

TEST(BiasModelChoice, AGaussMarkovAtTheRandomWalksLevelIsTakenByAicAndKeepsKRight) {
  // The paper's HG1900 gyro X (Table 7: N 0.045 deg/sqrt(h), GM 0.514 deg/h with T 192 s, K 2.18
  // deg/h/sqrt(h)) over its 16 h at 100 Hz: the GM's Allan peak sits below the random walk's there, the
  // GM fits better by a likelihood ratio of a few to 20, and BIC's ln n = 14 kept the flat B in most
  // records, whose K then ran 20-45 % high. AIC takes the GM where it stands out, and K is within the
  // issue's 30 % (the record's Cramer-Rao bound on K: 15 %, so 30 % is 2 sigma).
  const double deg = M_PI / 180.0;
  SensorTruth t;
  t.n = 0.045 * deg / 60.0;
  t.gm_sigma = 0.514 * deg / 3600.0;
  t.gm_t_s = 192.0;
  t.k = 2.18 * deg / 3600.0 / 60.0;
  const int seeds = 6;
  int gm_chosen = 0, bic_would_keep_flat = 0, k_within = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    const ChannelResult r = analyse_bias_model(simulate_rate(t, 0.01, 5760000, 900 + seed), 0.01);
    ASSERT_TRUE(r.fit && r.bias_model);
    ASSERT_EQ(r.fit->method, "whittle") << r.likelihood_error;
    print_choice("HG1900 gyro X", r);
    const BiasModelChoice& c = *r.bias_model;
    EXPECT_EQ(c.criterion, "AIC");
    gm_chosen += c.chosen == "gauss_markov";
    bic_would_keep_flat += c.flat.bic <= c.gauss_markov.bic;
    const double k_ratio = (*r.fit)[ModelTerm::kK].value / t.k;
    k_within += std::abs(k_ratio - 1.0) <= 0.3;
    std::printf("  K %.3f of the truth%s\n", k_ratio, c.chosen == "gauss_markov" ? "" : " (flat B kept)");
  }
  std::printf("GM chosen in %d of %d records (BIC would have kept the flat B in %d); K within 30 %% in %d\n", gm_chosen,
              seeds, bic_would_keep_flat, k_within);
  EXPECT_GE(bic_would_keep_flat, 2) << "the case this test is about: BIC's penalty above the evidence";
  EXPECT_GE(gm_chosen, seeds - 1);
  EXPECT_GE(k_within, seeds - 1);
}
