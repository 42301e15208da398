#include "toolbox/assess/outage_run.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <mutex>
#include <thread>

#include "common/io/input_error.hpp"
#include "common/parallel/parallel_for.hpp"
#include "estimator/run/alignment_options_from.hpp"
#include "estimator/run/run_navigation.hpp"
#include "toolbox/assess/filter_checkpoint.hpp"
#include "toolbox/assess/solution_comparison.hpp"

namespace ldv::assess {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kEpochTolerance_s = 1e-9;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Follows one outage segment epoch by epoch and measures its drift against the reference.
class DriftTracker {
 public:
  DriftTracker(const OutageWindow& w, const NavSeries& reference, const OutageRunOptions& o)
      : ref_(reference), o_(o) {
    r_.window = w;
  }

  void observe(const est::NavFilter& f) {
    last_ = f.state();
    reference_t_s_ = o_.reference_on_gps_time ? f.gnss_time_s() : last_.t_s;
    if (last_.t_s + kEpochTolerance_s < next_eval_s_) return;
    last_std_ = f.nav_std();
    evaluate();
    next_eval_s_ = last_.t_s + o_.eval_period_s;
  }

  OutageResult finish(const est::NavFilter& f) {
    last_ = f.state();
    reference_t_s_ = o_.reference_on_gps_time ? f.gnss_time_s() : last_.t_s;
    last_std_ = f.nav_std();
    if (const auto d = evaluate()) {
      r_.end_drift = *d;
      r_.end_std = last_std_;
      r_.end_measured = true;
    }
    r_.t_end_s = last_.t_s;
    return std::move(r_);
  }

 private:
  std::optional<NavDifference> evaluate() {
    const auto ref = ref_.at(reference_t_s_);
    if (!ref) return std::nullopt;
    const NavDifference d = nav_difference(sample_of(last_), *ref);
    const auto c = table_components(d);
    for (int i = 0; i < kComponents; ++i) r_.max_abs[i] = std::max(r_.max_abs[i], std::abs(c[i]));
    r_.max_horizontal_m = std::max(r_.max_horizontal_m, d.pos_ned_m.head<2>().norm());
    const double since = last_.t_s - r_.window.start_s;
    if (since + kEpochTolerance_s >= next_curve_s_) {
      r_.curve.push_back({since, d.pos_ned_m, last_std_.pos_ned_m, c[8]});
      next_curve_s_ = since + o_.curve_period_s;
    }
    return d;
  }

  const NavSeries& ref_;
  const OutageRunOptions& o_;
  OutageResult r_;
  est::NavState last_;
  double reference_t_s_ = 0.0;  // last_'s epoch on the reference's clock
  est::NavStd last_std_;
  double next_eval_s_ = -1e300, next_curve_s_ = 0.0;
};

}  // namespace

OutageResult run_outage_segment(const FilterCheckpoint& cp, const OutageWindow& w, const std::vector<ImuIncrement>& imu,
                                const NavSeries& reference, const OutageRunOptions& o) {
  est::NavFilter f = restore_filter(cp);
  DriftTracker tracker(w, reference, o);
  const double t_stop = w.start_s + w.length_s + kEpochTolerance_s;
  // An IMU epoch just after the start (fixes off the IMU grid) belongs to the outage, as in a re-run: it sets
  // the 10 Hz evaluation grid.
  if (f.state().t_s > w.start_s) tracker.observe(f);
  auto it = std::upper_bound(imu.begin(), imu.end(), f.state().t_s + kEpochTolerance_s,
                             [](double t, const ImuIncrement& s) { return t < s.t_s; });
  // Other sensors' readings go on, handed over as run_navigation does (0.5 s ahead of the IMU): the copy
  // already holds those up to its epoch + 0.5 s.
  auto other = std::upper_bound(o.others.begin(), o.others.end(), f.state().t_s + 0.5,
                                [](double t, const est::ObservationPtr& p) { return t < p->t_s; });
  for (; it != imu.end() && it->t_s <= t_stop; ++it) {
    for (; other != o.others.end() && (*other)->t_s <= it->t_s + 0.5; ++other) f.add_observation(*other);
    f.add_imu(*it);
    tracker.observe(f);
  }
  return tracker.finish(f);
}

namespace {

// The reference for the checkpoint: the whole run again with this outage's fixes removed.
OutageResult rerun_with_outage(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                               const KfGinsConfig& cfg, const est::FilterOptions& fo, const OutageWindow& w,
                               const NavSeries& reference, const OutageRunOptions& o) {
  std::vector<GnssFix> cut;
  const double t_stop = w.start_s + w.length_s;
  for (const GnssFix& g : gnss)
    if (g.t_s <= w.start_s || g.t_s > t_stop) cut.push_back(g);
  KfGinsConfig c = cfg;
  c.end_time_s = t_stop + kEpochTolerance_s;
  est::NavFilter f(fo);
  DriftTracker tracker(w, reference, o);
  est::RunCallbacks cb;
  cb.on_epoch = [&](const est::NavFilter& nf) {
    if (nf.state().t_s > w.start_s) tracker.observe(nf);
  };
  est::run_navigation(imu, cut, c, f, cb, nullptr, &o.others);
  return tracker.finish(f);
}

// Per outage length, one smoothed run with all of that length's gaps cut (they do not overlap: recovery_s
// apart); lengths in parallel.
void smooth_outages(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss, const KfGinsConfig& cfg,
                    const est::FilterOptions& fo, const std::vector<OutageWindow>& plan, const NavSeries& reference,
                    const OutageRunOptions& o, std::vector<OutageResult>& results) {
  std::map<double, std::vector<size_t>> by_length;
  for (size_t i = 0; i < plan.size(); ++i) by_length[plan[i].length_s].push_back(i);
  std::vector<const std::vector<size_t>*> groups;
  for (const auto& [length, idx] : by_length) groups.push_back(&idx);
  std::vector<size_t> order(groups.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::mutex say_mutex;
  parallel_for(order, o.threads, [&](size_t g) {
    std::vector<OutageWindow> windows;
    for (size_t i : *groups[g]) windows.push_back(plan[i]);
    const std::vector<SmoothedGap> s =
        smooth_through_gaps(imu, gnss, cfg, fo, windows, reference, o.others, o.eval_period_s, o.reference_on_gps_time);
    for (size_t k = 0; k < s.size(); ++k) results[(*groups[g])[k]].smoothed = s[k];
    if (o.progress) {
      std::lock_guard<std::mutex> lock(say_mutex);
      o.progress("outage: smoothed the " + std::to_string(windows.size()) + " gaps of " +
                 std::to_string(static_cast<int>(windows.front().length_s)) + " s");
    }
  });
}

}  // namespace

OutageRun run_outages(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss, const KfGinsConfig& cfg,
                      const est::FilterOptions& fo, const NavSeries& truth, const OutageRunOptions& options) {
  OutageRunOptions o = options;
  o.reference_on_gps_time = !truth.empty();
  auto say = [&](const std::string& s) {
    if (o.progress) o.progress(s);
  };
  if (imu.empty() || gnss.empty()) throw std::invalid_argument("outage: no IMU or no GNSS data");
  OutageRun run;
  run.reference = truth.empty() ? "uncut solution" : "truth";
  run.threads = o.threads;  // the threads that worked are counted by parallel_for
  double t_data_end = cfg.end_time_s > 0 ? std::min(cfg.end_time_s, imu.back().t_s) : imu.back().t_s;
  // Convergence counts from the filter's start (a run that aligns while moving starts late).
  const double t_init = est::initialisation_epoch(imu, gnss, cfg, est::alignment_options_from(fo));
  // Against truth, outages lie where the truth is (issue 46: a truth that ended before them gave 0.000 m).
  const double t_truth_start = truth.empty() ? -1e300 : truth.t_begin_s(),
               t_truth_end = truth.empty() ? 1e300 : truth.t_end_s();
  t_data_end = std::min(t_data_end, t_truth_end);
  std::vector<GnssFix> after_init;
  for (const GnssFix& f : gnss)
    if (f.t_s >= t_init) after_init.push_back(f);
  if (after_init.empty()) throw std::invalid_argument("outage: no GNSS after the filter's initialisation");
  // The convergence before an outage needs GNSS before it, so fixes before the truth still count; only the
  // outage's start is held within the truth.
  if (!truth.empty() && (t_truth_end <= after_init.front().t_s || t_truth_start >= t_data_end)) {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "outage: the truth (%.3f to %.3f s) does not overlap the run's GNSS (%.3f to %.3f s): no outage "
                  "can be measured against it",
                  t_truth_start, t_truth_end, after_init.front().t_s, after_init.back().t_s);
    throw std::invalid_argument(buf);
  }
  std::vector<OutageWindow> plan = plan_outages(after_init, o.lengths_s, t_data_end, o.plan);
  std::erase_if(plan, [&](const OutageWindow& w) { return w.start_s < t_truth_start; });
  if (plan.empty()) {
    char buf[480];
    std::snprintf(
        buf, sizeof buf,
        "outage: no outage fits: %.0f s of GNSS after the initialisation, outages start %.0f s later (--converge) when "
        "faster than %.1f m/s (--min-speed), %.0f s apart (--recovery), and end where the data's GNSS is back%s; "
        "lower these for a short or slow run",
        after_init.back().t_s - after_init.front().t_s, o.plan.converge_s, o.plan.min_speed_mps, o.plan.recovery_s,
        truth.empty()
            ? ""
            : (", within the truth (" + std::to_string(t_truth_start) + " to " + std::to_string(t_truth_end) + " s)")
                  .c_str());
    throw std::invalid_argument(buf);
  }
  {
    char buf[160];
    std::snprintf(buf, sizeof buf, "outage: %zu outages planned, drift against the %s", plan.size(), run.reference.c_str());
    say(buf);
  }

  // 1. The uncut run: its solution (reference without truth) and a checkpoint at each outage start.
  std::vector<double> starts;
  for (const OutageWindow& w : plan) starts.push_back(w.start_s);
  starts.erase(std::unique(starts.begin(), starts.end()), starts.end());
  std::vector<FilterCheckpoint> checkpoints;
  std::vector<NavSample> uncut;
  uncut.reserve(imu.size());
  const auto t0 = Clock::now();
  est::NavFilter uncut_filter(fo);
  est::RunCallbacks cb;
  cb.on_epoch = [&](const est::NavFilter& f) {
    uncut.push_back(sample_of(f.state()));
    // The fix at the start epoch has been applied once the IMU has reached it; the ones after it that the
    // run has already queued are the outage's.
    while (checkpoints.size() < starts.size() && f.state().t_s + kEpochTolerance_s >= starts[checkpoints.size()])
      checkpoints.push_back(capture_checkpoint(f, starts[checkpoints.size()]));
  };
  int last_percent = -10;
  cb.on_progress = [&](double done) {
    if (done * 100 >= last_percent + 10) {
      last_percent = static_cast<int>(done * 100) / 10 * 10;
      say("outage: uncut run " + std::to_string(last_percent) + " %");
    }
  };
  const est::RunSummary summary = est::run_navigation(imu, gnss, cfg, uncut_filter, cb, nullptr, &o.others);
  run.imu_samples = summary.imu_samples;
  run.uncut_run_s = seconds_since(t0);
  const NavSeries uncut_series(std::move(uncut));
  const NavSeries& reference = truth.empty() ? uncut_series : truth;

  // 2. The outages, longest first so the cores stay busy to the end.
  std::vector<size_t> order(plan.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return plan[a].length_s > plan[b].length_s; });
  std::vector<OutageResult> results(plan.size());
  std::atomic<int> done{0};
  std::mutex say_mutex;
  const auto t1 = Clock::now();
  run.threads = parallel_for(order, run.threads, [&](size_t i) {
    const OutageWindow& w = plan[i];
    const size_t c = static_cast<size_t>(std::lower_bound(starts.begin(), starts.end(), w.start_s) - starts.begin());
    if (o.exact_rerun)
      results[i] = rerun_with_outage(imu, gnss, cfg, fo, w, reference, o);
    else if (c < checkpoints.size())
      results[i] = run_outage_segment(checkpoints[c], w, imu, reference, o);
    else
      results[i].window = w;  // the filter never reached the start (cannot happen with a sane plan)
    if (!truth.empty()) {
      const auto u = uncut_series.at(results[i].t_end_s), t = truth.at(results[i].t_end_s);
      if (u && t) results[i].uncut_error = nav_difference(*u, *t);
    }
    char buf[160];
    std::snprintf(buf, sizeof buf, "outage: %d/%zu done (%.0f s from %.1f: %.2f m horizontal)", ++done, plan.size(),
                  w.length_s, w.start_s, results[i].end_drift.pos_ned_m.head<2>().norm());
    std::lock_guard<std::mutex> lock(say_mutex);
    say(buf);
  });
  run.outages_run_s = seconds_since(t1);
  if (o.smooth) smooth_outages(imu, gnss, cfg, fo, plan, reference, o, results);
  std::stable_sort(results.begin(), results.end(), [](const OutageResult& a, const OutageResult& b) {
    return a.window.length_s != b.window.length_s ? a.window.length_s < b.window.length_s : a.window.start_s < b.window.start_s;
  });
  // No result on no data: an outage whose end the reference does not reach is named, not reported as 0 m.
  for (const OutageResult& r : results)
    if (!r.end_measured) run.unmeasured.push_back(r.window);
  std::erase_if(results, [](const OutageResult& r) { return !r.end_measured; });
  if (results.empty())
    throw std::invalid_argument("outage: the " + run.reference + " has no sample at the end of any planned outage");
  run.outages = std::move(results);
  return run;
}

}  // namespace ldv::assess
