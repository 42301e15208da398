#pragma once
// One navigation session: what drives a NavFilter from a stream of sensor readings. `ldv nav` over files
// (run_navigation.hpp), `ldv nav --lcm-log` and the live fusion service all push their readings through it,
// so every configuration key means the same in all three:
//  - start: a given state (KF-GINS initpos/initvel/initatt) at the first IMU sample at or after the start
//    time; a warm start (a service's saved attitude and velocity plus the first GNSS fix); or the
//    alignment from the data (alignment.hpp), with the slow-course fallback for a vehicle (or walker) that
//    never reaches the configured speed, and the body-heading hypotheses for an unknown mounting;
//  - the time window [start_time_s, end_time_s];
//  - the feeding policy: a reading (GNSS fix, odometer, ...) is handed to the filter when the IMU comes
//    within kLookahead_s of its epoch, or at once when the IMU has passed that point already (a live
//    reading arriving late: the filter rewinds and applies it at its epoch).
// Before the start, IMU samples wait in a queue until a GNSS fix beyond their epoch has arrived (or
// align_wait_s of arrival time passed), so the aligner sees IMU and GNSS in the same order offline and live,
// whatever the GNSS latency. Arrival times are the caller's clock: the data time offline, the host time live.
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "estimator/calibrate/imu_latency_window.hpp"
#include "estimator/filter/imu_noise_scale.hpp"
#include "estimator/ins/alignment.hpp"
#include "estimator/ins/nav_state.hpp"
#include "estimator/options.hpp"
#include "estimator/run/heading_check.hpp"
#include "estimator/update/observation.hpp"

namespace ldv::est {

class NavFilter;  // nav_filter.hpp: the session drives one it is given (a declaration keeps the includers of
                  // this header from recompiling with every change of the filter)

struct SessionOptions {
  FilterOptions filter;
  AlignmentOptions alignment;
  // A given start (its t_s is set by the session); else the data are aligned. It holds at start_time_s: when
  // the first IMU sample comes more than given_start_max_gap_s later (a live stream joined late, a log cut
  // at the PPS lock), it still holds if the GNSS shows the vehicle at rest where it was given; else the data
  // are aligned instead. initialisation() says which.
  std::optional<std::pair<NavState, NavStd>> given_start;
  double given_start_max_gap_s = 1.0;
  double start_time_s = -1e300, end_time_s = 1e300;  // IMU samples outside are not used
  // Arrival-clock seconds a queued IMU sample waits for GNSS beyond its epoch before the aligner takes it.
  double align_wait_s = 1.0;
  // The slow-course fallback is used when the configured speed is not reached within this much data time
  // after the fallback aligned (offline, before this session: only when it was never reached in the file).
  double slow_course_grace_s = 60.0;
  // The IMU noise as installed, the floor of the filter's noise adaptation (FilterOptions::adapt_imu_noise):
  // e.g. measured over a standstill (installed_imu_noise.hpp); `ldv nav` measures it over the whole file's
  // longest. Unset (a live service, which has no file), the session measures it over a standstill in the last
  // kPreStartKept_s before the alignment (FilterOptions::installed_noise_floor), and a white-noise density
  // configured as 0 takes that standstill's measurement (NavFilter::fill_unset_white_noise), as offline.
  std::optional<ImuNoiseScale> imu_noise_floor;
  // With it: the std of |f| that standstill showed (InstalledImuNoise::f_norm_scatter_mps2; 0: none), for the
  // ZUPT's static detector.
  double standstill_f_scatter_mps2 = 0.0;
  // A failed alignment is redone (robust runs, FilterOptions::robust_update): when the horizontal velocity
  // changes the IMU senses, in the navigated attitude, are turned by more than this against the GNSS track's
  // (heading_check.hpp), and by more than 3 sigma of the filter's heading std, the heading has failed (a false
  // course, a mounting the trial missed), once that has held for heading_failed_for_s on end: the data are
  // aligned again while moving, with at least 4 body headings (the axis-aligned mountings).
  double heading_failed_rad = 30.0 * kDegToRad;
  double heading_failed_for_s = 5.0;
  // The IMU latency looked for live, over a sliding window (imu_latency_window.hpp), and taken out of the
  // IMU stamps from the moment it is found. Offline runs estimate it over the whole file before the session
  // (toolbox/assess/nav_inputs.hpp) and leave this unset.
  std::optional<ImuLatencyWindowOptions> imu_latency_window;
};

class NavSession {
 public:
  // The standstill before the start the IMU noise as installed was measured over [s] (0: none found or not looked
  // for).
  double noise_standstill_s() const { return noise_standstill_s_; }
  // Called after every IMU sample the filter navigated, with the GPS week the sample came with.
  using EpochSink = std::function<void(const NavFilter&, int gps_week)>;
  static constexpr double kLookahead_s = 0.5;  // readings are handed to the filter this far ahead of the IMU
  static constexpr double kSlowCourseSpeed_mps = 0.5;
  // How much more (in truncated NIS over the trial window) every heading beyond the best one's neighbours must
  // cost for the trial to be decided: a likelihood ratio of about e^4.5.
  static constexpr double kTrialMargin = 9.0;
  // How far the first fix may be from a given position that still holds (an antenna lever arm not configured).
  static constexpr double kGivenStillThere_m = 3.0;
  // How much data before the alignment is kept for the IMU noise as installed (SessionOptions::imu_noise_floor).
  static constexpr double kPreStartKept_s = 120.0;

  // Drives `filter` (the caller keeps it: its observer, its results after the run).
  NavSession(SessionOptions options, NavFilter& filter, EpochSink on_epoch);

  // A service's saved attitude and velocity: used with the first GNSS fix if it comes within 1 s. The saved gyro
  // bias (the one its filter took out) is taken out of every increment, as an alignment's turn-on bias is.
  void set_warm_start(const NavState& saved, const NavStd& saved_std, const Vec3& saved_gyro_bias_rad_s = Vec3::Zero());

  void add_imu(const ImuIncrement& imu, int gps_week, double arrival_s);
  void add_gnss(const GnssFix& fix, double arrival_s);
  void add_observation(ObservationPtr reading, double arrival_s);
  // Lets queued samples through when GNSS is silent (call periodically with the arrival clock).
  void idle(double now_s);
  // End of input: the alignment takes what is queued (the slow-course fallback and the heading trial too).
  void finish();

  bool navigating() const;
  const NavFilter& filter() const { return filter_; }
  NavFilter& filter() { return filter_; }
  // "given", "warm start", or the alignment's method with what was decided (fallback, heading trial).
  const std::string& initialisation() const { return initialisation_; }
  // A turn-on gyro bias the alignment's static start showed, taken out of every increment (else 0).
  const Vec3& gyro_bias_seed_rad_s() const { return gyro_bias_seed_rad_s_; }
  const Vec3& gyro_bias_seed_std_rad_s() const { return gyro_bias_seed_std_rad_s_; }  // 0 when not measured
  // The body heading an unknown mounting was found at (course_hypotheses > 1): the body x axis from the GNSS course
  // and the spacing of the headings tried. Unset when none was tried.
  struct BodyHeading {
    double from_course_rad = 0.0, spacing_rad = 0.0;
    int tried = 0;
    bool by_accelerations = false;  // else by the innovations of a filter per heading
  };
  const std::optional<BodyHeading>& body_heading() const { return body_heading_; }
  // The filter's initial epoch, and the IMU noise floor it runs with (FilterOptions::adapt_imu_noise).
  double started_at_s() const { return started_at_s_; }
  const ImuNoiseScale& imu_noise_floor() const { return imu_noise_floor_; }
  long imu_samples_used() const { return imu_used_; }
  long gnss_fixes_used() const { return gnss_used_; }
  long other_readings_used() const { return others_used_; }
  // Alignments redone after the navigated heading failed (SessionOptions::heading_failed_rad).
  int realignments() const { return realignments_; }
  // The live IMU latency (SessionOptions::imu_latency_window): nullptr when not looked for. IMU samples whose
  // re-timed stamp fell at or before one already used (a lag taken out part-way through) are dropped.
  const ImuLatencyWindow* imu_latency_window() const { return latency_window_ ? &*latency_window_ : nullptr; }
  long imu_samples_dropped_retimed() const { return imu_dropped_retimed_; }

 private:
  struct QueuedImu {
    ImuIncrement imu;
    int week;
    double arrival_s;
  };
  struct Alignment {
    NavState state;
    NavStd std;
    std::string method;
    Vec3 gyro_bias_seed = Vec3::Zero();
    Vec3 gyro_bias_seed_std = Vec3::Zero();
  };
  void drain_alignment_queue(double now_s, bool at_end);
  void decide_late_given_start(double now_s, bool at_end);
  AlignmentOptions slow_course_options() const;
  void take_slow_course_alignment();
  bool heading_trial_ready(double now_s, bool at_end) const;
  // Decides the body heading over the trial window, or (not at_end, the headings not told apart) grows the window.
  void run_heading_trial(bool at_end);
  // The heading error of `al` from the accelerations up to t_window_end (HeadingCheck), when they show it.
  std::optional<double> window_heading_misfit(const Alignment& al, double t_window_end) const;
  bool try_warm_start(const ImuIncrement& imu);
  void aligned(Alignment al);
  bool wants_pre_start_noise() const;
  void keep_pre_start(const ImuIncrement& imu);
  // The floor (and a white noise configured as 0) from a standstill before the alignment, once.
  void measure_noise_before_start();
  void measure_noise_while_navigating(const ImuIncrement& imu);
  // position_from_fix: the position is a GNSS fix's moved to the IMU (aligned, warm start), not a given one.
  void start(const NavState& s, const NavStd& sd, const std::string& how, const std::optional<Vec3>& gyro_bias_seed,
             bool position_from_fix);
  void release_backlog();
  void navigate(const ImuIncrement& imu, int week);
  void hand_over_readings(double up_to_s);
  void realign(double misfit_rad);

  SessionOptions o_;
  EpochSink on_epoch_;
  NavFilter& filter_;
  Aligner aligner_;
  std::optional<Aligner> slow_aligner_;  // course from kSlowCourseSpeed_mps (when the configured speed is higher)
  std::optional<Alignment> slow_result_;
  std::deque<QueuedImu> slow_replay_imu_;  // IMU samples and fixes the aligners took after slow_result_
  std::vector<GnssFix> slow_replay_gnss_;
  std::optional<Alignment> trial_;  // aligned from the course: which body heading? (course_hypotheses > 1)
  double trial_window_s_ = 0.0;     // its data window: course_trial_s, grown while the headings tie
  std::deque<ImuIncrement> pre_start_imu_;  // the data the aligner took, for measure_noise_before_start
  std::vector<GnssFix> pre_start_gnss_;
  bool noise_measured_ = false;
  double noise_standstill_s_ = 0.0;      // the standstill the noise was measured over (0: none found)
  std::optional<double> still_since_s_;  // navigating: the current standstill began (measure_noise_while_navigating)
  static constexpr double kMinNoiseStandstill_s = 10.0;
  std::optional<BodyHeading> body_heading_;
  std::string noise_note_;  // what measure_noise_before_start found, for the initialisation line
  std::deque<QueuedImu> imu_queue_;
  std::deque<GnssFix> gnss_queue_;          // fixes not yet handed over, in time order
  std::deque<ObservationPtr> other_queue_;  // other sensors' readings not yet handed over, in time order
  double latest_gnss_t_s_ = -1e300;
  double latest_imu_seen_t_s_ = -1e300;  // the latest IMU sample received, used or not
  double latest_imu_arrival_s_ = -1e300;
  std::optional<std::pair<NavState, NavStd>> warm_;
  Vec3 warm_gyro_bias_rad_s_ = Vec3::Zero();
  std::optional<GnssFix> warm_fix_;
  std::string initialisation_, given_note_, redo_note_;
  bool given_pending_ = false;  // the data started after the given state's time: the GNSS decides
  Vec3 gyro_bias_seed_rad_s_ = Vec3::Zero();
  Vec3 gyro_bias_seed_std_rad_s_ = Vec3::Zero();
  double started_at_s_ = 0.0;
  ImuNoiseScale imu_noise_floor_;
  long imu_used_ = 0, gnss_used_ = 0, others_used_ = 0;
  HeadingCheck heading_check_;
  std::deque<GnssFix> fixes_to_check_;  // handed to the filter, not yet to heading_check_
  std::optional<double> heading_failing_since_s_;
  int realignments_ = 0;
  std::optional<ImuLatencyWindow> latency_window_;
  double latest_retimed_imu_t_s_ = -1e300;
  long imu_dropped_retimed_ = 0;
};

}  // namespace ldv::est
