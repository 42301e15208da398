#include "estimator/run/nav_session.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>

#include "common/geo/earth_model.hpp"
#include "estimator/calibrate/imu_stamp_jitter.hpp"
#include "estimator/calibrate/installed_imu_noise.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/update/sensor_names.hpp"

namespace ldv::est {
namespace {

std::string fixed_text(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", v);
  return b;
}

template <typename Queue, typename T>
void insert_in_time_order(Queue& q, T item, double t_s) {
  // Readings arrive in time order from a receiver; a replayed or merged stream may not.
  auto it = std::upper_bound(q.begin(), q.end(), t_s, [](double t, const auto& x) {
    if constexpr (std::is_same_v<std::decay_t<decltype(x)>, GnssFix>)
      return t < x.t_s;
    else
      return t < x->t_s;
  });
  q.insert(it, std::move(item));
}

// The aligned state turned about the down axis by dyaw, the IMU moved so that the antenna stays where the fix
// put it (the alignment placed the IMU with the lever arm at the course heading; at a heading 180 deg from it a
// 0.5 m lever arm is 1 m off).
NavState turned_about_down(const NavState& aligned, double dyaw, const Vec3& lever_arm_b_m) {
  NavState s = aligned;
  s.q_b_n = (Quat(Eigen::AngleAxisd(dyaw, Vec3::UnitZ())) * aligned.q_b_n).normalized();
  s.pos = earth::offset_ned(aligned.pos, (aligned.C_b_n() - s.C_b_n()) * lever_arm_b_m);
  return s;
}

}  // namespace

bool NavSession::navigating() const { return filter_.initialized(); }

NavSession::NavSession(SessionOptions options, NavFilter& filter, EpochSink on_epoch)
    : o_(std::move(options)), on_epoch_(std::move(on_epoch)), filter_(filter), aligner_(o_.alignment) {
  if (o_.alignment.speed_min_mps > kSlowCourseSpeed_mps) slow_aligner_.emplace(slow_course_options());
  if (o_.imu_latency_window) latency_window_.emplace(*o_.imu_latency_window);
}

AlignmentOptions NavSession::slow_course_options() const {
  AlignmentOptions slow = o_.alignment;
  slow.speed_min_mps = kSlowCourseSpeed_mps;
  return slow;
}

void NavSession::set_warm_start(const NavState& saved, const NavStd& saved_std, const Vec3& saved_gyro_bias_rad_s) {
  warm_ = std::make_pair(saved, saved_std);
  warm_gyro_bias_rad_s_ = saved_gyro_bias_rad_s;
}

void NavSession::add_imu(const ImuIncrement& raw, int week, double arrival_s) {
  ImuIncrement imu = raw;
  if (latency_window_) {
    latency_window_->add_imu(raw);
    imu.t_s -= latency_window_->lag_s();
    if (std::isfinite(imu.t_s)) {  // a non-finite stamp is the filter's to reject, not a re-timing's
      if (imu.t_s <= latest_retimed_imu_t_s_) {
        ++imu_dropped_retimed_;
        return;
      }
      latest_retimed_imu_t_s_ = imu.t_s;
    }
  }
  latest_imu_seen_t_s_ = std::max(latest_imu_seen_t_s_, imu.t_s);
  latest_imu_arrival_s_ = arrival_s;
  if (imu.t_s < o_.start_time_s || imu.t_s > o_.end_time_s) {
    if (given_pending_)
      decide_late_given_start(arrival_s, false);
    else if (!navigating())
      drain_alignment_queue(arrival_s, false);
    return;
  }
  if (navigating()) {
    navigate(imu, week);
    return;
  }
  // A saved state (a restart seconds ago) is newer than a configuration's given one (the run's start): it goes
  // first, waiting for its fix; the given state is checked only once the saved one cannot be used.
  if (warm_) {
    if (try_warm_start(imu)) {
      navigate(imu, week);
      return;
    }
    if (warm_) {  // still waiting for the first fix
      imu_queue_.push_back({imu, week, arrival_s});
      drain_alignment_queue(arrival_s, false);
      return;
    }
  }
  if (o_.given_start && (given_pending_ || imu.t_s - o_.start_time_s > o_.given_start_max_gap_s)) {
    // The data start later than the given state holds: it still holds if the vehicle has not moved.
    given_pending_ = true;
    imu_queue_.push_back({imu, week, arrival_s});
    decide_late_given_start(arrival_s, false);
    return;
  }
  if (o_.given_start) {
    NavState s = o_.given_start->first;
    // The given state holds at the start of the first increment (KF-GINS: at starttime).
    s.t_s = std::max(o_.start_time_s, imu.t_s - imu.dt_s);
    start(s, o_.given_start->second, "given", std::nullopt, false);
    navigate(imu, week);
    return;
  }
  imu_queue_.push_back({imu, week, arrival_s});
  drain_alignment_queue(arrival_s, false);
}

void NavSession::add_gnss(const GnssFix& fix, double arrival_s) {
  if (latency_window_) latency_window_->add_gnss(fix);
  latest_gnss_t_s_ = std::max(latest_gnss_t_s_, fix.t_s);  // also while navigating: an alignment may be redone
  if (navigating()) {
    if (fix.t_s <= started_at_s_) return;  // before the initial epoch: not used, however late it arrives
    insert_in_time_order(gnss_queue_, fix, fix.t_s);
    hand_over_readings(filter_.state().t_s + kLookahead_s);
    return;
  }
  if (warm_ && !warm_fix_) warm_fix_ = fix;
  insert_in_time_order(gnss_queue_, fix, fix.t_s);
  (void)arrival_s;  // the queue waits on the IMU's arrival (drain_alignment_queue)
}

void NavSession::add_observation(ObservationPtr reading, double arrival_s) {
  (void)arrival_s;
  if (!reading) return;
  const double t = reading->t_s;
  if (navigating() && t <= started_at_s_) return;
  insert_in_time_order(other_queue_, std::move(reading), t);
  if (navigating()) hand_over_readings(filter_.state().t_s + kLookahead_s);
}

void NavSession::idle(double now_s) {
  if (given_pending_) decide_late_given_start(now_s, false);
  if (!navigating() && !given_pending_) drain_alignment_queue(now_s, false);
}

void NavSession::finish() {
  if (given_pending_) decide_late_given_start(1e300, true);
  if (!navigating()) drain_alignment_queue(1e300, true);
}

void NavSession::decide_late_given_start(double now_s, bool at_end) {
  // The GNSS decides: two consecutive fixes from the data's start on (up to 1 s before it), at walking pace
  // or less, the first within kGivenStillThere_m of the given position (plus 3 sigma of it): the vehicle is
  // where the given state left it, which then holds (attitude included: it has not moved). Else aligned.
  const double t0 = imu_queue_.front().imu.t_s;
  auto first = std::lower_bound(gnss_queue_.begin(), gnss_queue_.end(), t0 - 1.0,
                                [](const GnssFix& g, double t) { return g.t_s < t; });
  const bool two_fixes = first != gnss_queue_.end() && std::next(first) != gnss_queue_.end();
  const bool waited_long = now_s - imu_queue_.front().arrival_s > 3.0 * o_.align_wait_s;
  if (!two_fixes && !at_end && !waited_long) return;
  const auto& [given, given_std] = *o_.given_start;
  bool still_there = false;
  double distance_m = -1.0, speed_mps = -1.0;
  if (two_fixes) {
    const GnssFix& a = *first;
    const GnssFix& b = *std::next(first);
    distance_m = earth::ned_between(given.pos, a.pos).norm();
    speed_mps = b.t_s > a.t_s ? earth::ned_between(a.pos, b.pos).norm() / (b.t_s - a.t_s) : 1e9;
    still_there = given.v_n_mps.norm() < kSlowCourseSpeed_mps && speed_mps < kSlowCourseSpeed_mps &&
                  distance_m < kGivenStillThere_m + 3.0 * given_std.pos_ned_m.norm();
  }
  char b[240];
  std::snprintf(b, sizeof b,
                "the given state holds at %.3f s, the data start at %.3f s: the GNSS shows the vehicle %s (%.2f m "
                "from it, %.2f m/s): %s",
                o_.start_time_s, t0, still_there ? "still there" : "elsewhere or moving", distance_m, speed_mps,
                still_there ? "" : "aligned instead; ");
  given_note_ = b;
  given_pending_ = false;
  if (!still_there) {
    o_.given_start.reset();
    drain_alignment_queue(now_s, at_end);
    return;
  }
  NavState s = given;
  s.t_s = t0 - imu_queue_.front().imu.dt_s;
  start(s, given_std, "given", std::nullopt, false);
  release_backlog();
}

void NavSession::hand_over_readings(double up_to_s) {
  for (; !gnss_queue_.empty() && gnss_queue_.front().t_s <= up_to_s; gnss_queue_.pop_front()) {
    if (wants_pre_start_noise()) pre_start_gnss_.push_back(gnss_queue_.front());
    filter_.add_gnss(gnss_queue_.front());
    insert_in_time_order(fixes_to_check_, gnss_queue_.front(), gnss_queue_.front().t_s);
    ++gnss_used_;
  }
  for (; !other_queue_.empty() && other_queue_.front()->t_s <= up_to_s; other_queue_.pop_front()) {
    filter_.add_observation(other_queue_.front());
    ++others_used_;
  }
}

void NavSession::navigate(const ImuIncrement& imu, int week) {
  hand_over_readings(imu.t_s + kLookahead_s);
  for (; !fixes_to_check_.empty() && fixes_to_check_.front().t_s <= imu.t_s; fixes_to_check_.pop_front())
    heading_check_.add_fix(fixes_to_check_.front());
  filter_.add_imu(imu);
  ++imu_used_;
  measure_noise_while_navigating(imu);
  heading_check_.add_imu(filter_.state().q_b_n * imu.dvel_b_mps);
  if (on_epoch_) on_epoch_(filter_, week);
  if (!filter_.options().robust_update) return;
  // Failed: beyond the threshold and beyond 3 sigma of the filter's own heading (after a long outage it knows
  // its heading is poor, and the fixes will correct it).
  // And for heading_failed_for_s on end: one window's worth of odd data does not restart a filter.
  const std::optional<double> misfit = heading_check_.heading_misfit_rad();
  const bool failing =
      misfit && std::abs(*misfit) > std::max(o_.heading_failed_rad, 3.0 * filter_.nav_std().att_rad.z());
  if (!failing) {
    heading_failing_since_s_.reset();
    return;
  }
  if (!heading_failing_since_s_) heading_failing_since_s_ = imu.t_s;
  if (imu.t_s - *heading_failing_since_s_ >= o_.heading_failed_for_s) realign(*misfit);
}

void NavSession::realign(double misfit_rad) {
  const NavState lost = filter_.state();
  const NavStd lost_std = filter_.nav_std();
  heading_check_.clear();
  // Fixes already handed to the filter beyond this epoch go back to the queue, for the new alignment.
  for (const GnssFix& f : fixes_to_check_)
    if (f.t_s > lost.t_s) insert_in_time_order(gnss_queue_, f, f.t_s);
  fixes_to_check_.clear();
  heading_failing_since_s_.reset();
  warm_.reset();  // neither a given nor a saved state holds any more
  warm_fix_.reset();
  o_.given_start.reset();
  ++realignments_;
  filter_.restart();
  // Aligned again from here on: the level the filter held (tilt shows in every fix, unlike heading), the
  // course anew, with the axis-aligned body headings at least (the one taken before has just failed).
  o_.alignment.course_hypotheses = std::max(o_.alignment.course_hypotheses, 4);
  const Vec3 level_std(std::max(lost_std.att_rad.x(), 2.0 * kDegToRad), std::max(lost_std.att_rad.y(), 2.0 * kDegToRad),
                       0.0);
  const std::optional<Vec3> seed =
      gyro_bias_seed_rad_s_.isZero() ? std::nullopt : std::optional<Vec3>(gyro_bias_seed_rad_s_);
  aligner_ = Aligner(o_.alignment);
  aligner_.resume_levelled(lost.q_b_n, level_std, seed);
  slow_aligner_.reset();
  slow_result_.reset();
  slow_replay_imu_.clear();
  slow_replay_gnss_.clear();
  if (o_.alignment.speed_min_mps > kSlowCourseSpeed_mps) {
    slow_aligner_.emplace(slow_course_options());
    slow_aligner_->resume_levelled(lost.q_b_n, level_std, seed);
  }
  trial_.reset();
  char b[200];
  std::snprintf(b, sizeof b,
                "; at %.1f s the IMU's accelerations were turned %.0f deg against the GNSS track's: aligned again "
                "while moving: ",
                lost.t_s, misfit_rad * kRadToDeg);
  redo_note_ = initialisation_ + b;
}

void NavSession::drain_alignment_queue(double now_s, bool at_end) {
  while (!navigating()) {
    if (trial_) {
      if (!heading_trial_ready(now_s, at_end)) return;
      run_heading_trial(at_end);
      break;
    }
    if (imu_queue_.empty()) break;
    const QueuedImu head = imu_queue_.front();
    // The offline order: an IMU sample, then every fix up to its epoch. Wait until a fix beyond this
    // epoch has arrived, so none that belongs before it is still in flight.
    const bool gnss_beyond = latest_gnss_t_s_ > head.imu.t_s;
    if (!at_end && !gnss_beyond && now_s - head.arrival_s < o_.align_wait_s) return;
    imu_queue_.pop_front();
    const bool slow_running = slow_aligner_ && !slow_result_;
    aligner_.add_imu(head.imu);
    if (slow_running) slow_aligner_->add_imu(head.imu);
    keep_pre_start(head.imu);
    for (; !gnss_queue_.empty() && gnss_queue_.front().t_s <= head.imu.t_s; gnss_queue_.pop_front()) {
      if (wants_pre_start_noise()) pre_start_gnss_.push_back(gnss_queue_.front());
      aligner_.add_gnss(gnss_queue_.front());
      if (slow_running) slow_aligner_->add_gnss(gnss_queue_.front());
      if (slow_result_) slow_replay_gnss_.push_back(gnss_queue_.front());
    }
    if (slow_result_) slow_replay_imu_.push_back(head);
    if (aligner_.aligned()) {
      slow_aligner_.reset();
      slow_result_.reset();
      slow_replay_imu_.clear();
      slow_replay_gnss_.clear();
      aligned({aligner_.state(), aligner_.std(), aligner_.method(), aligner_.gyro_bias_seed().value_or(Vec3::Zero()),
               aligner_.gyro_bias_seed_std()});
      continue;
    }
    if (slow_running && slow_aligner_->aligned())
      slow_result_ =
          Alignment{slow_aligner_->state(), slow_aligner_->std(),
                    slow_aligner_->method() + " (the GNSS never reached " + fixed_text(o_.alignment.speed_min_mps) +
                        " m/s: course from " + fixed_text(kSlowCourseSpeed_mps) + " m/s)",
                    slow_aligner_->gyro_bias_seed().value_or(Vec3::Zero()), slow_aligner_->gyro_bias_seed_std()};
    if (slow_result_ && head.imu.t_s - slow_result_->state.t_s > o_.slow_course_grace_s) take_slow_course_alignment();
  }
  if (at_end && !navigating() && slow_result_) take_slow_course_alignment();
  if (at_end && !navigating() && trial_) run_heading_trial(true);
  if (navigating()) release_backlog();
}

void NavSession::take_slow_course_alignment() {
  Alignment al = *slow_result_;
  slow_result_.reset();
  slow_aligner_.reset();
  // The samples and fixes the configured-speed aligner took since go back to the front of the queues.
  for (auto it = slow_replay_imu_.rbegin(); it != slow_replay_imu_.rend(); ++it) imu_queue_.push_front(*it);
  gnss_queue_.insert(gnss_queue_.begin(), slow_replay_gnss_.begin(), slow_replay_gnss_.end());
  slow_replay_imu_.clear();
  slow_replay_gnss_.clear();
  aligned(std::move(al));
}

bool NavSession::wants_pre_start_noise() const {
  return !o_.imu_noise_floor && !noise_measured_ && filter_.options().adapt_imu_noise &&
         filter_.options().installed_noise_floor;
}

void NavSession::keep_pre_start(const ImuIncrement& imu) {
  if (!wants_pre_start_noise()) return;
  pre_start_imu_.push_back(imu);
  while (pre_start_imu_.front().t_s < imu.t_s - kPreStartKept_s) pre_start_imu_.pop_front();
  const auto old = std::find_if(pre_start_gnss_.begin(), pre_start_gnss_.end(),
                                [&](const GnssFix& f) { return f.t_s >= pre_start_imu_.front().t_s; });
  pre_start_gnss_.erase(pre_start_gnss_.begin(), old);
}

void NavSession::measure_noise_before_start() {
  if (!wants_pre_start_noise()) return;
  noise_measured_ = true;
  const std::vector<ImuIncrement> imu(pre_start_imu_.begin(), pre_start_imu_.end());
  pre_start_imu_.clear();
  // A live session's tags, as run_navigation measures a file's: from the samples before the start.
  std::string jitter_note;
  if (filter_.options().imu_stamp_jitter_from_tags && filter_.options().imu_stamp_jitter_s == 0.0) {
    const ImuStampJitter jitter = measure_imu_stamp_jitter(imu);
    if (jitter.found) filter_.set_imu_stamp_jitter(jitter.sigma_s);
    if (jitter.noticeable()) {
      char b[160];
      std::snprintf(b, sizeof b, "; IMU tags %.2f ms off the sensor's %.1f Hz sampling: modelled", 1e3 * jitter.sigma_s,
                    1.0 / jitter.sample_interval_s);
      jitter_note = b;
    }
  }
  noise_note_ = jitter_note;
  const InstalledImuNoise noise = measure_installed_imu_noise(imu, pre_start_gnss_);
  pre_start_gnss_.clear();
  if (!noise.found) return;
  noise_standstill_s_ = noise.standstill_s;
  const bool filled = filter_.fill_unset_white_noise(noise.arw_rad_per_sqrt_s, noise.vrw_mps_per_sqrt_s);
  o_.imu_noise_floor = noise.psd_scale(filter_.options().arw_rad_per_sqrt_s, filter_.options().vrw_mps_per_sqrt_s);
  o_.standstill_f_scatter_mps2 = noise.f_norm_scatter_mps2;
  char b[200];
  std::snprintf(b, sizeof b,
                "; IMU noise as installed over the %.0f s standstill before the start: gyro %.3gx, accel %.3gx the "
                "configured PSD%s",
                noise.standstill_s, o_.imu_noise_floor->gyro, o_.imu_noise_floor->accel,
                filled ? " (a white noise configured as 0 took the standstill's)" : "");
  noise_note_ = b + jitter_note;
}

// A start that needed no standstill (a given or saved state) measures the IMU noise as installed over the first
// standstill while navigating (issue 46: `ldv nav --lcm-log` of a drive starting with 60 s standing still said
// "no standstill in the data"): once the vehicle moves off after one, or once the kept span is full.
void NavSession::measure_noise_while_navigating(const ImuIncrement& imu) {
  if (!wants_pre_start_noise()) return;
  keep_pre_start(imu);
  const bool still = (filter_.status() & kStatusZuptActive) != 0;
  if (still && !still_since_s_) still_since_s_ = imu.t_s;
  const bool moved_off = !still && still_since_s_ && imu.t_s - *still_since_s_ >= kMinNoiseStandstill_s;
  if (!still) still_since_s_.reset();
  if (!moved_off && imu.t_s - pre_start_imu_.front().t_s < kPreStartKept_s - 1.0) return;
  measure_noise_before_start();
  if (o_.imu_noise_floor && filter_.options().adapt_imu_noise) {
    filter_.set_imu_noise_floor(*o_.imu_noise_floor);
    filter_.set_standstill_f_scatter(o_.standstill_f_scatter_mps2);
    imu_noise_floor_ = filter_.imu_noise_floor();
  }
  initialisation_ += noise_note_;
  noise_note_.clear();
}

void NavSession::aligned(Alignment al) {
  measure_noise_before_start();
  const Vec3& seed = al.gyro_bias_seed;
  if (!seed.isZero()) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "; gyro turn-on bias from the static start [%.4f %.4f %.4f] deg/s taken out",
                  seed.x() * kRadToDeg, seed.y() * kRadToDeg, seed.z() * kRadToDeg);
    al.method += buf;
  }
  if (o_.alignment.course_hypotheses > 1 && al.method.find("course") != std::string::npos) {
    trial_ = std::move(al);  // unknown mounting: wait for course_trial_s of data to try the body headings on
    trial_window_s_ = o_.alignment.course_trial_s;
    return;
  }
  gyro_bias_seed_std_rad_s_ = al.gyro_bias_seed_std;
  start(al.state, al.std, al.method, al.gyro_bias_seed, true);
}

bool NavSession::heading_trial_ready(double now_s, bool at_end) const {
  if (at_end) return true;
  // Every IMU sample of the trial window is in once a later one came; every fix it uses (up to kLookahead_s
  // beyond its last sample) once a fix beyond that came, or the wait for GNSS is over.
  const double t_window_end = std::min(o_.end_time_s, trial_->state.t_s + trial_window_s_);
  if (latest_imu_seen_t_s_ <= t_window_end) return false;
  return latest_gnss_t_s_ > t_window_end + kLookahead_s || now_s - latest_imu_arrival_s_ >= o_.align_wait_s;
}

void NavSession::run_heading_trial(bool at_end) {
  Alignment al = std::move(*trial_);
  trial_.reset();
  // Unknown mounting: which body heading matches the GNSS track over the trial window?
  const int n = o_.alignment.course_hypotheses;
  const double step = 2.0 * kPi / n;
  const double t_window_end = std::min(o_.end_time_s, al.state.t_s + trial_window_s_);
  double best_dyaw = 0.0;
  // First by the accelerations: the IMU's velocity changes (the aligned attitude carried by the gyros alone)
  // against the GNSS track's over the window give the heading error directly (heading_check.hpp); the
  // hypothesis nearest to it is taken. The innovations of a filter per hypothesis decide only when the window
  // has too little acceleration for that. Only over the first course_trial_s: carried by a MEMS gyro alone for a
  // minute (a turn-on bias known to 0.2 deg/s from a vibrating start), the attitude tilts by degrees, gravity
  // leaks into the horizontal, and the accelerations of a later U-turn read the heading 50-140 deg off.
  const double t_gyro_only_end = std::min(t_window_end, al.state.t_s + o_.alignment.course_trial_s);
  const std::optional<double> misfit = window_heading_misfit(al, t_gyro_only_end);
  if (misfit) {
    const double k = std::remainder(-*misfit, 2.0 * kPi) / step;
    best_dyaw = std::remainder(std::lround(k) * step, 2.0 * kPi);
    if (best_dyaw < 0) best_dyaw += 2.0 * kPi;
  }
  std::vector<double> cost_of(misfit ? 0 : n, 0.0);
  for (int k = 0; k < n && !misfit; ++k) {
    const double dyaw = k * step;
    // Without the in-flight noise adaptation (held at the installed noise): adapted, a wrong heading follows
    // the fixes too (the trial's NIS would barely tell them apart).
    FilterOptions trial_options = filter_.options();
    trial_options.adapt_imu_noise = false;
    // The GNSS-side effects held at their prior means: estimated with a wide prior (a diagnosis's candidate
    // lever arm: 0.6 m), they move the predicted fix to follow a wrong heading's misfit, and the trial chose
    // headings 90-135 deg off.
    for (const char* held : {"lever_arm", "time_offset", "gnss_position_bias"}) trial_options.drop.emplace_back(held);
    NavFilter trial(trial_options);
    const NavState s = turned_about_down(al.state, dyaw, trial_options.lever_arm.init);
    NavStd sd = al.std;
    sd.att_rad.z() = std::max(al.std.att_rad.z(), 0.5 * step);
    trial.initialize(s, sd);
    trial.set_input_gyro_bias(al.gyro_bias_seed);
    if (o_.imu_noise_floor) trial.set_imu_noise_floor(*o_.imu_noise_floor);
    auto fix = std::upper_bound(gnss_queue_.begin(), gnss_queue_.end(), s.t_s,
                                [](double t, const GnssFix& g) { return t < g.t_s; });
    for (const QueuedImu& q : imu_queue_) {
      if (q.imu.t_s > t_window_end) break;
      for (; fix != gnss_queue_.end() && fix->t_s <= q.imu.t_s + kLookahead_s; ++fix) trial.add_gnss(*fix);
      trial.add_imu(q.imu);
      // Each fix adds at most the gate: one GNSS outlier (a 1 m jump, NIS 1000s under the right heading) must
      // not outweigh a wrong heading's steady misfit.
      for (const auto& r : trial.take_innovations())
        if (r.sensor == sensors::kGnssPosition)
          cost_of[k] += std::min(r.nis, trial.gate_threshold(r.innovation.size()));
    }
  }
  if (!misfit) {
    const int best = static_cast<int>(std::min_element(cost_of.begin(), cost_of.end()) - cost_of.begin());
    best_dyaw = best * step;
    // Decided when every heading beyond the best one's neighbours costs kTrialMargin more; a window without
    // enough acceleration (a straight at constant speed) leaves them level and picks one at random. Then the
    // window grows, up to course_trial_max_s: the start is the same epoch, so no output is lost, only delayed.
    bool decided = true;
    for (int k = 0; k < n; ++k) {
      const int apart = std::min((k - best + n) % n, (best - k + n) % n);
      if (apart > 1 && cost_of[k] - cost_of[best] < kTrialMargin) decided = false;
    }
    const bool more_data = !at_end && t_window_end < o_.end_time_s;
    if (!decided && more_data && trial_window_s_ < o_.alignment.course_trial_max_s) {
      trial_window_s_ = std::min(2.0 * trial_window_s_, o_.alignment.course_trial_max_s);
      trial_ = std::move(al);
      return;
    }
  }
  body_heading_ = BodyHeading{std::remainder(best_dyaw, 2.0 * kPi), step, n, misfit.has_value()};
  al.state = turned_about_down(al.state, best_dyaw, filter_.options().lever_arm.init);
  al.std.att_rad.z() = std::max(al.std.att_rad.z(), 0.5 * step);
  al.method += " (best of " + std::to_string(n) + " body headings" + (misfit ? " by the accelerations" : "") +
               " over " + fixed_text(trial_window_s_) + " s: x axis " +
               std::to_string(static_cast<int>(std::lround(best_dyaw * kRadToDeg))) + " deg from the course)";
  gyro_bias_seed_std_rad_s_ = al.gyro_bias_seed_std;
  start(al.state, al.std, al.method, al.gyro_bias_seed, true);
}

std::optional<double> NavSession::window_heading_misfit(const Alignment& al, double t_window_end) const {
  HeadingCheck check(o_.alignment.course_trial_s + 1.0);
  Quat q_b_n = al.state.q_b_n;
  auto fix = std::upper_bound(gnss_queue_.begin(), gnss_queue_.end(), al.state.t_s,
                              [](double t, const GnssFix& g) { return t < g.t_s; });
  for (const QueuedImu& q : imu_queue_) {
    if (q.imu.t_s > t_window_end) break;
    if (q.imu.t_s <= al.state.t_s) continue;
    for (; fix != gnss_queue_.end() && fix->t_s <= q.imu.t_s; ++fix) check.add_fix(*fix);
    q_b_n = (q_b_n * quat_from_rotvec(q.imu.dtheta_b_rad - al.gyro_bias_seed * q.imu.dt_s)).normalized();
    check.add_imu(q_b_n * q.imu.dvel_b_mps);
  }
  return check.heading_misfit_rad();
}

bool NavSession::try_warm_start(const ImuIncrement& imu) {
  if (!warm_fix_) return false;
  const GnssFix fix = *warm_fix_;
  const auto [saved, saved_std] = *warm_;
  warm_.reset();
  if (imu.t_s < fix.t_s || imu.t_s - fix.t_s > 1.0) return false;
  NavState s = saved;
  s.t_s = imu.t_s - imu.dt_s;
  const Vec3 v_n = fix.has_velocity ? fix.vel_n_mps : saved.v_n_mps;
  const Vec3& v_saved = saved.v_n_mps;
  const double speed_min = o_.alignment.speed_min_mps;
  const bool course_turned =
      fix.has_velocity && v_n.head<2>().norm() > speed_min && v_saved.head<2>().norm() > speed_min;
  if (course_turned) {
    const double turn = std::remainder(std::atan2(v_n.y(), v_n.x()) - std::atan2(v_saved.y(), v_saved.x()), 2.0 * kPi);
    s.q_b_n = (Quat(Eigen::AngleAxisd(turn, Vec3::UnitZ())) * s.q_b_n).normalized();
  }
  // Antenna fix -> IMU centre, then carried to the start of this sample with the velocity.
  const Vec3 lever_n = s.C_b_n() * filter_.options().lever_arm.init;
  const double taken_at_s = fix.t_s - filter_.options().time_offset_init_s;  // on the IMU's clock
  s.pos = earth::offset_ned(fix.pos, -lever_n + v_n * (s.t_s - taken_at_s));
  s.v_n_mps = v_n;
  NavStd sd;
  sd.pos_ned_m = 2.0 * fix.pos_std_ned_m + Vec3::Constant(0.05);
  sd.vel_n_mps = fix.has_velocity ? Vec3(2.0 * fix.vel_std_n_mps + Vec3::Constant(0.05)) : Vec3::Constant(2.0);
  // Attitude kept through a restart gap of a few seconds: heading may have turned meanwhile. Moving
  // then and now: the saved attitude turned by the change of the course over ground.
  sd.att_rad = saved_std.att_rad + Vec3(0.5, 0.5, 5.0) * kDegToRad;
  if (course_turned) sd.att_rad.z() = saved_std.att_rad.z() + o_.alignment.cog_yaw_std_rad;
  const Vec3& bias = warm_gyro_bias_rad_s_;
  start(s, sd, "warm start", bias.isZero() ? std::nullopt : std::optional<Vec3>(bias), true);
  return true;
}

void NavSession::start(const NavState& s, const NavStd& sd, const std::string& how,
                       const std::optional<Vec3>& gyro_bias_seed, bool position_from_fix) {
  filter_.initialize(s, sd);
  if (position_from_fix) filter_.couple_start_to_gnss_effects();
  // A turn-on bias the alignment's static start showed (or a warm start's saved gyro bias) is taken out of every
  // increment.
  if (gyro_bias_seed) {
    filter_.set_input_gyro_bias(*gyro_bias_seed);
    gyro_bias_seed_rad_s_ = *gyro_bias_seed;
  }
  if (o_.imu_noise_floor && filter_.options().adapt_imu_noise) {
    filter_.set_imu_noise_floor(*o_.imu_noise_floor);
    filter_.set_standstill_f_scatter(o_.standstill_f_scatter_mps2);
  }
  initialisation_ = (redo_note_.empty() ? given_note_ + how : redo_note_ + how) + noise_note_;
  noise_note_.clear();  // said once: a redo's note starts with this one
  started_at_s_ = s.t_s;
  imu_noise_floor_ = filter_.imu_noise_floor();
  // Readings up to the initial epoch are not used.
  while (!gnss_queue_.empty() && gnss_queue_.front().t_s <= s.t_s) gnss_queue_.pop_front();
  while (!other_queue_.empty() && other_queue_.front()->t_s <= s.t_s) other_queue_.pop_front();
}

void NavSession::release_backlog() {
  std::deque<QueuedImu> rest;
  rest.swap(imu_queue_);
  while (!rest.empty()) {
    if (!navigating()) {  // the heading failed on the way (realign): the rest goes to the new alignment
      imu_queue_.insert(imu_queue_.begin(), rest.begin(), rest.end());
      drain_alignment_queue(rest.back().arrival_s, false);
      return;
    }
    navigate(rest.front().imu, rest.front().week);
    rest.pop_front();
  }
}

}  // namespace ldv::est
