// Given simulated drives with exactly one hidden effect (or none), when `ldv diagnose` runs with the
// model under test, then the hidden effect is named, confirmed, estimated, and adding it removes the
// excess error; with none, nothing is added. (The many-seed version: test_diagnose_montecarlo.)
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include "common/io/input_error.hpp"
#include "tests/diagnose/trial.hpp"
#include "toolbox/diagnose/report_json.hpp"
#include "toolbox/diagnose/report_text.hpp"

namespace ldv::diag {
namespace {

using testing::Outcome;
using testing::Trial;

void expect_found_and_fixed(const Trial& t) {
  const Outcome o = testing::run_trial(t, true);
  EXPECT_TRUE(o.ranked_first) << t.effect << ": ranked first was " << o.first;
  EXPECT_TRUE(o.verdict_has) << t.effect;
  EXPECT_GE(o.excess_removed(), 0.8) << t.effect << ": RMS error " << o.err_base_m << " m -> " << o.err_after_m
                                      << " m (known model " << o.err_ref_m << " m)";
}

}  // namespace

TEST(DiagnoseSim, NoHiddenEffectAddsNothing) {
  for (const char* grade : {"hg1700-typical", "3dm-gx2-typical"})
    for (uint64_t seed : {11u, 12u, 13u}) {
      const Outcome o = testing::run_trial({grade, "", "kfgins21", seed});
      EXPECT_FALSE(o.verdict_any) << grade << " seed " << seed << ": top candidate " << o.first;
    }
}

TEST(DiagnoseSim, HiddenLeverArmIsFoundEstimatedAndRemovesTheError) {
  expect_found_and_fixed({"hg1700-typical", "lever_arm=0.5,-0.3,-1.2", "kfgins21", 21});
}

TEST(DiagnoseSim, HiddenTimeOffsetIsFoundAndRemovesTheError) {
  expect_found_and_fixed({"hg1700-typical", "time_offset=0.05", "kfgins21", 22});
}

TEST(DiagnoseSim, HiddenGyroScaleIsFoundByAnIns15Model) {
  // kfgins21 already estimates gyro_scale: the model under test is ins15.
  expect_found_and_fixed({"hg1700-typical", "gyro_scale=1500,-1000,2000", "ins15", 23});
}

TEST(DiagnoseSim, MemsLeverArmIsRankedFirst) {
  const Outcome o = testing::run_trial({"3dm-gx2-typical", "lever_arm=0.5,-0.3,-1.2", "kfgins21", 24});
  EXPECT_TRUE(o.ranked_first) << o.first;
  EXPECT_TRUE(o.verdict_has);
}

// Issue 48, item 4: a van's antenna 3.5 m behind and 2.6 m above a MEMS IMU (lever arm -3.54, 2.35, -2.63 m), 5 Hz RTK,
// a model (ins15) without it. So far from the data the score test lost its power (p = 0.12: the states absorb the
// signal, the gate drops 243 turning fixes) and the verdict named accel and gyro scales. Where the model check fails
// every testable candidate is confirmed by its rerun: the lever arm gains 8800 in log-likelihood.
TEST(DiagnoseSim, GivenAVansLeverArmOnAMemsImu_ThenTheLikelihoodNamesItFirstAndTheErrorFalls) {
  Trial t{"3dm-gx2-typical", "lever_arm=-3.54,2.35,-2.63", "ins15", 12};
  t.duration_s = 600.0;
  t.gnss_rate_hz = 5.0;
  const Outcome o = testing::run_trial(t, true);
  std::printf("van lever arm: first %s, estimate within %.1f sigma, RMS error %.3f m -> %.3f m (known model %.3f m)\n",
              o.first.c_str(), o.estimate_error_sigmas, o.err_base_m, o.err_after_m, o.err_ref_m);
  EXPECT_TRUE(o.ranked_first) << o.first;
  EXPECT_TRUE(o.verdict_has);
  EXPECT_LT(o.estimate_error_sigmas, 3.0);
  EXPECT_GE(o.excess_removed(), 0.9);
}

// Issue 48, item 4: a MEMS accel misalignment of realistic size (1300, -1200, 1500 arcsec: 6-7 mrad), 5 Hz RTK, a
// model (ins15) that also misses the grade's scale factors. The screening ranked a gyro misalignment first and the
// accel misalignment fifth, past the two candidates rerun, and the verdict added the gyro misalignment first. Every
// significant candidate is rerun now: the accel misalignment gains the most. (Its value: within 2.5 and 5.8 sigma of
// the truth here, the missing scales' share in it; 2.1 and 3.3 sigma with kfgins21, which holds them.)
TEST(DiagnoseSim, GivenAMemsAccelMisalignment_ThenTheRerunsNameItFirst) {
  for (const uint64_t seed : {11u, 12u}) {
    Trial t{"3dm-gx2-typical", "accel_misalignment=1300,-1200,1500", "ins15", seed};
    t.duration_s = 1200.0;
    t.gnss_rate_hz = 5.0;
    const Outcome o = testing::run_trial(t);
    std::printf("MEMS accel misalignment, seed %lu: first %s, estimate within %.1f sigma\n",
                static_cast<unsigned long>(seed), o.first.c_str(), o.estimate_error_sigmas);
    EXPECT_TRUE(o.ranked_first) << "seed " << seed << ": first " << o.first;
    EXPECT_TRUE(o.verdict_has) << "seed " << seed;
  }
}

// A 3 cm lever arm (near its detectable size) whose rerun competes with every significant candidate: the time
// offset's rerun dropped the first fix (moved before the IMU's start), and that fix's term alone gained 286 in
// log-likelihood: the verdict named a 0.03 +- 0.3 ms time offset first. Runs are compared over the fixes both used.
TEST(DiagnoseSim, GivenANearThresholdLeverArm_ThenNoRerunGainsByLosingAFix) {
  Trial t{"hg1700-typical", "lever_arm=0.02,-0.015,0.03", "kfgins21", 1000};
  const Outcome o = testing::run_trial(t);
  std::printf("near lever arm: first %s, estimate within %.1f sigma\n", o.first.c_str(), o.estimate_error_sigmas);
  EXPECT_TRUE(o.ranked_first) << o.first;
  EXPECT_TRUE(o.verdict_has);
  EXPECT_LT(o.estimate_error_sigmas, 3.0);
}

TEST(DiagnoseSim, LeverArmEstimateAndJsonContract) {
  testing::SimCase c;
  c.effect = "lever_arm=0.5,-0.3,-1.2";
  c.seed = 25;
  c.duration_s = 600.0;
  const sim::SimResult r = testing::simulate(c);
  const Diagnosis d = diagnose(testing::inputs(r), testing::options(r, "kfgins21"));
  ASSERT_EQ(d.add.size(), 1u);
  EXPECT_EQ(d.add[0], "lever_arm");
  ASSERT_EQ(d.added_estimates.size(), 1u);
  EXPECT_TRUE(d.added_estimates[0].value_si.isApprox(Eigen::Vector3d(0.5, -0.3, -1.2), 0.05));
  const CandidateScore& top = d.steps.front().screening.ranked.front();
  EXPECT_EQ(top.name, "lever_arm");
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(top.estimate_si(i), r.injected_effects.at("lever_arm")[i], 0.05);
  const std::string json = diagnosis_json(d);
  for (const char* key : {"\"model\": \"kfgins21\"", "\"consistent\": false", "\"candidates\": [", "\"effect\": \"lever_arm\"",
                          "\"statistic\": ", "\"p_value\": ", "\"estimate\": [", "\"sigma\": [", "\"group\": [",
                          "\"verdict\": {\"add\": [\"lever_arm\"]"})
    EXPECT_NE(json.find(key), std::string::npos) << key;
  if (std::filesystem::exists("/dev/full")) {  // a full disk: an error naming the file, not a report said written
    try {
      write_json(d, "/dev/full");
      ADD_FAILURE() << "a JSON report written to a full disk was reported written";
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
    }
  }
}

// Standing still, nothing excites a scale factor or a time offset: they are reported untestable, not
// guessed. (The lever arm stays testable against the initial position prior.)
TEST(DiagnoseSim, ScaleFactorsAreUntestableWhenStandingStill) {
  testing::SimCase c;
  c.scenario = "static";
  c.duration_s = 300.0;
  const sim::SimResult r = testing::simulate(c);
  const Diagnosis d = diagnose(testing::inputs(r), testing::options(r, "ins15"));
  for (const CandidateScore& s : d.steps.front().screening.ranked)
    if (s.name == "gyro_scale" || s.name == "time_offset") {
      EXPECT_FALSE(s.testable) << s.name;
    }
  EXPECT_TRUE(d.add.empty());
}

}  // namespace ldv::diag

namespace ldv::diag {

// On constant-speed circles the time offset moves the antenna along track, exactly as a lever arm
// along body x does: the two come out as one group (with the manoeuvre that separates them), not as a
// coin toss.
TEST(DiagnoseSim, TimeOffsetAndLeverArmAreOneGroupOnCircles) {
  testing::SimCase c;
  c.scenario = "circle";
  c.effect = "time_offset=0.05";
  c.duration_s = 600.0;
  c.seed = 26;
  const sim::SimResult r = testing::simulate(c);
  const Diagnosis d = diagnose(testing::inputs(r), testing::options(r, "kfgins21"));
  const CandidateScore& top = d.steps.front().screening.ranked.front();
  ASSERT_TRUE(top.name == "time_offset" || top.name == "lever_arm") << top.name;
  const auto has = [&](const char* n) { return std::find(top.group.begin(), top.group.end(), n) != top.group.end(); };
  EXPECT_TRUE(has("time_offset") && has("lever_arm"));
  EXPECT_FALSE(top.separate_by.empty());
}

}  // namespace ldv::diag

namespace ldv::diag {
// Issue 46 (6), results on no data: a drive whose GNSS never overlapped the IMU (0 measurement epochs) was reported
// as "the model is consistent with the data", and a truth that ended early silently dropped the comparison.
TEST(DiagnoseSim, GivenNoMeasurementEpochs_ThenTheDiagnosisIsRefusedSayingWhereTheDataLie) {
  testing::SimCase c;
  c.duration_s = 120.0;
  c.scenario = "circle";  // never stops: no standstill either
  const sim::SimResult r = testing::simulate(c);
  DiagnoseInputs in = testing::inputs(r);
  for (GnssFix& f : in.gnss) f.t_s += 10000.0;  // another time scale
  in.cfg.gnss_path = "gnss_late.txt";
  try {
    diagnose(in, testing::options(r, "kfgins21"));
    FAIL() << "a diagnosis on no measurement";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("gnss_late.txt"), std::string::npos) << what;
    EXPECT_NE(what.find("no measurement reached the filter"), std::string::npos) << what;
  }
}

TEST(DiagnoseSim, GivenATruthThatEndsEarly_ThenTheReportSaysWhatItCovered) {
  testing::SimCase c;
  c.duration_s = 120.0;
  const sim::SimResult r = testing::simulate(c);
  DiagnoseInputs in = testing::inputs(r);
  DiagnoseOptions o = testing::options(r, "kfgins21");
  o.max_added = 0;
  const double t0 = in.truth.front().sow_s;
  std::erase_if(in.truth, [&](const NavRecord& n) { return n.sow_s > t0 + 30.0; });  // before the 60 s skip ends
  const Diagnosis none = diagnose(in, o);
  EXPECT_TRUE(none.truth_before.given);
  EXPECT_FALSE(none.truth_before.available);
  EXPECT_NE(none.truth_before.coverage_note.find("covers 0 of"), std::string::npos) << none.truth_before.coverage_note;
  std::ostringstream text;
  print_report(text, none);
  EXPECT_NE(text.str().find("not compared: the truth"), std::string::npos) << text.str();

  in = testing::inputs(r);
  std::erase_if(in.truth, [&](const NavRecord& n) { return n.sow_s > t0 + 90.0; });  // half the compared span
  const Diagnosis part = diagnose(in, o);
  EXPECT_TRUE(part.truth_before.available);
  EXPECT_GT(part.truth_before.compared_epochs, 0);
  EXPECT_LT(part.truth_before.compared_epochs, part.truth_before.run_epochs);
  EXPECT_FALSE(part.truth_before.coverage_note.empty());
}
}  // namespace ldv::diag

namespace ldv::diag {
// Issue 47, the contract: `ldv diagnose --json` lists {name: gnss_noise, estimate, sigma, applied} in
// self_calibration[]: the factor the GNSS position innovations call for on the stated variance, per solution quality,
// estimated apart from the IMU's. A drive whose gnss.txt states a std 5x too small: the simulator's RTK error is half
// white, so fix-to-fix differences show 12.5x the stated variance.
TEST(DiagnoseSim, GivenAGnssStdStatedFiveTimesTooSmall_ThenTheSelfCalibrationReportsTheGnssNoiseFactor) {
  testing::SimCase c;
  c.duration_s = 300.0;
  c.gnss_rate_hz = 5.0;
  c.seed = 47;
  const sim::SimResult r = testing::simulate(c);
  DiagnoseInputs in = testing::inputs(r);
  for (GnssFix& f : in.gnss) f.pos_std_ned_m /= 5.0;
  DiagnoseOptions o = testing::options(r, "kfgins21");
  o.max_added = 0;
  const Diagnosis d = diagnose(in, o);
  const SelfCalibration* gnss = nullptr;
  for (const SelfCalibration& s : d.self_calibration)
    if (s.name == "gnss_noise") gnss = &s;
  ASSERT_NE(gnss, nullptr);
  ASSERT_EQ(gnss->estimate_si.size(), 1);  // fixed solutions only
  EXPECT_NEAR(gnss->estimate_si(0), 12.5, 0.3 * 12.5);
  // With its sigma (issue 48, 5): the windowed Fisher information of 120 s of 5 Hz fix pairs, about 3 % in the log
  std::printf("[ info ] GNSS noise factor %.2f +- %.2f\n", gnss->estimate_si(0), gnss->sigma_si(0));
  ASSERT_EQ(gnss->sigma_si.size(), 1);
  EXPECT_GT(gnss->sigma_si(0), 0.01 * gnss->estimate_si(0));
  EXPECT_LT(gnss->sigma_si(0), 0.1 * gnss->estimate_si(0));
  EXPECT_FALSE(gnss->applied);
  const std::string json_path = (std::filesystem::temp_directory_path() / "ldv_gnss_noise.json").string();
  write_json(d, json_path);
  std::ifstream json(json_path);
  std::stringstream text;
  text << json.rdbuf();
  EXPECT_NE(text.str().find("\"name\": \"gnss_noise\""), std::string::npos) << text.str().substr(0, 400);
}
}  // namespace ldv::diag

namespace ldv::diag {
namespace {
// A drive whose gnss.txt states a std 5x smaller than its noise, diagnosed to the end.
Diagnosis diagnose_with_std_stated_small(const std::string& grade, const std::string& effect, uint64_t seed) {
  testing::SimCase c;
  c.grade = grade;
  c.effect = effect;
  c.duration_s = 600.0;
  c.gnss_rate_hz = 5.0;
  c.seed = seed;
  const sim::SimResult r = testing::simulate(c);
  DiagnoseInputs in = testing::inputs(r);
  for (GnssFix& f : in.gnss) f.pos_std_ned_m /= 5.0;
  return diagnose(in, testing::options(r, "kfgins21"));
}
}  // namespace

// Issue 47, "effects before noise", one model selection: a receiver that states a std 5x too small made every effect's
// rerun fit worse (each pulled the state towards the noise), and the diagnosis ended "nothing to add ... NOT shown
// consistent" with the GNSS factor only reported. The GNSS noise is now a candidate judged on the same likelihood:
// it is the verdict, with the factor the fix-to-fix differences show (12.5, the white half of the simulator's RTK
// error), no effect is added, the rescaled model's NIS is at its expectation and the error does not grow.
TEST(DiagnoseSim, GivenAGnssStdStatedFiveTimesTooSmall_ThenTheVerdictRescalesTheNoiseAndAddsNoEffect) {
  for (const char* grade : {"hg1700-typical", "3dm-gx2-typical"}) {
    const Diagnosis d = diagnose_with_std_stated_small(grade, "", 41);
    const SensorCheck* after = d.check_after.find(est::sensors::kGnssPosition);
    ASSERT_NE(after, nullptr);
    std::printf(
        "[ info ] %s: effects added %zu, GNSS noise added %d (x%.2f), mean NIS after %.2f, error %.3f -> %.3f m\n",
        grade, d.add.size(), static_cast<int>(d.gnss_noise_added.has_value()),
        d.gnss_noise_added ? d.gnss_noise_added->value_si(0) : NAN, after->mean_nis.value, d.truth_before.rms_pos_3d_m,
        d.truth_after.rms_pos_3d_m);
    EXPECT_TRUE(d.add.empty()) << grade << ": " << (d.add.empty() ? "" : d.add.front());
    ASSERT_TRUE(d.gnss_noise_added.has_value()) << grade;
    ASSERT_EQ(d.gnss_noise_added->value_si.size(), 1);  // fixed solutions only
    EXPECT_NEAR(d.gnss_noise_added->value_si(0), 12.5, 0.3 * 12.5) << grade;
    EXPECT_NEAR(d.final_options.gnss_variance_scale[0], d.gnss_noise_added->value_si(0), 1e-9);
    // From about 30 to its expectation, 3 (to 10 %: the correlated half of the RTK error is left to the model)
    EXPECT_NEAR(after->mean_nis.value, 3.0, 0.3) << grade;
    EXPECT_LE(d.truth_after.rms_pos_3d_m, 1.05 * d.truth_before.rms_pos_3d_m) << grade;
    EXPECT_NE(config_snippet(d).find("gnss_variance_scale: ["), std::string::npos) << config_snippet(d);
  }
}

// The same misstated receiver with a lever arm the configuration does not know: both are named, the lever arm as an
// effect whose estimate is within 3 sigma of the truth, the noise as the GNSS factor; the noise takes no part of the
// lever arm's misfit (the fix-to-fix differences do not show a structured error).
TEST(DiagnoseSim, GivenAHiddenLeverArmAndTheGnssStdStatedFiveTimesTooSmall_ThenBothAreNamed) {
  const Diagnosis d = diagnose_with_std_stated_small("hg1700-typical", "lever_arm=0.5,-0.3,-1.2", 43);
  std::string order;
  for (const DiagnosisStep& s : d.steps) order += s.added + " ";
  std::printf("[ info ] steps added: %s\n", order.c_str());
  ASSERT_EQ(d.add.size(), 1u) << order;
  EXPECT_EQ(d.add.front(), "lever_arm");
  ASSERT_TRUE(d.gnss_noise_added.has_value()) << order;
  EXPECT_NEAR(d.gnss_noise_added->value_si(0), 12.5, 0.3 * 12.5);
  ASSERT_EQ(d.added_estimates.size(), 1u);
  const EffectEstimate& lever = d.added_estimates.front();
  const Vec3 truth(0.5, -0.3, -1.2);
  for (int i = 0; i < 3; ++i)
    EXPECT_LT(std::abs(lever.value_si(i) - truth(i)), 3.0 * lever.std_si(i))
        << "axis " << i << ": " << lever.value_si(i) << " +- " << lever.std_si(i);
}
}  // namespace ldv::diag

namespace ldv::diag {
// Issue 47, the IMU noise in the same selection: vibration on the move that the standstill at the start cannot show
// (white noise of 100x the configured PSD once the drive moves off, as a vehicle's grows with speed). No effect is
// missing: the verdict raises the IMU noise by the factors the fixes' likelihood finds (gyro 76, accel 48: the
// adaptation's own windowed MAP factor, held near the standstill's measurement by its prior, read 14x for both) and
// adds no effect.
TEST(DiagnoseSim, GivenVibrationOnTheMoveTheStandstillCannotShow_ThenTheVerdictRaisesTheImuNoiseAndAddsNoEffect) {
  testing::SimCase c;
  c.grade = "3dm-gx2-typical";
  c.duration_s = 600.0;
  c.gnss_rate_hz = 5.0;
  c.seed = 45;
  const sim::SimResult r = testing::simulate(c);
  DiagnoseInputs in = testing::inputs(r);
  const est::FilterOptions configured = est::options_from_kfgins(r.kfgins);
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  const double extra = std::sqrt(100.0 - 1.0);  // the PSD 100x: the added std sqrt(99) x the configured density
  const double moves_off_s = in.gnss.front().t_s + 65.0;  // the `drive` scenario stands for its first 60 s
  for (ImuIncrement& m : in.imu) {
    if (m.t_s < moves_off_s) continue;
    const double sqrt_dt = std::sqrt(m.dt_s);
    for (int i = 0; i < 3; ++i) {
      m.dtheta_b_rad(i) += extra * configured.arw_rad_per_sqrt_s(i) * sqrt_dt * n(rng);
      m.dvel_b_mps(i) += extra * configured.vrw_mps_per_sqrt_s(i) * sqrt_dt * n(rng);
    }
  }
  const Diagnosis d = diagnose(in, testing::options(r, "kfgins21"));
  std::string order;
  for (const DiagnosisStep& s : d.steps) order += s.added + " ";
  if (d.imu_noise_added)
    std::printf("[ info ] steps added: %s; IMU noise %.1f +- %.1f (gyro), %.1f +- %.1f (accel) x the PSD\n",
                order.c_str(), d.imu_noise_added->value_si(0), d.imu_noise_added->std_si(0),
                d.imu_noise_added->value_si(1), d.imu_noise_added->std_si(1));
  if (!d.imu_noise_added || !d.add.empty()) print_report(std::cout, d);
  EXPECT_TRUE(d.add.empty()) << order;
  ASSERT_TRUE(d.imu_noise_added.has_value()) << order;
  // The gyros' 100x within 0.6-1.5x. The accelerometers' share is weakly observable here (their noise moves the 5 Hz
  // positions by about a millimetre between fixes, the RTK's is a centimetre): within a factor 3.
  EXPECT_GT(d.imu_noise_added->value_si(0), 0.6 * 100.0);
  EXPECT_LT(d.imu_noise_added->value_si(0), 1.5 * 100.0);
  EXPECT_GT(d.imu_noise_added->value_si(1), 100.0 / 3.0);
  EXPECT_LT(d.imu_noise_added->value_si(1), 3.0 * 100.0);
  EXPECT_FALSE(d.gnss_noise_added.has_value()) << order;
}
}  // namespace ldv::diag
