#pragma once
// Every setting of the estimator, in SI units, with one place that prints it (engineering units).
#include <array>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "common/math/rotation.hpp"

namespace ldv::est {

// Stochastic model of a 3-axis effect block (prior + own dynamics).
struct BlockOptions {
  enum class Process { kConstant, kRandomWalk, kGaussMarkov };
  Vec3 init = Vec3::Zero();      // prior mean
  Vec3 init_std = Vec3::Zero();  // prior 1-sigma
  Process process = Process::kConstant;
  Vec3 sigma = Vec3::Zero();     // Gauss-Markov steady-state 1-sigma (q_c = 2 sigma^2 / T)
  double corr_time_s = 3600.0;   // Gauss-Markov correlation time
  Vec3 rw_density = Vec3::Zero();  // random walk: sigma growth per sqrt(s) (q_c = rw^2)
};

// The paper's multi-component bias, per axis: [constant, Gauss-Markov, random walk, ramp value, ramp rate];
// the bias is constant + Gauss-Markov + random walk + ramp value; d(ramp value)/dt = ramp rate (constant).
struct MovingBiasOptions {
  Vec3 constant_std = Vec3::Zero();
  Vec3 gm_sigma = Vec3::Zero();
  double gm_corr_time_s = 3600.0;
  Vec3 rw_density = Vec3::Zero();     // K [unit/sqrt(s)]
  Vec3 ramp_rate_std = Vec3::Zero();  // prior of R [unit/s]
};

struct ZuptOptions {
  bool enabled = true;
  double window_s = 0.5;           // detector window
  double f_std_mps2 = 0.05;        // std of |f| over the window below this
  double omega_max_rad_s = 0.5 * kDegToRad;  // mean |omega| over the window below this
  double speed_max_mps = 0.3;      // and the filter's own speed below this (no false ZUPT at constant velocity)
  // and the horizontal specific force (navigation frame, low-passed) below this: braking to a stop
  // keeps |f| ~ g and w ~ 0 (the detector fires) but not f_h ~ 0; a false ZUPT there, deep in a GNSS outage,
  // drags the position through its correlation with the velocity.
  double f_horizontal_max_mps2 = 0.15;
  double period_s = 0.2;           // apply at most this often
  // Measurement noise of the zero velocity: the detector cannot tell creeping below about 2 cm/s
  // from rest (a smooth start stays under f_horizontal_max for that long).
  double std_mps = 0.02;
};

// The land-vehicle aids (--aid, ldv.aids): names of updaters (updater_list.hpp) or "odometer", and their
// noise. The vehicle frame: x forward, y right, z down; mounting_rpy_rad is the coarse rotation of the
// IMU body in it (C_b_v = Rz(yaw) Ry(pitch) Rx(roll)): backwards = yaw 180 deg, upside down = roll 180 deg.
struct AidOptions {
  std::vector<std::string> enabled;
  Vec3 mounting_rpy_rad = Vec3::Zero();
  double nhc_std_mps = 0.1;                  // lateral/vertical velocity a real car has (slip, suspension)
  double nhc_period_s = 0.1;                 // at most this often (vibration makes successive ones correlated)
  double zaru_std_rad_s = 0.01 * kDegToRad;  // what the static detector lets through, beyond white noise
  double odometer_std_mps = 0.05;
  bool has(const std::string& name) const;
};

struct FilterOptions {
  std::string model = "kfgins21";
  std::vector<std::string> add, drop;

  Vec3 arw_rad_per_sqrt_s = Vec3::Constant(0.003 * kDegToRad);  // gyro white noise
  Vec3 vrw_mps_per_sqrt_s = Vec3::Constant(0.001);              // accel white noise
  // The gyros' Allan Q [rad] (IEEE 952's quantization noise, the paper's Q): a white error of std Q on the
  // integrated angle, not on the rate, so it does not accumulate in attitude. It tilts the specific force:
  // velocity takes a random walk of density |f x e| sqrt(tau0) (tau0 the IMU sample period), and the reported
  // attitude sigma holds Q itself (nav_filter.cpp). 0: none (KF-GINS has no such term).
  Vec3 gyro_quantization_rad = Vec3::Zero();
  // The 1-sigma [s] of the IMU samples' time tags about the instants the sensor sampled (a host that stamps on
  // reading, a sensor read faster than it samples). Each increment then spans a wrong interval: its error is the
  // change of the rate since the sample before times the tag's error, a random walk in attitude and velocity that
  // grows with the motion's jerk and vanishes at rest (nav_filter.cpp). 0: tags exact.
  double imu_stamp_jitter_s = 0.0;
  // run_navigation measures it from the tags (imu_stamp_jitter.hpp) unless ldv.imu_stamp_jitter_s states it or the
  // run is KF-GINS's (--kfgins-compatible).
  bool imu_stamp_jitter_from_tags = true;

  BlockOptions gyro_bias, accel_bias, gyro_scale, accel_scale;
  BlockOptions gyro_misalignment, accel_misalignment, g_sensitivity;
  BlockOptions lever_arm, gravity_anomaly;
  BlockOptions gnss_position_bias;  // NED [m]; Gauss-Markov sigma / corr_time_s (ldv: gnss_bias_sigma_m, gnss_bias_tau_s)
  // An unstated IMU-GNSS time offset: as late as real IMUs come (host-stamped USB boxes: hundreds of ms).
  double time_offset_init_s = 0.0, time_offset_std_s = 0.3;
  MovingBiasOptions gyro_moving_bias, accel_moving_bias;
  // Land-vehicle effects (entering the aids): residual mounting rotation [rad], odometer point [m, body],
  // odometer scale [-].
  BlockOptions vehicle_mounting, odometer_lever_arm;
  double odometer_scale_init = 0.0, odometer_scale_std = 0.02;
  AidOptions aids;
  // Priors the configuration states for effect blocks (ldv.priors, written by `ldv diagnose --write-config`
  // from the estimates it found): mean and 1-sigma in SI, by effect name, replacing the block's own.
  struct EffectPrior {
    Eigen::VectorXd mean, std;
  };
  std::map<std::string, EffectPrior> effect_priors;

  // Taken out of every raw gyro increment before anything else: a turn-on bias the alignment's static
  // start showed (Aligner::gyro_bias_seed; NavFilter::set_input_gyro_bias). The gyro-bias states then
  // estimate what is left, inside their configured prior.
  Vec3 input_gyro_bias_rad_s = Vec3::Zero();
  double cov_period_s = 0.1;         // covariance propagated at least this often (and at each measurement)
  double gate_probability = 0.9999;  // chi-square gate on the NIS of each 3-D measurement
  // Beyond the gate: robust (default) keeps the measurement with its noise inflated (kalman_update.hpp),
  // and a step of the measured quantity confirmed by consecutive measurements beyond the gate that agree
  // for step_confirm_s is taken up at once (covariance opened). Not robust (ldv.kfgins_compatible,
  // --kfgins-compatible): rejected, and accepted by force after gate_max_consecutive_rejects, as KF-GINS.
  bool robust_update = true;
  // Scale the IMU white noise up from the configured floor while the GNSS position NIS says the IMU is
  // noisier as installed (vibration) than configured; the scale is reported (NavFilter::imu_noise_scale).
  // Off with ldv.kfgins_compatible and in `ldv diagnose` (whose model check judges the configured model).
  bool adapt_imu_noise = true;
  // With adapt_imu_noise: the GNSS position variance and the IMU noise each get their own factor, told apart by
  // the innovations' whiteness (estimator/filter/noise_adaptation.hpp), instead of one factor on the IMU that
  // every NIS excess went to (issue 47).
  bool split_noise_adaptation = true;
  // The GNSS position variance the receiver states, times this per solution quality (NoiseAdaptation's classes:
  // fixed, float, other), before any adaptation and the gate: a receiver whose std is found too small, as
  // `ldv diagnose` finds it (its gnss_noise finding) and writes it (ldv.gnss_variance_scale).
  std::array<double, 3> gnss_variance_scale = {1.0, 1.0, 1.0};
  // With adapt_imu_noise: run_navigation first measures the noise as installed over a standstill in the data
  // and makes it the floor (installed_imu_noise.hpp). Off where the adaptation itself is the measurement
  // (the IMU-latency decision compares how much noise the filter needs with and without a lag).
  bool installed_noise_floor = true;
  double step_confirm_s = 1.0;
  int gate_max_consecutive_rejects = 10;  // then accept (re-synchronise) and flag
  // Judge each measurement against a gate at all. KF-GINS has none (GIEngine::gnssUpdate updates with every fix):
  // --kfgins-compatible / ldv.kfgins_compatible turn it off, so that mode is KF-GINS fix by fix on real data.
  bool gate_measurements = true;
  // A measurement this close to an IMU epoch is applied at that epoch instead of splitting the IMU interval at it:
  // KF-GINS's TIME_ALIGN_ERR, 1 ms, with --kfgins-compatible (a fix 0.9 ms after an IMU sample updated the state
  // at the sample there, 1-3 cm from ldv's split on the real walk); 0: split exactly.
  double measurement_snap_s = 0.0;
  bool use_gnss_velocity = true;
  ZuptOptions zupt;
  double history_s = 3.0;            // how late a measurement may arrive (IMU history kept)
  // Alignment without a given state (estimator/ins/alignment.hpp): GNSS speed above which the course gives
  // the heading, and how many body headings to try when the mounting is unknown (hand-held: 12).
  double align_speed_mps = 2.0;
  // 8 by default: an IMU mounted backwards or sideways (common: the user cannot know which way the box
  // sits) starts within 22.5 deg of one of them; the trials' innovations pick it. KF-GINS: 1.
  int align_hypotheses = 8;

  FilterOptions();
  void print(std::ostream& out) const;
  // Throws std::invalid_argument naming the first setting that is not finite or outside its physical
  // range (a NaN lever arm would otherwise freeze the filter's time for thousands of rows).
  void check() const;
};

// Effect names of a named model (ins15, kfgins21, geoldv51) after --add/--drop; throws
// std::invalid_argument naming the unknown model or effect.
std::vector<std::string> resolve_model(const std::string& model, const std::vector<std::string>& add,
                                       const std::vector<std::string>& drop);

}  // namespace ldv::est
