#pragma once
// The fusion service's logic without the bus, so it is tested (and replayed by `ldv nav --lcm-log`)
// exactly as it runs live. It drives the estimator's NavSession (estimator/run/nav_session.hpp), the same
// session `ldv nav` runs over files, so every configuration key (given start, start/end time, heading
// hypotheses, aids) means the same live and offline:
//  - alignment: IMU samples wait in a queue until a GNSS fix beyond their epoch has arrived (or
//    align_wait_s of host time passed), so the aligner sees IMU and GNSS in the same order as offline,
//    whatever the GNSS latency;
//  - navigation: late readings go to the NavFilter, which re-processes its IMU history, so a fix is
//    applied at its true epoch;
//  - GPS time: every reading's week + seconds of week is put on one continuous scale (seconds from the start
//    of the first week seen), so a week rollover is a step of one IMU interval, not a jump back by a week;
//    outputs are brought back to week + seconds of week;
//  - warm start: after a restart, a recent saved state (attitude, velocity) plus the first GNSS fix
//    restart navigation at once instead of waiting for a static period (NavSession::set_warm_start).
#include <ldv_lcm/wheel_speed_t.hpp>
#include <memory>
#include <vector>

#include "common/formats/kfgins_config.hpp"
#include "common/time/gps_time.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/nav_session.hpp"
#include "services/fusion/warm_start.hpp"

namespace ldv {

enum class FusionMode : int { kInitialising = 0, kAligning = 1, kAided = 2, kFreeInertial = 3 };

// The session a KF-GINS configuration describes, run live (the fusion service, `ldv nav --lcm-log`): as
// `ldv nav` runs it over files (est::session_options_from), and the IMU latency looked for over a sliding
// window (a live stream has no file to search first) unless the configuration rules it out
// (est::imu_latency_wanted). InputError (file, line) on a wrong ldv.imu_latency.
est::SessionOptions live_session_options(const KfGinsConfig& cfg, const est::FilterOptions& filter,
                                         const est::AlignmentOptions* alignment = nullptr);

struct FusionOutput {
  int gps_week = 0;
  double gps_sow_s = 0.0;  // the state's epoch on the GNSS time scale (NavFilter::gnss_time_s)
  est::NavState state;
  est::NavStd std;
  std::uint32_t status = 0;
  FusionMode mode = FusionMode::kInitialising;
};

class FusionEngine {
 public:
  explicit FusionEngine(const est::SessionOptions& session_options);
  FusionEngine(const FusionEngine&) = delete;  // the session drives this engine's filter
  FusionEngine& operator=(const FusionEngine&) = delete;

  // Optional: called with the filter itself after every navigated IMU sample, when it happens (a backlog
  // released at alignment gives many in one call; the FusionOutput vectors hold only the navigation state).
  void set_epoch_observer(est::NavSession::EpochSink observer) { epoch_observer_ = std::move(observer); }

  // Optional: resume from a saved state (used until the first GNSS fix arrives).
  void set_warm_start(const WarmState& saved) {
    run_->session.set_warm_start(saved.state, saved.std, saved.gyro_bias_rad_s);
  }
  // What set_warm_start takes: the filter's state now, with the gyro bias it takes out.
  WarmState warm_state(double host_time_s) const;

  // Appends the navigation outputs this sample produced (none while aligning). imu.t_s and fix.t_s are seconds
  // of the week gps_week.
  void on_imu(const ImuIncrement& imu, int gps_week, double arrival_s, std::vector<FusionOutput>& out);
  void on_gnss(const GnssFix& fix, int gps_week, double arrival_s);
  // Another sensor's reading (odometer from wheel_speed_t, ...).
  void on_observation(est::ObservationPtr reading, double arrival_s, std::vector<FusionOutput>& out);
  // Lets queued samples through when GNSS is silent (call periodically with the host time).
  void on_idle(double now_s, std::vector<FusionOutput>& out);
  // End of a replayed log: the alignment takes what is queued.
  void on_end(std::vector<FusionOutput>& out);

  // The odometer aid is on (FilterOptions::aids): wheel speeds (wheel_speed_t) are fed as odometer readings.
  bool wants_odometer() const;
  // A wheel_speed_t the input gate accepted, as an odometer reading (ignored without the odometer aid).
  void on_wheel_speed(const ldv_lcm::wheel_speed_t& m, double arrival_s, std::vector<FusionOutput>& out);

  // The input's time line went back (FusionInputGate::imu_jumps_back: a receiver corrected its week, the first
  // message was stamped ahead): a filter cannot go back in time, so the session starts again, warm from the state
  // it had when navigating, on a new continuous time scale.
  void restart_on_new_time_line(double host_time_s);

  // A filter epoch (seconds on the engine's continuous scale, as in InnovationRecord::t_s) as week + seconds.
  GpsTime week_time(double filter_t_s) const { return time_.week_time(filter_t_s); }

  bool navigating() const { return run_->session.navigating(); }
  const est::NavFilter& filter() const { return run_->filter; }
  est::NavFilter& filter() { return run_->filter; }
  const std::string& initialisation() const { return run_->session.initialisation(); }
  const est::NavSession& session() const { return run_->session; }

 private:
  // The filter and the session that drives it: one run on one time line (restart_on_new_time_line makes another).
  struct Run {
    Run(const est::SessionOptions& so, est::NavSession::EpochSink sink) : filter(so.filter), session(so, filter, std::move(sink)) {}
    est::NavFilter filter;
    est::NavSession session;
  };
  void on_epoch(const est::NavFilter& f, int reference_week);

  est::SessionOptions options_;
  ContinuousGpsTime time_;
  std::vector<FusionOutput>* out_ = nullptr;  // where the session's epochs go during a call
  est::NavSession::EpochSink epoch_observer_;
  std::unique_ptr<Run> run_;
};

}  // namespace ldv
