// The likelihood refinement (whittle_fit.hpp) on simulated sensors with known truth: no random walk
// appears out of white noise (the end-effect floor of a differenced record, see the taper comment
// in whittle_fit.cpp), a ramp is not read as a random walk, a random walk is found with an honest
// interval, and the fit reports what it did.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/toolbox_allan/sensor_sim.hpp"
#include "toolbox/allan/analysis.hpp"

using namespace ldv::allan;
using namespace ldv::allan::test;

namespace {

ChannelResult analyse(const SensorTruth& t, double dt, long samples, unsigned seed) {
  auto y = simulate_rate(t, dt, samples, seed);
  AnalysisOptions opt;
  // The flat B, as these tests were written for (they pass with the default auto choice as well, at
  // twice the time: test_bias_model_choice.cpp tests the choice).
  opt.fit_options.choose_bias_model = false;
  return analyze({phase_from_rates(std::move(y), dt, "gyro_x", "rad/s")}, opt).front();
}

}  // namespace

TEST(WhittleFit, WhiteNoiseGivesNoRandomWalk) {
  // 2 h of white noise at 100 Hz. Before the taper, every seed gave a "resolved" K of about
  // 0.2 N per s here (5x a tactical gyro's K); now K must be absent for every seed.
  SensorTruth t;
  t.n = 4.4e-5;  // 0.15 deg/sqrt(h)
  for (unsigned seed : {1u, 2u, 3u}) {
    const ChannelResult r = analyse(t, 0.01, 720000, seed);
    ASSERT_TRUE(r.fit);
    ASSERT_EQ(r.fit->method, "whittle") << r.likelihood_error;
    const TermEstimate& k = (*r.fit)[ModelTerm::kK];
    EXPECT_FALSE(k.resolved) << "seed " << seed << " K " << k.value << " +- " << k.sigma;
    EXPECT_LE(k.lo, 0.0 + 1e-300) << "seed " << seed;  // the interval reaches down to 0
    EXPECT_NEAR((*r.fit)[ModelTerm::kN].value / t.n, 1.0, 0.01);
    EXPECT_FALSE((*r.fit)[ModelTerm::kB].resolved);
  }
}

TEST(WhittleFit, RampIsNotReadAsRandomWalk) {
  // White noise, a rate random walk and a strong ramp (over the hour it drifts 10x the walk's
  // one-sigma excursion, about 9 sigma of its estimate): the ramp is a constant in the block differences and must not
  // inflate K; it is estimated from that constant against the noise the walk puts there.
  SensorTruth t;
  t.n = 1e-3;
  t.k = 2e-5;
  t.r = 3e-6;
  int covered = 0;
  for (unsigned seed : {11u, 12u, 13u}) {
    const ChannelResult r = analyse(t, 0.01, 360000, seed);
    ASSERT_TRUE(r.fit);
    ASSERT_EQ(r.fit->method, "whittle") << r.likelihood_error;
    const TermEstimate& k = (*r.fit)[ModelTerm::kK];
    EXPECT_LT(k.value, 2.0 * t.k) << "seed " << seed;
    covered += k.lo <= t.k && t.k <= k.hi;
    // The ramp itself, from the same data: found, and within 3 sigma of the truth.
    const TermEstimate& r_est = (*r.fit)[ModelTerm::kR];
    EXPECT_TRUE(r_est.resolved) << "seed " << seed << " R " << r_est.value << " +- " << r_est.sigma;
    EXPECT_NEAR(r_est.value, t.r, 3.0 * r_est.sigma) << "seed " << seed;
  }
  EXPECT_GE(covered, 2);
}

TEST(WhittleFit, RandomWalkFoundWithHonestInterval) {
  // White noise + random walk, 1 h at 100 Hz, K dominating from about 20 s: K within its interval
  // and within 20 % (its information here is large), the fit's summary filled in.
  SensorTruth t;
  t.n = 1e-3;
  t.k = 1e-4;
  int covered = 0, close = 0;
  for (unsigned seed : {21u, 22u, 23u, 24u}) {
    const ChannelResult r = analyse(t, 0.01, 360000, seed);
    ASSERT_TRUE(r.fit && r.curve_fit && r.likelihood);
    const TermEstimate& k = (*r.fit)[ModelTerm::kK];
    EXPECT_TRUE(k.resolved);
    covered += k.lo <= t.k && t.k <= k.hi;
    close += std::fabs(k.value / t.k - 1.0) < 0.2;
    EXPECT_NEAR(r.likelihood->block_s, 0.02, 1e-12);
    EXPECT_GT(r.likelihood->ordinates, 10000);
  }
  EXPECT_GE(covered, 3);
  EXPECT_GE(close, 3);
}

TEST(WhittleFit, CurveOnlyOptionAndTooShortRecordKeepTheCurveFit) {
  SensorTruth t;
  t.n = 1e-3;
  auto y = simulate_rate(t, 0.01, 4000, 5);  // 40 s: 2000 blocks of 0.02 s are enough...
  AnalysisOptions opt;
  opt.fit_options.likelihood_block_s = 1.0;  // ...but 40 blocks of 1 s are not
  const ChannelResult r = analyze({phase_from_rates(std::move(y), 0.01, "x", "rad/s")}, opt).front();
  ASSERT_TRUE(r.fit);
  EXPECT_EQ(r.fit->method, "allan_gls");
  EXPECT_NE(r.likelihood_error.find("at least 65"), std::string::npos) << r.likelihood_error;
  opt.fit_options.likelihood = false;
  auto y2 = simulate_rate(t, 0.01, 100000, 5);
  const ChannelResult r2 = analyze({phase_from_rates(std::move(y2), 0.01, "x", "rad/s")}, opt).front();
  EXPECT_FALSE(r2.likelihood);
  EXPECT_FALSE(r2.curve_fit);
}

TEST(WhittleCramerRao, WhiteNoiseBoundIsTheClosedForm) {
  // White noise only: the variance of n block means is known to sd sqrt(2/n) (relative), so N to
  // sqrt(1/(2n)); the tapered likelihood pays its variance factor (1.12) on top.
  NoiseLevels white;
  white.n = 1e-3;
  const long samples = 360000;
  const double block_s = 0.02, tau0 = 0.01;
  const long blocks = samples / 2;
  const RelativeBounds b = whittle_cramer_rao(white, tau0, samples, block_s);
  EXPECT_NEAR(b.n / std::sqrt(1.12 / (2.0 * blocks)), 1.0, 0.02);
  EXPECT_EQ(b.k, 0.0);
}

TEST(WhittleCramerRao, MoreDataTightensEveryTermAsTheSquareRootOfTheDuration) {
  // Beyond the transient of a term that barely shows, information grows with the number of
  // ordinates: four times the record, half the sd (within 10 %).
  NoiseLevels s;
  s.n = 4.4e-5;
  s.k = 8e-7;
  s.gm_sigma = 2.4e-5;
  s.gm_t_s = 50.0;
  const RelativeBounds b10 = whittle_cramer_rao(s, 0.01, 10L * 3600 * 100, 0.02);
  const RelativeBounds b40 = whittle_cramer_rao(s, 0.01, 40L * 3600 * 100, 0.02);
  EXPECT_NEAR(b10.k / b40.k, 2.0, 0.2);
  EXPECT_NEAR(b10.gm_sigma / b40.gm_sigma, 2.0, 0.2);
  EXPECT_NEAR(b10.n / b40.n, 2.0, 0.05);
}

TEST(WhittleCramerRao, RecordNeededFollowsTheSquareRootLaw) {
  // A fit of 1 h of white noise + random walk (K dominant from 20 s on): the record at which K
  // reaches 5 % is the present one times (sd now / 5 %)^2, within 15 % (the asymptotic law).
  SensorTruth t;
  t.n = 1e-3;
  t.k = 1e-4;
  const ChannelResult r = analyse(t, 0.01, 360000, 31);
  ASSERT_TRUE(r.information);
  const RecordInformation& info = *r.information;
  ASSERT_GT(info.now.k, 0.05);
  const double expected_h = 1.0 * std::pow(info.now.k / 0.05, 2);
  AnalysisOptions opt;
  opt.fit_options.target_precision = 0.05;
  opt.fit_options.choose_bias_model = false;  // as analyse() above
  auto y = simulate_rate(t, 0.01, 360000, 31);
  const ChannelResult r5 = analyze({phase_from_rates(std::move(y), 0.01, "x", "rad/s")}, opt).front();
  ASSERT_TRUE(r5.information);
  EXPECT_NEAR(r5.information->hours_k / expected_h, 1.0, 0.15);
  EXPECT_EQ(r5.information->hours_b, 0.0);  // B not resolved: no record length claimed
}

namespace {

ChannelResult analyse_gauss_markov(const SensorTruth& t, double dt, long samples, unsigned seed) {
  auto y = simulate_rate(t, dt, samples, seed);
  AnalysisOptions opt;
  opt.fit_options.gauss_markov = true;  // what `ldv allan --gauss-markov` runs
  return analyze({phase_from_rates(std::move(y), dt, "gyro_x", "rad/s")}, opt).front();
}

}  // namespace

TEST(WhittleFit, NoDegenerateGaussMarkovOnWhiteNoise) {
  // Issue 14: a gyro with white noise only (the paper's HG1700 N, 0.041 deg/sqrt(h)), no bias term,
  // 1 h at 100 Hz, fitted with --gauss-markov. Before the lower bound on T, seed 506 gave a GM of
  // T = 0.026 s (2.6 samples) holding 22 % of N^2 (N 0.885 of the truth) and its curve fit N = 0
  // (GM T 0.003 s); seeds 504 and 508 a curve GM of T = 0.002 s. Now a GM at the bound is folded
  // into N. Tolerance: the likelihood's bound on N here is sqrt(1.12 / (2 x 180000 blocks)) = 0.18 %
  // (WhittleCramerRao.WhiteNoiseBoundIsTheClosedForm); a free GM may still take a slice at an
  // interior T, so 3 % (the criterion) is the check, 16 sd of the bound.
  SensorTruth t;
  t.n = 0.041 * M_PI / 180.0 / 60.0;
  for (unsigned seed : {504u, 506u, 508u}) {
    const ChannelResult r = analyse_gauss_markov(t, 0.01, 360000, seed);
    ASSERT_TRUE(r.fit && r.curve_fit);
    ASSERT_EQ(r.fit->method, "whittle") << r.likelihood_error;
    for (const NoiseFit* f : {&*r.fit, &*r.curve_fit}) {
      const TermEstimate& n = (*f)[ModelTerm::kN];
      const TermEstimate& gm = (*f)[ModelTerm::kGaussMarkov];
      EXPECT_NEAR(n.value / t.n, 1.0, 0.03) << f->method << " seed " << seed;
      EXPECT_FALSE(gm.resolved) << f->method << " seed " << seed << " GM " << gm.value << " T " << gm.shape;
      // Never below the bound: 5 blocks of 0.02 s (likelihood), 5 shortest taus of 0.01 s (curve).
      EXPECT_GE(gm.shape, (f == &*r.fit ? 0.1 : 0.05) * (1 - 1e-9)) << f->method << " seed " << seed;
      EXPECT_EQ(gm.lo, 0.0) << f->method << " seed " << seed;  // its interval reaches 0
      std::printf("seed %u %s: N %.4f of the truth, GM %.3g (T %.3g s) %s\n", seed, f->method.c_str(), n.value / t.n,
                  gm.value, gm.shape, gm.resolved ? "resolved" : "not resolved");
    }
  }
}

TEST(WhittleFit, NoGaussMarkovWhereQuantisationHidesTheWhiteNoise) {
  // Issue 14: the paper's HG1700 gyro Z (Table 5: Q 16.687 arcsec, N 0.045 deg/sqrt(h), no bias term) at
  // 100 Hz, fitted with --gauss-markov. Q, white noise of the integrated angle, has the rate density
  // (2 pi f)^2 Q^2 tau0 at low f, above N^2 from f_c = N / (2 pi Q sqrt(tau0)) = 0.26 Hz: white noise shows
  // only below f_c. A GM with its corner 1/(2 pi T) near f_c (T of 0.3-2 s, well above the 0.1 s
  // bound of 5 blocks) then split N's band with it: in the 16 h paper-sensor study N came out 1-6 % low in
  // some seeds, and its interval's lower end at 0.16-0.8 of the truth (the record measures N to 0.6 %).
  // Checked: N within 3 % (the criterion), its 95 % interval holding the truth and no wider
  // than 10 % below it, and no GM resolved.
  constexpr double kArcsec = M_PI / 180.0 / 3600.0, dt = 0.01;
  const double q = 16.687 * kArcsec;
  SensorTruth t;
  t.n = 0.045 * M_PI / 180.0 / 60.0;
  const double f_c_hz = t.n / (2.0 * M_PI * q * std::sqrt(dt));
  EXPECT_NEAR(f_c_hz, 0.26, 0.01);
  for (unsigned seed : {5001u, 5002u, 5003u}) {
    auto y = simulate_rate(t, dt, 4 * 360000, seed);
    add_quantisation(y, dt, q, seed + 100);
    AnalysisOptions opt;
    opt.fit_options.gauss_markov = true;
    const ChannelResult r = analyze({phase_from_rates(std::move(y), dt, "gyro_z", "rad/s")}, opt).front();
    ASSERT_TRUE(r.fit);
    ASSERT_EQ(r.fit->method, "whittle") << r.likelihood_error;
    const TermEstimate& n = (*r.fit)[ModelTerm::kN];
    const TermEstimate& gm = (*r.fit)[ModelTerm::kGaussMarkov];
    std::printf("seed %u: N %.4f of the truth [%.4f, %.4f]; GM %.3g (T %.3g s) %s\n", seed, n.value / t.n, n.lo / t.n,
                n.hi / t.n, gm.value, gm.shape, gm.resolved ? "resolved" : "not resolved");
    EXPECT_NEAR(n.value / t.n, 1.0, 0.03) << "seed " << seed;
    EXPECT_LE(n.lo, t.n) << "seed " << seed;
    EXPECT_GE(n.hi, t.n) << "seed " << seed;
    EXPECT_GT(n.lo / t.n, 0.9) << "seed " << seed;
    EXPECT_FALSE(gm.resolved) << "seed " << seed;
  }
}

TEST(WhittleFit, RealGaussMarkovIsStillFound) {
  // Control: the same white noise with a GM that dominates (sigma 5x the white noise's Allan
  // deviation at T: 2 sigma^2 T = 50 N^2) at T = 20 s and at a short but resolved T = 0.5 s (25 blocks, 5x the bound).
  // Tolerances of the noise study: sigma within 10 %, T within 20 %.
  for (double T : {20.0, 0.5}) {
    SensorTruth t;
    t.n = 0.041 * M_PI / 180.0 / 60.0;
    t.gm_t_s = T;
    t.gm_sigma = 5.0 * t.n / std::sqrt(T);
    const ChannelResult r = analyse_gauss_markov(t, 0.01, 360000, 41);
    ASSERT_TRUE(r.fit);
    ASSERT_EQ(r.fit->method, "whittle") << r.likelihood_error;
    const TermEstimate& gm = (*r.fit)[ModelTerm::kGaussMarkov];
    EXPECT_TRUE(gm.resolved) << "T " << T;
    EXPECT_NEAR(gm.value / t.gm_sigma, 1.0, 0.10) << "T " << T;
    EXPECT_NEAR(gm.shape / T, 1.0, 0.20) << "T " << T;
    EXPECT_NEAR((*r.fit)[ModelTerm::kN].value / t.n, 1.0, 0.03) << "T " << T;
    std::printf("GM T %.1f s: sigma %.4f, T %.4f, N %.4f of the truth\n", T, gm.value / t.gm_sigma, gm.shape / T,
                (*r.fit)[ModelTerm::kN].value / t.n);
  }
}
