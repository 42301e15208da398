#pragma once
// NavFilter: the error-state EKF around the strapdown INS. The one engine used by `ldv nav`,
// the live fusion service and `ldv diagnose`.
//
// Feeding: add_imu() for every raw IMU increment, in time order; add_observation() (add_gnss() for a fix)
// for every reading of an external sensor, at any time, in one time-ordered queue for all sensors:
//  - a reading ahead of the IMU waits in the queue and is applied exactly at its epoch (label -
//    time_offset): the IMU interval containing it is split there (offline: feed readings before the IMU
//    reaches them);
//  - a late reading (epoch already passed, up to options.history_s) rewinds to the last snapshot before
//    its epoch and re-processes the kept raw IMU history with it inserted, so the result equals the
//    on-time result (live use: GNSS solutions arrive ~0.1-1 s late). Snapshots: every 0.2 s.
// Aids that watch the IMU stream (ZUPT, ZARU, NHC: estimator/update/updater.hpp) run after each sample.
// A copy of a filter is an exact checkpoint: it continues exactly as the original would. The copy has no
// observer (the original's belongs to the original's owner); set one on it if it should report.
// Covariance: accumulated F over IMU samples, propagated at most every options.cov_period_s and at every
// measurement with Phi = I + F T + (F T)^2 / 2, exploiting the nav / effect block structure.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <deque>
#include <vector>

#include "common/formats/nav_types.hpp"
#include "estimator/filter/imu_noise_scale.hpp"
#include "estimator/filter/noise_adaptation.hpp"
#include "estimator/filter/records.hpp"
#include "estimator/filter/status.hpp"
#include "estimator/ins/mechanization.hpp"
#include "estimator/options.hpp"
#include "estimator/state/state_layout.hpp"
#include "estimator/update/measurement.hpp"
#include "estimator/update/observation.hpp"
#include "estimator/update/updater.hpp"
#include "estimator/update/zupt.hpp"

namespace ldv::est {

// Covariance of the gyros' white angle error (their Allan Q per body axis [rad]) in n [rad^2]: no state holds it
// (it does not accumulate), so it is added where attitude is reported, not to P.
Mat3 attitude_quantization_cov_n(const Mat3& C_b_n, const Vec3& gyro_quantization_rad);

class NavFilter {
 public:
  explicit NavFilter(FilterOptions options);

  // Starts the filter at `s` with this uncertainty; effect blocks start at their priors.
  void initialize(const NavState& s, const NavStd& std);
  // After initialize, when the initial position came from a GNSS fix moved to the IMU by the lever arm's prior
  // mean and carried over the time offset's: its error holds those priors' errors too (delta_r = delta_r_fix -
  // C_b_n delta_l + v_n delta_time_offset), so the covariance gets them, correlated. Without it the start ties a
  // lever arm estimated with a wide prior to that prior's mean: the vertical, seen otherwise only through roll
  // and pitch, read -0.78 m for -1.2 (ldv diagnose, a vehicle from its datasheet config).
  void couple_start_to_gnss_effects();
  bool initialized() const { return c_.initialized; }
  // Forgets the run: back to before initialize(), with the same options and observer (a redone alignment).
  void restart();

  void add_imu(const ImuIncrement& raw);
  // An external sensor's reading (GNSS fix, odometer, ...); an invalid one is counted and dropped.
  void add_observation(ObservationPtr observation);
  void add_gnss(const GnssFix& fix);

  const NavState& state() const { return c_.nav; }
  // Covariance at the last covariance epoch (lags state() by less than cov_period_s).
  const Eigen::MatrixXd& covariance() const { return c_.P; }
  // Replaces the covariance (tools / tests). A matrix that is not finite and PD is reset and flagged.
  void set_covariance(const Eigen::MatrixXd& P);
  // Position, velocity and attitude sigmas; the attitude's with the gyros' Q (attitude_quantization_cov_n).
  NavStd nav_std() const;
  // Covariance of the gyros' white angle error Q in n [rad^2] at the current attitude (the free function below).
  Mat3 attitude_quantization_cov_n() const;
  // Nominal estimates of the effect states (layout offsets minus 9), SI units.
  const Eigen::VectorXd& effect_state() const { return c_.x_eff; }
  const ImuErrorModel& error_model() const { return c_.model; }
  // The state's epoch on the GNSS (GPS) time scale: the IMU's time plus the time_offset, estimated or configured
  // (docs/effects.md). What a TSPI row is stamped with: the filter runs on the IMU's clock, and an IMU that tags
  // 64 ms late shows a vehicle 64 ms back at each of its tags. state().t_s where there is no time offset.
  double gnss_time_s() const { return c_.nav.t_s + c_.model.time_offset_s; }
  const StateLayout& layout() const { return layout_; }
  const FilterOptions& options() const { return opt_; }
  // FilterOptions::input_gyro_bias_rad_s, set once the alignment has seen it (after initialize).
  void set_input_gyro_bias(const Vec3& gyro_bias_rad_s) { opt_.input_gyro_bias_rad_s = gyro_bias_rad_s; }
  std::uint32_t status() const { return c_.status; }
  const FaultCounters& faults() const { return faults_; }
  // The factor the NIS adaptation puts on top of the floor (FilterOptions::adapt_imu_noise; >= 1).
  double imu_noise_scale() const { return c_.imu_noise_scale; }
  // The largest that factor reached over the run (every re-alignment included) and when: the value at the end
  // says what the filter ran with last, not what it needed on the way (one factor on the IMU ended a real walk
  // at 5.5x after about 3000x while walking).
  struct ImuNoisePeak {
    double scale = 1.0;
    double t_s = NAN;
  };
  const ImuNoisePeak& imu_noise_peak() const { return imu_noise_peak_; }
  // The factor on the GNSS position variances the receiver states (FilterOptions::split_noise_adaptation; 1 without)
  // and the estimator behind both factors (its whiteness check).
  double gnss_noise_scale(int gnss_class = 0) const { return c_.noise_adaptation.gnss_scale(gnss_class); }
  const NoiseAdaptation& noise_adaptation() const { return c_.noise_adaptation; }
  // The IMU tags' scatter [s] measured from the data (FilterOptions::imu_stamp_jitter_s), before the first sample.
  void set_imu_stamp_jitter(double sigma_s) { opt_.imu_stamp_jitter_s = sigma_s; }
  // A white-noise density configured as 0 (a datasheet that prints none) takes the one given, axis by axis,
  // e.g. what a standstill in the data showed: the floor below is a factor and cannot raise a 0. Before
  // initialize (the static detector reads the densities there). Returns whether anything was filled.
  bool fill_unset_white_noise(const Vec3& arw_rad_per_sqrt_s, const Vec3& vrw_mps_per_sqrt_s);
  // The floor: the noise as installed, e.g. what a standstill in the data showed (installed_imu_noise.hpp), set
  // after initialize; without it the configuration. The adaptation never goes below it.
  void set_imu_noise_floor(const ImuNoiseScale& psd_floor);
  // The std of |f| a standstill showed (InstalledImuNoise::f_norm_scatter_mps2), for the ZUPT's static detector:
  // an engine's harmonics at idle are in it, not in the floor. After initialize.
  void set_standstill_f_scatter(double f_scatter_mps2);
  const ImuNoiseScale& imu_noise_floor() const { return c_.imu_noise_floor; }
  // What the filter runs with: the floor times the adapted factor, on the configured PSDs.
  ImuNoiseScale imu_noise_psd_scale() const {
    return {c_.imu_noise_floor.gyro * c_.imu_noise_scale, c_.imu_noise_floor.accel * c_.imu_noise_scale};
  }
  // Angular rate and specific force of the last sample, error-compensated (body axes).
  const MechanizationStep& last_step() const { return c_.mech.last(); }
  // Records since the last call (pre-update innovations with gate decisions).
  std::vector<InnovationRecord> take_innovations();
  const std::vector<InnovationRecord>& innovations() const { return innovations_; }
  void set_observer(FilterObserver* observer) { observer_.p = observer; }
  // Chi-square gate of a measurement with `dof` rows (gate_threshold(): the 3-D GNSS one).
  double gate_threshold(int dof = 3) const;
  // Where the measurement models linearise now: attitude, compensated rates, the effects' estimates.
  LinearizationPoint linearization_point() const;
  // Forgets queued GNSS fixes tagged after t_s, keeping other sensors' readings (a copy restarting into a
  // GNSS outage: toolbox/assess/filter_checkpoint).
  void drop_queued_gnss_after(double t_s);

 private:
  struct Event {
    long id;
    double t_apply_s;
    ObservationPtr obs;
    double t_s() const { return obs->t_s; }
  };
  // Measurements of one sensor beyond the gate in a row (the step confirmation).
  struct RejectRun {
    SensorName sensor;
    int count = 0;
    double first_t_s = 0.0;  // epoch of the first of them
    Eigen::VectorXd last_y;  // innovation of the last rejection before re-synchronisation was due
    Eigen::VectorXd held_y;  // innovation of the last one held back while due (empty: none)
  };
  // Everything that changes while filtering: copied into snapshots for late measurements.
  struct Core {
    bool initialized = false;
    NavState nav;
    Eigen::VectorXd x_eff;
    Eigen::MatrixXd P;
    ImuErrorModel model;
    Mechanization mech;
    double acc_T_s = 0.0;
    Vec3 acc_dv_n = Vec3::Zero();
    // The stamp jitter's process noise since the last covariance step (FilterOptions::imu_stamp_jitter_s), n frame,
    // and the rates of the IMU sample before.
    Mat3 acc_jitter_att_n = Mat3::Zero(), acc_jitter_vel_n = Mat3::Zero();
    Vec3 prev_omega_b_rad_s = Vec3::Zero(), prev_f_b_mps2 = Vec3::Zero();
    bool have_prev_rates = false;
    Eigen::Matrix<double, 9, Eigen::Dynamic> acc_B;  // accumulated F_ne * dt
    StaticDetector detector{0.5, 0.05, 0.01};
    Vec3 f_n_smooth_mps2 = Vec3::Zero();  // specific force in n, first-order low pass (window / 4: little lag)
    double last_gnss_t_s = -1e300;
    Vec3 v_n_at_last_gnss_mps = Vec3::Zero();  // the velocity then (after its update)
    double last_health_t_s = -1e300;
    std::vector<RejectRun> reject_runs;  // per sensor
    std::vector<UpdaterSlot> updaters;   // the IMU-driven aids, with their own small state
    std::uint32_t status = 0;
    double imu_interval_s = 0.0;  // the last regular IMU interval (what one increment normally spans)
    // Factors on the configured IMU white-noise PSDs: the installed noise's floor per sensor, and on top of
    // it one factor adapted from the GNSS position NIS (>= 1). Vibration of an installed IMU is often 10x
    // its datasheet noise.
    ImuNoiseScale imu_noise_floor;
    double standstill_f_scatter_mps2 = 0.0;  // set_standstill_f_scatter
    double imu_noise_scale = 1.0;
    NoiseAdaptation noise_adaptation;  // FilterOptions::split_noise_adaptation: the GNSS and IMU factors
    std::deque<Event> applied;  // readings applied within the history horizon (what a snapshot contains)
    // The last GNSS position fix, if it was taken in at the edge of the gate (NIS above the 99 % quantile) or
    // right after a rejected one: the one to try without when the next fix is rejected (retract_suspect_fix).
    long gnss_suspect_id = -1;  // -1: none
    bool last_gnss_position_rejected = false;
  };

  void process_imu(const ImuIncrement& raw);
  void propagate_sample(const ImuIncrement& raw_part);
  // The stamp jitter's process noise of one raw IMU sample (FilterOptions::imu_stamp_jitter_s).
  void accumulate_stamp_jitter(const ImuIncrement& raw);
  // Coasts from the state's epoch to t_end_s inside a hole in the IMU data that began at hole_start_s: the
  // uncertainty opens by what the hole's length so far allows, whichever pieces it is coasted in.
  void coast_over_imu_gap(double hole_start_s, double t_end_s);
  void adapt_imu_noise(const InnovationRecord& rec);
  // split_noise_adaptation
  void adapt_noise(const InnovationRecord& rec, const Eigen::MatrixXd& R_used, int gnss_class);
  void flush_covariance();
  void accumulate_effect_inputs(const MechanizationStep& st, double dt);  // the effects' B over one step
  void turn_error_frame_over_pole();
  void run_aids();
  void apply_event(const Event& event);
  // Brings P to the state's epoch and applies the first queued reading there.
  void apply_next_pending();
  void enqueue(const Event& event);
  void apply_measurement(const Measurement& given);
  RejectRun& reject_run(SensorName sensor);
  void correct(const Eigen::VectorXd& dx);
  void rebuild_error_model();
  // A block's prior: its own, or the one the configuration states for it (FilterOptions::effect_priors).
  void block_prior(const StateBlock& b, Eigen::Ref<Eigen::VectorXd> mean, Eigen::Ref<Eigen::VectorXd> std) const;
  void reset_static_detector();  // for the configured noise times the floor
  void check_health(bool full);
  void reset_covariance();
  // Re-synchronisation: each accelerometer error block's variance back to at least its prior.
  void reopen_accel_errors_to_prior();
  void announce_restart();  // to the observer: the covariance does not follow from the one before
  void take_snapshot();
  double kept_history_s() const;  // snapshots and IMU history: history_s, or longer for retract_suspect_fix
  void rewind_and_apply(const Event& event);
  // Restores snapshot k and re-processes the IMU history after it, with the readings applied since except the one
  // with id `excluded_id`.
  void replay_from_snapshot(int k, long excluded_id);
  // The fix after a suspect one (taken in at the gate's edge or right after a rejection) was rejected: keep the
  // branch without the suspect if the rejected one fits there (retract_suspect_fix). Called where no reading is
  // being applied.
  void settle_suspect_fix();
  bool retract_suspect_fix(long suspect_id, long rejected_id);
  double gate_edge(int dof) const;  // NIS above it: taken in at the gate's edge
  void note_gnss_position_outcome(const InnovationRecord& rec, bool forced, bool beyond_gate);

  FilterOptions opt_;
  StateLayout layout_;
  int m_ = 0;  // effect states
  Eigen::VectorXd prior_std_;
  std::vector<Triplet> F_ee_;  // effect dynamics, effect-local indices
  Eigen::VectorXd q_c_;
  std::vector<Mat3X> J_gyro_, J_accel_;  // per-block workspaces
  std::vector<double> gates_;            // chi-square gate by dof (index = rows)
  std::vector<double> gate_edges_;       // the gate's edge (kGateEdgeProbability) by dof
  Mat3 C_b_v_coarse_ = Mat3::Identity();

  Core c_;
  Core last_good_;
  std::deque<Event> pending_;  // sorted by time tag
  long next_event_id_ = 0;
  std::deque<ImuIncrement> imu_history_;
  std::deque<Core> snapshots_;
  bool replaying_ = false;
  long applying_event_id_ = -1;  // the reading apply_event is applying
  // A GNSS position fix rejected right after a suspect one: {suspect, rejected fix} ids, -1: none.
  long suspect_to_settle_ = -1, rejected_after_suspect_ = -1;
  bool trying_branch_ = false;  // inside retract_suspect_fix's trial
  bool trial_fits_ = false;     // the rejected fix, in the trial branch: within the gate's edge
  // A fix whose NIS is above this quantile (of its dof) is at the gate's edge.
  static constexpr double kGateEdgeProbability = 0.99;

  FaultCounters faults_;
  ImuNoisePeak imu_noise_peak_;
  void note_imu_noise_peak();
  std::vector<InnovationRecord> innovations_;
  // Not taken over by a copy (a checkpoint must not report into its original's observer); a move keeps it.
  struct ObserverPtr {
    FilterObserver* p = nullptr;
    ObserverPtr() = default;
    ObserverPtr(const ObserverPtr&) {}
    ObserverPtr(ObserverPtr&& o) noexcept : p(o.p) {}
    ObserverPtr& operator=(const ObserverPtr&) {
      p = nullptr;
      return *this;
    }
    ObserverPtr& operator=(ObserverPtr&& o) noexcept {
      p = o.p;
      return *this;
    }
  } observer_;
  Eigen::VectorXd dx_;
  Eigen::MatrixXd K_;
};

}  // namespace ldv::est
