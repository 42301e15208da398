// The real walk (../shared/data/drives/walk_0827: hand-held consumer MEMS IMU at ~150 Hz with z up, the
// receiver's own RTK solution at 4 Hz, heights above MSL), end to end with no given initial state.
// Given the data as recorded, when the filter aligns itself (levelling with the IMU upside down in FRD
// terms, heading from the GNSS course) and runs aided, then it agrees with the RTK-fixed epochs at the cm
// level; and when GNSS is cut for 10 s or 30 s while walking, the solution drifts from the uncut one by
// no more than a MEMS free-inertial budget allows (bounds below); and the IMU time base (the device counter,
// whose rate the host reception times confirm once the tag positions are matched in their CRLF convention)
// leaves no time offset for the filter to find.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "common/geo/earth_model.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/alignment_options_from.hpp"
#include "estimator/run/run_navigation.hpp"
#include "toolbox/assess/nav_inputs.hpp"
#include "toolbox/assess/outage_smoothed.hpp"

namespace ldv::est {
namespace {
namespace fs = std::filesystem;

const std::string kWalk = std::string(LDV_SHARED_DATA_DIR) + "/drives/walk_0827/";
const std::string kConfig = (fs::path(__FILE__).parent_path() / "data/walk_0827_mems.yaml").string();

struct Walk {
  assess::NavInputs in;
  std::vector<GnssFix> gnss;  // as loaded (heights + geoid separation, float std floored)
};

const Walk& walk() {
  static const Walk w = [] {
    Walk r;
    assess::NavInputArgs a;
    a.config = kConfig;
    r.in = assess::load_nav_inputs(a);
    r.gnss = r.in.gnss;
    return r;
  }();
  return w;
}

struct WalkRun {
  std::vector<double> t;
  std::vector<Geodetic> pos;
  std::vector<InnovationRecord> innovations;
  std::string initialisation;
  double t_start = 0;
  Eigen::VectorXd effects, effects_std;
};

WalkRun run_walk(const std::vector<GnssFix>& gnss, const std::vector<std::string>& add = {}) {
  const Walk& w = walk();
  FilterOptions o = w.in.options;
  o.add.insert(o.add.end(), add.begin(), add.end());
  NavFilter f(o);
  const AlignmentOptions ao = alignment_options_from(o);
  WalkRun r;
  RunCallbacks cb;
  cb.on_epoch = [&](const NavFilter& nf) {
    r.t.push_back(nf.state().t_s);
    r.pos.push_back(nf.state().pos);
  };
  cb.on_innovation = [&](const InnovationRecord& rec) { r.innovations.push_back(rec); };
  const RunSummary s = run_navigation(w.in.imu, gnss, w.in.config, f, cb, &ao);
  r.initialisation = s.initialisation;
  r.t_start = s.t_start_s;
  r.effects = f.effect_state();
  r.effects_std = f.covariance().diagonal().tail(f.effect_state().size()).cwiseSqrt();
  return r;
}

// Largest horizontal difference between a run with GNSS cut over [t0, t0 + len) and the uncut run.
double outage_drift(const WalkRun& uncut, double t0, double len) {
  std::vector<GnssFix> cut;
  for (const auto& g : walk().gnss)
    if (g.t_s < t0 || g.t_s >= t0 + len) cut.push_back(g);
  const WalkRun r = run_walk(cut);
  double worst = 0;
  for (size_t i = 0, j = 0; i < r.t.size(); ++i) {
    if (r.t[i] < t0 || r.t[i] >= t0 + len) continue;
    while (j < uncut.t.size() && uncut.t[j] < r.t[i] - 1e-9) ++j;
    if (j >= uncut.t.size()) break;
    worst = std::max(worst, earth::ned_between(uncut.pos[j], r.pos[i]).head<2>().norm());
  }
  return worst;
}

TEST(Walk, RunsEndToEndWithoutInitialState) {
  const Walk& w = walk();
  const WalkRun r = run_walk(w.gnss);
  EXPECT_NE(r.initialisation.find("course over ground"), std::string::npos) << r.initialisation;
  ASSERT_FALSE(r.t.empty());
  EXPECT_GT(r.t.back() - r.t.front(), 100.0) << "navigates over the whole walk";
  for (const auto& p : r.pos) ASSERT_TRUE(std::isfinite(p.lat_rad) && std::isfinite(p.h_m));
}

TEST(Walk, AgreesWithRtkFixedAndBoundsOutageDrift) {
  const Walk& w = walk();
  ASSERT_GT(w.in.imu.size(), 15000u);
  ASSERT_GT(w.gnss.size(), 500u);
  const WalkRun uncut = run_walk(w.gnss);
  ASSERT_FALSE(uncut.t.empty());
  std::map<long, GnssQuality> quality;  // fix epoch (ms) -> quality
  for (const auto& g : w.gnss) quality[std::lround(g.t_s * 1e3)] = g.quality;

  // Agreement with RTK-fixed epochs: the position innovations (predicted - measured) while aided,
  // from 10 s after the alignment.
  double sh = 0, sv = 0;
  long n = 0, accepted = 0, n_all = 0;
  for (const auto& r : uncut.innovations) {
    if (r.sensor != sensors::kGnssPosition || r.t_s < uncut.t_start + 10.0) continue;
    ++n_all;
    const auto q = quality.find(std::lround(r.t_s * 1e3));
    if (q == quality.end() || q->second != GnssQuality::kFixed) continue;
    ++n;
    accepted += r.accepted;
    sh += r.innovation.head<2>().squaredNorm();
    sv += r.innovation(2) * r.innovation(2);
  }
  ASSERT_GT(n, 200);
  const double h_rms = std::sqrt(sh / n), v_rms = std::sqrt(sv / n);

  // Simulated outages while walking (the walk moves from ~t_start + 10 s to ~2 min).
  const double t0 = w.gnss.front().t_s;
  std::vector<double> d10, d30;
  for (double s : {30.0, 45.0, 60.0, 75.0, 90.0}) d10.push_back(outage_drift(uncut, t0 + s, 10.0));
  for (double s : {30.0, 60.0}) d30.push_back(outage_drift(uncut, t0 + s, 30.0));
  std::printf("walk_0827: initial state by %s at %.2f s; RTK-fixed epochs: %ld of %ld position updates, "
              "%.1f %% accepted, innovation RMS horizontal %.3f m vertical %.3f m\n",
              uncut.initialisation.c_str(), uncut.t_start - t0, n, n_all, 100.0 * accepted / n, h_rms, v_rms);
  std::printf("walk_0827: 10 s outage drift (starts +30..+90 s):");
  for (double d : d10) std::printf(" %.2f", d);
  std::printf(" m; 30 s outage drift (+30, +60 s):");
  for (double d : d30) std::printf(" %.2f", d);
  std::printf(" m\n");

  EXPECT_NE(uncut.initialisation.find("course over ground"), std::string::npos) << uncut.initialisation;
  // Aided: the innovations are the INS prediction over one 0.25 s GNSS interval against a ~1 cm solution;
  // a hand-held walk swings the antenna/IMU by cm, so a few cm RMS is the physical floor.
  EXPECT_LT(h_rms, 0.10);
  EXPECT_LT(v_rms, 0.15);
  EXPECT_GT(static_cast<double>(accepted) / n, 0.95);
  // Outages: after calibration a consumer MEMS keeps ~5-10 mg of effective accel error (bias residual plus
  // tilt error 0.3-0.5 deg times g), i.e. 0.5 a t^2 = 2.5-5 m after 10 s, and ~25-45 m after 30 s (plus the
  // heading error times distance walked, 0.5 deg x 40 m = 0.35 m). Bounds: 6 m and 60 m.
  for (double d : d10) EXPECT_LT(d, 6.0);
  for (double d : d30) EXPECT_LT(d, 60.0);
}

// Post-processing the walk: GNSS cut in 10 s and 30 s gaps while walking, filtered forward and smoothed
// backward; inside each gap, the largest horizontal error of both against the uncut solution (which follows the
// ~1 cm RTK fixes: innovation RMS a few cm).
TEST(Walk, SmoothingTiesBothEndsOfAnOutage) {
  const Walk& w = walk();
  std::vector<assess::NavSample> uncut;
  {
    NavFilter f(w.in.options);
    RunCallbacks cb;
    cb.on_epoch = [&](const NavFilter& nf) {
      uncut.push_back(assess::sample_of(nf.state()));
    };
    const AlignmentOptions ao = alignment_options_from(w.in.options);
    run_navigation(w.in.imu, w.gnss, w.in.config, f, cb, &ao);
  }
  const assess::NavSeries reference(std::move(uncut));
  const double t0 = w.gnss.front().t_s;
  auto gaps = [&](std::vector<double> starts, double len) {
    std::vector<assess::OutageWindow> windows;
    for (double s : starts) windows.push_back({len, t0 + s, true});
    return assess::smooth_through_gaps(w.in.imu, w.gnss, w.in.config, w.in.options, windows, reference, {}, 0.05,
                                       false);  // the reference is the uncut run, on the filter's clock
  };
  const auto g10 = gaps({30.0, 45.0, 60.0, 75.0, 90.0}, 10.0);
  const auto g30a = gaps({30.0}, 30.0), g30b = gaps({60.0}, 30.0);
  std::vector<assess::SmoothedGap> all = g10;
  all.push_back(g30a.front());
  all.push_back(g30b.front());
  for (std::size_t i = 0; i < all.size(); ++i) {
    const assess::SmoothedGap& g = all[i];
    std::printf("walk_0827: %s gap %zu: forward max %.2f m, smoothed max %.3f m (1-sigma %.3f m), %d samples\n",
                i < 5 ? "10 s" : "30 s", i, g.forward_max_horizontal_m, g.max_horizontal_m, g.std_horizontal_at_max_m,
                g.samples);
    ASSERT_GT(g.samples, 100);
    // Never worse than forward, and inside the smoother's own 3 sigma (plus the reference's few cm).
    EXPECT_LE(g.max_horizontal_m, g.forward_max_horizontal_m);
    EXPECT_LE(g.max_horizontal_m, 3.0 * g.std_horizontal_at_max_m + 0.05);
  }
  // 30 s free-inertial walking drifts 5-17 m forward; tied at both ends the error stays at a few decimetres.
  for (const auto* g : {&g30a.front(), &g30b.front()}) EXPECT_LE(g->max_horizontal_m, 0.25 * g->forward_max_horizontal_m);
}

// The IMU clock: the time_offset effect (IMU time error, estimated through the filter's own gains against the
// RTK positions) finds less than 30 ms with a sigma below 10 ms: -20.9 +- 1.9 ms since the tags are read as RTKLIB
// writes them (each ends its chunk), the stamps late by the delivery's least latency, which the lower envelope of
// the reception times cannot take out. (With the tag positions read in the wrong line-end
// convention the fitted rate was 2.05 % off: the time stamps would drift by 2.7 s over the walk and the filter
// loses lock, issue 3 note; issue 12 item 6 found the cause.)
TEST(Walk, ImuTimeBaseLeavesNoTimeOffset) {
  const WalkRun r = run_walk(walk().gnss, {"time_offset"});
  ASSERT_EQ(r.effects.size(), 13);  // kfgins21's 12 + the offset, last
  const double offset_s = r.effects(12), sigma_s = r.effects_std(12);
  std::printf("walk_0827: estimated IMU time offset %.1f ms +- %.1f ms\n", offset_s * 1e3, sigma_s * 1e3);
  EXPECT_LT(std::abs(offset_s), 0.030);
  EXPECT_LT(sigma_s, 0.010);
}

}  // namespace
}  // namespace ldv::est
