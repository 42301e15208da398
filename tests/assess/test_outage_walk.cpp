// `ldv outage` on the real walk (../shared/data/drives/walk_0827 through tests/estimator/data/walk_0827_mems.yaml):
// no truth, so the drift is measured against the uncut RTK-aided solution. Outages of 10 s and 30 s start while
// walking (turning most of the time); the checkpoint restarts must equal a rerun of the whole file with the
// fixes removed (what a user cutting the GNSS file gets), and the drift stays within a consumer-MEMS budget.
#include <gtest/gtest.h>

#include <filesystem>

#include "toolbox/assess/nav_inputs.hpp"
#include "toolbox/assess/outage_run.hpp"

namespace ldv::assess {
namespace {
namespace fs = std::filesystem;

NavInputs walk_inputs() {
  NavInputArgs a;
  a.config = (fs::path(__FILE__).parent_path().parent_path() / "estimator/data/walk_0827_mems.yaml").string();
  return load_nav_inputs(a);
}

OutageRunOptions walk_plan(bool exact) {
  OutageRunOptions o;
  o.lengths_s = {10.0, 30.0};
  o.plan.converge_s = 20.0;  // the walk lasts ~100 s
  o.plan.recovery_s = 10.0;
  o.plan.min_speed_mps = 0.8;
  o.exact_rerun = exact;
  return o;
}

TEST(OutageWalk, DriftAgainstTheUncutSolutionStaysWithinAConsumerMemsBudget) {
  const NavInputs in = walk_inputs();
  const OutageRun fast = run_outages(in.imu, in.gnss, in.config, in.options, NavSeries{}, walk_plan(false));
  const OutageRun exact = run_outages(in.imu, in.gnss, in.config, in.options, NavSeries{}, walk_plan(true));
  EXPECT_EQ(fast.reference, "uncut solution");
  ASSERT_EQ(fast.outages.size(), exact.outages.size());
  int n10 = 0, n30 = 0;
  for (size_t k = 0; k < fast.outages.size(); ++k) {
    const OutageResult& r = fast.outages[k];
    // Checkpoint restart == rerun from the start with the fixes removed.
    EXPECT_NEAR(r.max_horizontal_m, exact.outages[k].max_horizontal_m, 1e-9) << "outage from " << r.window.start_s;
    EXPECT_LE((r.end_drift.pos_ned_m - exact.outages[k].end_drift.pos_ned_m).norm(), 1e-9)
        << "outage from " << r.window.start_s;
    std::printf("walk_0827: %2.0f s outage from %.1f: max horizontal drift %.2f m\n", r.window.length_s,
                r.window.start_s, r.max_horizontal_m);
    // Budget (tests/estimator/test_walk.cpp): 5-10 mg effective accel error -> 0.5 a t^2 = 2.5-5 m at 10 s and
    // 25-45 m at 30 s, plus heading error times distance walked.
    if (r.window.length_s == 10.0) {
      ++n10;
      EXPECT_LT(r.max_horizontal_m, 6.0);
    } else {
      ++n30;
      EXPECT_LT(r.max_horizontal_m, 60.0);
    }
  }
  EXPECT_GE(n10, 4);
  EXPECT_GE(n30, 2);
}

}  // namespace
}  // namespace ldv::assess
