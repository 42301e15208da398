// Given simulated drives with truth (tactical and MEMS grades, RTK at 1 and 5 Hz, a 60 s outage during
// manoeuvres), when the filter runs from the simulator's KF-GINS configuration, then the errors are at
// RTK level while aided, the outage drift is bounded, and the errors are consistent with the filter's
// own covariance (average NEES per 3-dof block inside a band around 3).
#include <gtest/gtest.h>

#include "estimator/run/run_navigation.hpp"
#include "sim_run.hpp"

namespace ldv::est {
namespace {

sim::SimResult simulate(const std::string& grade, double gnss_hz, uint64_t seed, double duration_s,
                        std::vector<sim::Outage> outages = {}) {
  sim::SimRequest req;
  req.grade = grade;
  req.seed = seed;
  req.duration_s = duration_s;
  req.scenario = "drive";
  req.gnss_rate_hz = gnss_hz;
  req.outages = std::move(outages);
  return sim::simulate(req);
}

void report(const char* name, const test::Accuracy& a) {
  std::printf("%s: horizontal RMS %.4f m, vertical RMS %.4f m, velocity RMS %.4f m/s, roll/pitch RMS %.4f deg, "
              "yaw RMS %.4f deg, outage drift %.3f m (1 sigma %.3f m), NEES pos %.2f vel %.2f att %.2f (3 expected), gate rejections %ld\n",
              name, a.horiz_rms_m, a.vert_rms_m, a.vel_rms_mps, a.roll_pitch_rms_deg, a.yaw_rms_deg, a.outage_drift_m, a.outage_drift_sigma_m,
              a.nees_pos, a.nees_vel, a.nees_att, a.gate_rejections);
}

// Time-averaged NEES of strongly time-correlated errors: a generous but two-sided band around 3.
// Position is checked separately: the simulator's RTK noise has a Gauss-Markov part (tau 60 s) that a
// white measurement model (KF-GINS's too) cannot represent, so without a state that absorbs it the
// position covariance is optimistic (measured NEES ~9 for kfgins21 at 5 Hz; see estimator/README.md).
void expect_consistent(const test::Accuracy& a, bool position_too = true) {
  if (position_too) {
    EXPECT_GT(a.nees_pos, 0.3);
    EXPECT_LT(a.nees_pos, 9.0);
  }
  EXPECT_GT(a.nees_vel, 0.3);
  EXPECT_LT(a.nees_vel, 9.0);
  EXPECT_GT(a.nees_att, 0.3);
  EXPECT_LT(a.nees_att, 9.0);
}

TEST(Accuracy, TacticalGradeRtk5HzWithOutageKfgins21) {
  const auto sim = simulate("hg1700-typical", 5.0, 11, 600.0, {{300.0, 60.0}});
  FilterOptions o = options_from_kfgins(sim.kfgins);
  o.model = "kfgins21";
  const auto a = test::evaluate(sim, o);
  report("hg1700-typical 5 Hz kfgins21", a);
  EXPECT_LT(a.horiz_rms_m, 0.03);
  EXPECT_LT(a.vel_rms_mps, 0.02);
  EXPECT_LT(a.roll_pitch_rms_deg, 0.02);
  EXPECT_LT(a.yaw_rms_deg, 0.1);
  EXPECT_LT(a.outage_drift_m, 6.0);  // KF-GINS reference: 3-6 m after 60 s
  expect_consistent(a, /*position_too=*/false);
}

TEST(Accuracy, TacticalGradeRtk5HzGeoLdv51) {
  const auto sim = simulate("hg1700-typical", 5.0, 12, 600.0, {{300.0, 60.0}});
  FilterOptions o = options_from_kfgins(sim.kfgins);
  o.model = "geoldv51";
  const auto a = test::evaluate(sim, o);
  report("hg1700-typical 5 Hz geoldv51", a);
  EXPECT_LT(a.horiz_rms_m, 0.03);
  EXPECT_LT(a.yaw_rms_deg, 0.1);
  EXPECT_LT(a.outage_drift_m, 6.0);
  expect_consistent(a);
}

TEST(Accuracy, MemsGradeRtk1HzWithOutage) {
  const auto sim = simulate("3dm-gx2-typical", 1.0, 13, 600.0, {{300.0, 60.0}});
  FilterOptions o = options_from_kfgins(sim.kfgins);
  const auto a = test::evaluate(sim, o);
  report("3dm-gx2-typical 1 Hz kfgins21", a);
  EXPECT_LT(a.horiz_rms_m, 0.10);
  EXPECT_LT(a.roll_pitch_rms_deg, 0.2);
  EXPECT_LT(a.yaw_rms_deg, 1.0);
  // One seed of a 60 s MEMS outage: the drift spreads from 70 to 330 m over seeds of this drive (the
  // outage starts at a stop; ZUPTs there help on average, 229 -> 177 m over five seeds, not in every
  // seed), so the single-run check is that the filter knows its drift: inside its own 3 sigma.
  EXPECT_LT(a.outage_drift_m, 3.0 * a.outage_drift_sigma_m);
  expect_consistent(a);
}

}  // namespace
}  // namespace ldv::est
