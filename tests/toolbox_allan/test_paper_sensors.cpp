// The short version of issue 14's study at the paper's record lengths (the full one, 20 seeds of each sensor:
// test_paper_sensors_montecarlo.cpp): the 3DM-GX2 as printed in Tables 8-9 (gyro Q in degrees), 5 h at 20 Hz as
// the paper recorded it, 3 seeds; `ldv allan`'s default analysis and the forced Gauss-Markov, each judged by the
// issue's criteria in 2 of 3 seeds (where the record's Cramer-Rao bound allows the tolerance); terms the paper
// did not identify (R) never resolved.
#include "tests/toolbox_allan/paper_sensor_study.hpp"

using namespace ldv::allan;
using namespace ldv::allan::test;

TEST(PaperSensors, Gx2AsPrintedFiveHoursThreeSeedsMeetTheCriteriaTheRecordAllows) {
  const PaperStudy s = run_paper_study("3dm-gx2-paper", 5.0, 20.0, 3, 101);
  print_study(s, "default (bias model by AIC)", s.by_default);
  print_study(s, "--gauss-markov", s.gauss_markov);
  expect_paper_criteria(s, s.by_default, "default", 2.0 / 3.0);
  expect_paper_criteria(s, s.gauss_markov, "--gauss-markov", 2.0 / 3.0);
  // The accelerometers' terms are all within the record's reach: every one is judged, not just printed.
  for (const AxisTally& a : s.gauss_markov) {
    if (a.truth.channel.rfind("accel_", 0) != 0) continue;
    for (PaperTerm t : {PaperTerm::kN, PaperTerm::kGmSigma, PaperTerm::kK})
      EXPECT_TRUE(reachable(a[t], t)) << a.truth.channel << " " << term_name(t);
  }
}

TEST(PaperSensors, AForcedGaussMarkovThatIsWhiteWhereNShowsIsFoldedIntoN) {
  // The gyros Z of the 3DM-GX2 (Q in degrees, then the GM: N dominant nowhere on the Allan curve) and of the
  // HG1700 (Q 16.7 arcsec over N 0.045 deg/sqrt(h), no bias term), with the GM forced. The curve fit did not
  // resolve N on these records (seeds 7 and 11 of the 20-seed study), so T was searched from 5 blocks: a GM of
  // T 0.13-0.5 s, white up to where Q hides N (2 sigma^2 T of density), took N 12-14 % low (0.856, 0.879 of the
  // truth), its interval down to 0.52 and 0. The record measures N to 1.0 % and 0.6 % (Cramer-Rao): checked, N
  // within 3 % (the criterion) and inside its 95 % interval, that interval no more than 10 % below the
  // truth, and the GM not resolved where the sensor has none. Where it has one (the 3DM-GX2, T 144 s, which this
  // record cannot see: the GM is folded into N at the floor and K takes the slow part), the GM sigma's interval
  // holds the truth: the Fisher upper end at the floor's T alone did not.
  struct Record {
    const char* grade;
    double hours, rate_hz;
    uint64_t seed;
  };
  for (const Record& rec : {Record{"3dm-gx2-paper", 5.0, 20.0, 5007u}, Record{"hg1700-paper", 16.0, 100.0, 5011u}}) {
    const ldv::sim::ImuGrade grade = ldv::sim::imu_grade(rec.grade);
    const AxisTruth truth = axes_of(grade)[2];
    const std::vector<PhaseSeries> channels = simulate_static_channels(grade, rec.hours, rec.rate_hz, rec.seed);
    AnalysisOptions forced;
    forced.fit_options.gauss_markov = true;
    forced.fit_options.choose_bias_model = false;
    const ChannelResult r = analyze({channels[2]}, forced).front();
    ASSERT_TRUE(r.fit);
    ASSERT_EQ(r.fit->method, "whittle") << r.likelihood_error;
    const TermEstimate& n = (*r.fit)[ModelTerm::kN];
    const TermEstimate& gm = (*r.fit)[ModelTerm::kGaussMarkov];
    const double n_true = truth[PaperTerm::kN];
    std::printf("%s gyro_z seed %lu: N %.4f of the truth [%.4f, %.4f]; GM %.3g (T %.3g s) %s\n", rec.grade,
                static_cast<unsigned long>(rec.seed), n.value / n_true, n.lo / n_true, n.hi / n_true, gm.value,
                gm.shape, gm.resolved ? "resolved" : "not resolved");
    EXPECT_NEAR(n.value / n_true, 1.0, kTolN) << rec.grade;
    EXPECT_LE(n.lo, n_true) << rec.grade;
    EXPECT_GE(n.hi, n_true) << rec.grade;
    EXPECT_GT(n.lo / n_true, 0.9) << rec.grade;
    if (truth[PaperTerm::kGmSigma] == 0) {
      EXPECT_FALSE(gm.resolved) << rec.grade;
    } else {  // folded or not, the sigma's interval holds the truth (its upper end from the profile over T)
      EXPECT_LE(gm.lo, truth[PaperTerm::kGmSigma]) << rec.grade;
      EXPECT_GE(gm.hi, truth[PaperTerm::kGmSigma]) << rec.grade;
    }
  }
}

TEST(PaperSensors, AQuantisationWeakAgainstTheWhiteNoiseIsEstimatedWithIt_SoNsIntervalHoldsTheTruth) {
  // The 3DM-GX2 accelerometer X: Q is 3-5 % of N's Allan deviation at tau0, and the record bounds it only to
  // 2.7x its value (Cramer-Rao): any estimate of Q is 0 or several times the truth, and N trades against it.
  // With Q held at the curve fit's value (N's interval widened by the curve's sigma of Q, none at Q = 0), N's
  // 95 % interval held the truth in 7 of these 10 records (the study's seeds 1-10). With Q estimated in the
  // likelihood beside N, N's profile interval is over Q too. 9 of 10 asked: a calibrated interval meets it in
  // 91 % of sets of 10.
  const ldv::sim::ImuGrade grade = ldv::sim::imu_grade("3dm-gx2-paper");
  const AxisTruth truth = axes_of(grade)[3];
  ASSERT_EQ(truth.channel, "accel_x");
  const double n_true = truth[PaperTerm::kN];
  int inside = 0;
  const int seeds = 10;
  for (int seed = 1; seed <= seeds; ++seed) {
    const std::vector<PhaseSeries> channels = simulate_static_channels(grade, 5.0, 20.0, 5000u + seed);
    const ChannelResult r = analyze({channels[3]}, AnalysisOptions{}).front();
    ASSERT_TRUE(r.fit);
    ASSERT_EQ(r.fit->method, "whittle") << r.likelihood_error;
    const TermEstimate& n = (*r.fit)[ModelTerm::kN];
    inside += n.lo <= n_true && n_true <= n.hi;
    std::printf("accel_x seed %d: N %.4f of the truth [%.4f, %.4f]; Q %.2f of the truth (curve fit %.2f)\n", seed,
                n.value / n_true, n.lo / n_true, n.hi / n_true, (*r.fit)[ModelTerm::kQ].value / truth[PaperTerm::kQ],
                (*r.curve_fit)[ModelTerm::kQ].value / truth[PaperTerm::kQ]);
    EXPECT_NEAR(n.value / n_true, 1.0, kTolN);
  }
  EXPECT_GE(inside, seeds - 1);
}
