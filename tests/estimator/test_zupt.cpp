// Zero-velocity updates inside a GNSS outage, against the simulator's truth: stop-and-go traffic (tactical IMU),
// GNSS cut for 200 s over several stops. Given the outage, when the vehicle stands still then ZUPTs fire and
// hold the drift below the no-ZUPT drift; when it brakes to a stop (|f| ~ g and w ~ 0 already) no ZUPT fires
// before it has actually stopped; and the error at the outage end stays inside the filter's 3-sigma.
#include <gtest/gtest.h>

#include <cmath>

#include "estimator/run/run_navigation.hpp"
#include "sim_run.hpp"

namespace ldv::est {
namespace {

struct ZuptRun {
  std::vector<double> zupt_true_speed_mps;  // truth speed at each applied ZUPT
  double end_error_m = 0.0, end_sigma_m = 0.0;  // horizontal, at the outage end
};

const sim::SimResult& stop_and_go() {
  static const sim::SimResult s = [] {
    sim::SimRequest r;
    r.grade = "hg1700";
    r.scenario = "stops";
    r.duration_s = 420.0;
    r.gnss_rate_hz = 1.0;
    r.seed = 7;
    r.outages = {{150.0, 200.0}};
    return sim::simulate(r);
  }();
  return s;
}

ZuptRun run(bool zupt) {
  const sim::SimResult& s = stop_and_go();
  FilterOptions o = options_from_kfgins(s.kfgins);
  o.zupt.enabled = zupt;
  NavFilter f(o);
  const double t0 = s.truth.front().t_s, dt = 1.0 / s.request.imu_rate_hz;
  const double t_end = t0 + 150.0 + 200.0 - 0.5;
  auto truth_at = [&](double t) -> const sim::TruthSample& {
    return s.truth[std::min(s.truth.size() - 1, static_cast<size_t>(std::llround((t - t0) / dt)))];
  };
  ZuptRun r;
  bool end_taken = false;
  RunCallbacks cb;
  cb.on_innovation = [&](const InnovationRecord& rec) {
    if (rec.kind == MeasurementKind::kZeroVelocity && rec.accepted)
      r.zupt_true_speed_mps.push_back(truth_at(rec.t_s).vel_n_mps.norm());
  };
  cb.on_epoch = [&](const NavFilter& nf) {
    if (end_taken || nf.state().t_s < t_end) return;
    end_taken = true;
    r.end_error_m = test::nav_error(nf.state(), truth_at(nf.state().t_s)).head<2>().norm();
    r.end_sigma_m = nf.nav_std().pos_ned_m.head<2>().norm();
  };
  run_navigation(s.imu, s.gnss, s.kfgins, f, cb);
  return r;
}

TEST(Zupt, HoldsTheDriftAtStopsAndNeverFiresWhileBraking) {
  const ZuptRun with = run(true), without = run(false);
  std::printf("200 s outage over stops: %zu ZUPTs; horizontal error at the end %.2f m (3 sigma %.2f m) with ZUPT, "
              "%.2f m without\n", with.zupt_true_speed_mps.size(), with.end_error_m, 3 * with.end_sigma_m,
              without.end_error_m);
  ASSERT_GT(with.zupt_true_speed_mps.size(), 50u);  // stops of 5-30 s at up to 5 Hz
  for (double v : with.zupt_true_speed_mps) EXPECT_LT(v, 0.03) << "a ZUPT while moving";
  EXPECT_LT(with.end_error_m, 0.5 * without.end_error_m);
  EXPECT_LT(with.end_error_m, 3.0 * with.end_sigma_m);
  EXPECT_TRUE(without.zupt_true_speed_mps.empty());
}

}  // namespace
}  // namespace ldv::est
