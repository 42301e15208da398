#include "estimator/filter/nav_filter.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "common/formats/gnss_solution_checks.hpp"
#include "common/geo/earth_model.hpp"
#include "common/math/chi_square.hpp"
#include "estimator/filter/nav_error_dynamics.hpp"
#include "estimator/update/gnss_fix.hpp"
#include "estimator/update/gnss_velocity.hpp"
#include "estimator/update/kalman_update.hpp"

namespace ldv::est {
namespace {
constexpr double kSnapshotPeriod_s = 0.2;
// History kept for retracting an edge fix: one GNSS interval back at 1 Hz, with room for the snapshot period.
constexpr double kRetractHistory_s = 2.5;
constexpr double kHealthPeriod_s = 1.0;
// A re-synchronisation opens the heading by at most this: beyond, the session's heading check aligns again
// (SessionOptions::heading_failed_rad, 30 deg).
constexpr double kMaxResyncHeading_rad = 0.52;
constexpr double kSplitTolerance_s = 1e-6;
// IMU noise adaptation (FilterOptions::adapt_imu_noise): step in ln(scale) per position fix at NIS/3 - 1,
// and the largest scale (1e4 on the PSD: 100x the configured noise density).
constexpr double kNoiseAdaptGain = 0.1;
constexpr double kMaxImuNoiseScale = 1e4;
// Holding the IMU's rates over missing samples is sound for a few samples, not for a hole: beyond this
// the state coasts at its velocity and the covariance opens by what a land vehicle can do meanwhile.
constexpr double kMaxBridgedImuGap_s = 1.0;
constexpr double kGapAccelStd_mps2 = 2.0;      // unknown acceleration during a gap
constexpr double kGapTurnRateStd_rad_s = 0.1;  // unknown rotation during a gap
constexpr double kGapMaxDeadReckoning_s = 10.0;  // beyond: the velocity is not carried on, the position held
// Caps that keep the linearised filter meaningful after a long hole: the next fixes pull the state in
// (a land vehicle stays about level; its heading is what is lost).
constexpr double kGapMaxPosStd_m = 1e3, kGapMaxVelStd_mps = 10.0, kGapMaxTiltStd_rad = 2.0 * kDegToRad,
                 kGapMaxYawStd_rad = 30.0 * kDegToRad;
// Gates are kept for measurements of up to this many rows (larger ones: computed when met).
constexpr int kCachedGateDof = 8;

ImuIncrement scaled(const ImuIncrement& in, double fraction) {
  ImuIncrement out = in;
  out.dtheta_b_rad *= fraction;
  out.dvel_b_mps *= fraction;
  out.dt_s *= fraction;
  return out;
}

// Finite, and where a vehicle can be: a speed above any receiver's (1000 m/s) or a height beyond the plausible
// ones is a diverged state, not navigation (a forced GNSS step 1 km away, then a fix back, once drove the
// velocity to 8e6 m/s: garbage on every NAV after it).
bool usable(const NavState& s) {
  return std::isfinite(s.pos.lat_rad) && std::isfinite(s.pos.lon_rad) && std::isfinite(s.pos.h_m) &&
         s.v_n_mps.allFinite() && s.q_b_n.coeffs().allFinite() &&
         s.v_n_mps.norm() <= gnss::kMaxPlausibleSpeed_mps && s.pos.h_m >= gnss::kMinPlausibleHeight_m &&
         s.pos.h_m <= gnss::kMaxPlausibleHeight_m;
}
}  // namespace

NavFilter::NavFilter(FilterOptions options)
    : opt_((options.check(), std::move(options))), layout_(resolve_model(opt_.model, opt_.add, opt_.drop), opt_) {
  m_ = layout_.effect_dim();
  prior_std_ = Eigen::VectorXd::Zero(m_);
  q_c_ = Eigen::VectorXd::Zero(m_);
  for (const auto& b : layout_.blocks()) {
    const int o = b.offset - kNavDim;
    Eigen::VectorXd mean(b.dim), std(b.dim);
    block_prior(b, mean, std);
    prior_std_.segment(o, b.dim) = std;
    b.effect->process_noise(q_c_.segment(o, b.dim));
    for (const Triplet& t : b.effect->dynamics()) F_ee_.push_back({o + t.row, o + t.col, t.value});
    J_gyro_.push_back(Mat3X::Zero(3, b.dim));
    J_accel_.push_back(Mat3X::Zero(3, b.dim));
  }
  for (int dof = 0; dof <= kCachedGateDof; ++dof) {
    gates_.push_back(dof == 0 ? 0.0 : math::chi_square_quantile(opt_.gate_probability, dof));
    gate_edges_.push_back(dof == 0 ? 0.0 : math::chi_square_quantile(kGateEdgeProbability, dof));
  }
  C_b_v_coarse_ = C_b_n_from_euler(opt_.aids.mounting_rpy_rad);
}

void NavFilter::block_prior(const StateBlock& b, Eigen::Ref<Eigen::VectorXd> mean,
                            Eigen::Ref<Eigen::VectorXd> std) const {
  b.effect->prior(mean, std);
  const auto stated = opt_.effect_priors.find(b.effect->name());
  if (stated == opt_.effect_priors.end()) return;
  if (stated->second.mean.size() != b.dim || stated->second.std.size() != b.dim)
    throw std::invalid_argument(std::string("prior of ") + b.effect->name() + ": expected " + std::to_string(b.dim) +
                                " values and sigmas");
  mean = stated->second.mean;
  std = stated->second.std;
}

double NavFilter::gate_threshold(int dof) const {
  if (dof >= 0 && dof <= kCachedGateDof) return gates_[dof];
  return math::chi_square_quantile(opt_.gate_probability, dof);
}

double NavFilter::gate_edge(int dof) const {
  if (dof >= 0 && dof <= kCachedGateDof) return gate_edges_[dof];
  return math::chi_square_quantile(kGateEdgeProbability, dof);
}

void NavFilter::restart() {
  FilterObserver* observer = observer_.p;
  const FaultCounters faults = faults_;  // a run's summary counts its faults over every re-alignment
  const ImuNoisePeak peak = imu_noise_peak_;
  *this = NavFilter(opt_);
  observer_.p = observer;
  faults_ = faults;
  imu_noise_peak_ = peak;
}

void NavFilter::initialize(const NavState& s, const NavStd& std) {
  // A NaN or absurd initial state would freeze the filter (every step rejected as non-finite).
  if (!usable(s) || std::abs(s.pos.lat_rad) > 0.5 * M_PI || !std::isfinite(s.t_s))
    throw std::invalid_argument("initial state: not finite or out of range (|lat| <= 90 deg, h in [-1, 100] km, |v| <= 1000 m/s)");
  if (!std.pos_ned_m.allFinite() || !std.vel_n_mps.allFinite() || !std.att_rad.allFinite() ||
      std.pos_ned_m.minCoeff() < 0 || std.vel_n_mps.minCoeff() < 0 || std.att_rad.minCoeff() < 0)
    throw std::invalid_argument("initial state std: must be >= 0 and finite");
  c_ = Core{};
  c_.nav = s;
  c_.x_eff = Eigen::VectorXd::Zero(m_);
  Eigen::VectorXd var(kNavDim + m_);
  var << std.pos_ned_m.cwiseAbs2(), std.vel_n_mps.cwiseAbs2(), std.att_rad.cwiseAbs2(), prior_std_.cwiseAbs2();
  for (const auto& b : layout_.blocks()) {
    Eigen::VectorXd mean(b.dim), sd(b.dim);
    block_prior(b, mean, sd);
    c_.x_eff.segment(b.offset - kNavDim, b.dim) = mean;
  }
  c_.P = var.asDiagonal();
  c_.acc_B = Eigen::Matrix<double, 9, Eigen::Dynamic>::Zero(9, m_);
  reset_static_detector();
  c_.mech.reset(s);
  c_.updaters = make_updaters(opt_);
  c_.initialized = true;
  c_.status = kStatusInitialized;
  c_.last_gnss_t_s = s.t_s;
  c_.v_n_at_last_gnss_mps = s.v_n_mps;
  rebuild_error_model();
  last_good_ = c_;
  pending_.clear();
  snapshots_.clear();
  imu_history_.clear();
  if (kept_history_s() > 0.0) snapshots_.push_back(c_);  // a fix at the initial epoch may still arrive late
  announce_restart();
}

void NavFilter::couple_start_to_gnss_effects() {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, c_.P.cols());  // d(initial position error) / d(effect errors)
  for (const auto& b : layout_.blocks()) {
    const std::string_view name = b.effect->name();  // compared as text: a const char* == compares addresses
    if (name == "lever_arm") J.middleCols(b.offset, 3) = -c_.nav.C_b_n();
    if (name == "time_offset") J.col(b.offset) = c_.nav.v_n_mps;
  }
  if (J.isZero()) return;
  // P <- T P T^T with T = I + E, E's position rows J: the error moves into the position, the rest unchanged.
  const Eigen::MatrixXd JP = J * c_.P;
  c_.P.topRows(3) += JP;
  c_.P.leftCols(3) += JP.transpose();
  c_.P.topLeftCorner(3, 3) += JP * J.transpose();
  last_good_ = c_;
  if (!snapshots_.empty()) snapshots_.back() = c_;
}

void NavFilter::rebuild_error_model() {
  ImuErrorModel& m = c_.model;
  m.clear_imu_terms();
  m.gravity_anomaly_n_mps2.setZero();
  m.gnss_position_bias_n_m.setZero();
  m.lever_arm_b_m = opt_.lever_arm.init;  // used as given when lever_arm is not estimated
  m.time_offset_s = opt_.time_offset_init_s;
  m.vehicle_mounting_rad = opt_.vehicle_mounting.init;
  m.odometer_lever_arm_b_m = opt_.odometer_lever_arm.init;
  m.odometer_scale = opt_.odometer_scale_init;
  for (const auto& b : layout_.blocks()) b.effect->apply(c_.x_eff.segment(b.offset - kNavDim, b.dim), m);
  c_.mech.set_gravity_anomaly_n(m.gravity_anomaly_n_mps2);
}

void NavFilter::add_imu(const ImuIncrement& input) {
  ImuIncrement raw = input;
  raw.dtheta_b_rad -= opt_.input_gyro_bias_rad_s * raw.dt_s;
  if (!std::isfinite(raw.t_s) || !(raw.dt_s > 0.0) || !raw.dtheta_b_rad.allFinite() || !raw.dvel_b_mps.allFinite()) {
    c_.status |= kStatusImuRejected;
    ++faults_.imu_rejected;
    return;
  }
  c_.status &= ~(kStatusImuRejected | kStatusImuGap | kStatusCovarianceReset | kStatusStateReset | kStatusLateDropped |
                 kStatusMeasurementRejected);
  if (!c_.initialized) return;
  // The IMU since the last healthy state is always kept: a state reset brings that state forward with it.
  const double imu_kept_s = std::max(kept_history_s(), 2.0 * kHealthPeriod_s);
  imu_history_.push_back(raw);
  while (!imu_history_.empty() && imu_history_.front().t_s < raw.t_s - imu_kept_s) imu_history_.pop_front();
  process_imu(raw);
  if (kept_history_s() > 0.0) take_snapshot();
  settle_suspect_fix();
}

double NavFilter::kept_history_s() const {
  // The robust update keeps a few seconds even offline (history_s 0: no fix is late there), so that a fix taken
  // in at the gate's edge can be undone when the next one shows it was the outlier (retract_suspect_fix).
  return opt_.robust_update ? std::max(opt_.history_s, kRetractHistory_s) : opt_.history_s;
}

void NavFilter::take_snapshot() {
  if (snapshots_.empty() || c_.nav.t_s - snapshots_.back().nav.t_s >= kSnapshotPeriod_s) snapshots_.push_back(c_);
  while (snapshots_.size() > 1 && snapshots_[1].nav.t_s < c_.nav.t_s - kept_history_s()) snapshots_.pop_front();
}

void NavFilter::coast_over_imu_gap(double hole_start_s, double t_end_s) {
  flush_covariance();
  const double from_s = c_.nav.t_s - hole_start_s, to_s = t_end_s - hole_start_s;
  NavState s = c_.nav;
  s.pos = earth::offset_ned(
      s.pos, s.v_n_mps * (std::min(to_s, kGapMaxDeadReckoning_s) - std::min(from_s, kGapMaxDeadReckoning_s)));
  s.t_s = t_end_s;
  // The standard deviations a hole opens in its first t seconds; a piece of it adds its share of the variance.
  const auto opened = [&](auto std_after, double cap) {
    return std::pow(std::min(std_after(to_s), cap), 2) - std::pow(std::min(std_after(from_s), cap), 2);
  };
  const double var_pos = opened([](double t) { return 0.5 * kGapAccelStd_mps2 * t * t; }, kGapMaxPosStd_m);
  const double var_vel = opened([](double t) { return kGapAccelStd_mps2 * t; }, kGapMaxVelStd_mps);
  const auto turned = [](double t) { return kGapTurnRateStd_rad_s * t; };
  const Eigen::VectorXd var_before = c_.P.diagonal();
  for (int i = 0; i < 3; ++i) {
    c_.P(kPos + i, kPos + i) += var_pos;
    c_.P(kVel + i, kVel + i) += var_vel;
    c_.P(kAtt + i, kAtt + i) += opened(turned, i < 2 ? kGapMaxTiltStd_rad : kGapMaxYawStd_rad);
  }
  const double coasted_s = t_end_s - c_.nav.t_s;
  c_.nav = s;
  c_.mech.reset(s);
  if (observer_.p && observer_.p->wants_matrices()) {  // to a smoother, a piece of the hole is an epoch of its own
    const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(c_.P.rows(), c_.P.cols());
    observer_.p->on_propagation(t_end_s, coasted_s, I, Eigen::MatrixXd((c_.P.diagonal() - var_before).asDiagonal()));
  }
}

void NavFilter::process_imu(const ImuIncrement& raw) {
  const double t_end = raw.t_s;
  const double t0 = c_.nav.t_s;
  if (t_end <= t0 + 1e-9) return;  // before the initial epoch
  ImuIncrement in = raw;
  if (in.dt_s > kMaxBridgedImuGap_s || t_end - in.dt_s - t0 > kMaxBridgedImuGap_s) {
    // A hole in the data (an increment said to span the hole, or samples missing before it): coast to
    // one regular interval before this sample, then integrate the sample over that interval only.
    const double interval_s =
        c_.imu_interval_s > 0.0 ? c_.imu_interval_s : std::min(in.dt_s, kMaxBridgedImuGap_s);
    if (in.dt_s > interval_s) in = scaled(raw, interval_s / raw.dt_s);
    in.dt_s = interval_s;
    c_.status |= kStatusImuGap;
    ++faults_.imu_gaps;
    // The fixes that arrived during the hole are applied at their own epochs, each on the state coasted to it:
    // applied at its end, the oldest would pull the state back by the distance driven since (20 m after 2 s at 10 m/s).
    const double coast_to_s = t_end - interval_s;
    while (!pending_.empty() && pending_.front().t_s() - c_.model.time_offset_s < coast_to_s - kSplitTolerance_s) {
      const double t_m = pending_.front().t_s() - c_.model.time_offset_s;
      if (t_m > c_.nav.t_s + kSplitTolerance_s) coast_over_imu_gap(t0, t_m);
      apply_next_pending();
    }
    if (coast_to_s > c_.nav.t_s) coast_over_imu_gap(t0, coast_to_s);
  } else {
    c_.imu_interval_s = in.dt_s;
  }
  ImuIncrement rem = in;
  const double t_start = t_end - in.dt_s;
  const double t_from = c_.nav.t_s;
  if (t_start < t_from - 1e-9) rem = scaled(in, (t_end - t_from) / in.dt_s);  // initialised inside this interval
  if (t_start > t_from + 1e-9) {
    // A few missing samples: integrate the increment over the whole gap (its rate held).
    if (t_end - t_from > 5.0 * in.dt_s) {
      c_.status |= kStatusImuGap;
      ++faults_.imu_gaps;
    }
    rem = scaled(in, (t_end - t_from) / in.dt_s);
  }
  rem.dt_s = t_end - t_from;

  // A measurement within `snap` of the sample's end is applied there (KF-GINS: 1 ms,
  // FilterOptions::measurement_snap_s), one within it after the start at the start; else the interval is split at its
  // epoch.
  const double snap = std::max(kSplitTolerance_s, opt_.measurement_snap_s);
  while (!pending_.empty()) {
    const double t_m = pending_.front().t_s() - c_.model.time_offset_s;
    if (t_m > t_end + snap) break;
    if (t_m > c_.nav.t_s + snap && t_m < t_end - snap) {
      // Split the interval exactly at the measurement epoch (increments shared in proportion to time).
      const double lambda = (t_m - c_.nav.t_s) / (t_end - c_.nav.t_s);
      ImuIncrement part = scaled(rem, lambda);
      part.t_s = t_m;
      rem = scaled(rem, 1.0 - lambda);
      propagate_sample(part);
    } else if (t_m >= t_end - snap && rem.dt_s > 0.0) {
      propagate_sample(rem);
      rem.dt_s = 0.0;
    }
    apply_next_pending();
  }
  if (rem.dt_s > 0.0) propagate_sample(rem);
  accumulate_stamp_jitter(raw);

  const MechanizationStep& st = c_.mech.last();
  const bool stat = c_.detector.add(st.dt_s, st.omega_ib_b_rad_s, st.f_b_mps2);
  if (st.dt_s > 0.0)
    c_.f_n_smooth_mps2 += std::min(1.0, st.dt_s / (0.25 * opt_.zupt.window_s)) * (st.dv_sf_n_mps / st.dt_s - c_.f_n_smooth_mps2);
  c_.status = stat ? (c_.status | kStatusZuptActive) : (c_.status & ~kStatusZuptActive);
  if (c_.acc_T_s >= opt_.cov_period_s) flush_covariance();
  run_aids();
  if (c_.nav.t_s - c_.last_gnss_t_s > 2.0)
    c_.status |= kStatusGnssOutage;
  else
    c_.status &= ~kStatusGnssOutage;
  if (!usable(c_.nav)) {
    // Restore the last healthy state and open its covariance: never continue with NaN or a diverged state.
    const std::uint32_t bits = c_.status;
    const double t_now = c_.nav.t_s;
    c_ = last_good_;
    c_.P *= 4.0;
    // ... brought forward to this sample by the IMU alone: the state's time only increases (issue 46: the
    // restored state's older time went into the .nav again, 8303 rows stepping back).
    for (const ImuIncrement& raw : imu_history_)
      if (raw.t_s > c_.nav.t_s + kSplitTolerance_s && raw.t_s <= t_now + kSplitTolerance_s) propagate_sample(raw);
    flush_covariance();
    c_.status = bits | kStatusStateReset;
    ++faults_.state_resets;
    announce_restart();
    return;
  }
  if (c_.nav.t_s - c_.last_health_t_s >= kHealthPeriod_s) check_health(true);
}

void NavFilter::accumulate_stamp_jitter(const ImuIncrement& raw) {
  if (!(opt_.imu_stamp_jitter_s > 0.0) || !(raw.dt_s > 0.0)) return;
  const Vec3 omega = raw.dtheta_b_rad / raw.dt_s, f = raw.dvel_b_mps / raw.dt_s;
  if (c_.have_prev_rates) {
    // Increment k spans [t_k-1 + e_k-1, t_k + e_k] instead of [t_k-1, t_k]: summed, the errors telescope to
    // sum_k e_k (rate_k - rate_k+1), one independent term per sample, common to the three axes.
    const Mat3 C = c_.nav.C_b_n();
    const Vec3 d_omega_n = C * (omega - c_.prev_omega_b_rad_s), d_f_n = C * (f - c_.prev_f_b_mps2);
    const double var = opt_.imu_stamp_jitter_s * opt_.imu_stamp_jitter_s;
    c_.acc_jitter_att_n += var * d_omega_n * d_omega_n.transpose();
    c_.acc_jitter_vel_n += var * d_f_n * d_f_n.transpose();
  }
  c_.prev_omega_b_rad_s = omega;
  c_.prev_f_b_mps2 = f;
  c_.have_prev_rates = true;
}

void NavFilter::run_aids() {
  if (c_.updaters.empty()) return;
  const bool gnss_recent = c_.nav.t_s - c_.last_gnss_t_s < 1.0;
  // The linearisation point is taken only for an aid that measures, after the covariance is brought to this
  // epoch (which may move the effects' nominal states): due() does not look at it, and at 200 Hz taking it for
  // every sample cost 5 % of a run.
  LinearizationPoint lp;
  const auto context = [&] {
    return AidContext{c_.nav, lp, layout_, opt_, c_.P, c_.detector, c_.f_n_smooth_mps2,
                      gnss_recent, imu_noise_psd_scale().gyro, faults_};
  };
  std::vector<Measurement> measurements;
  for (UpdaterSlot& updater : c_.updaters) {
    if (!updater->due(context())) continue;
    flush_covariance();
    lp = linearization_point();
    measurements.clear();
    updater->measure(context(), measurements);
    for (const Measurement& m : measurements) apply_measurement(m);
  }
}

void NavFilter::propagate_sample(const ImuIncrement& raw_part) {
  const ImuIncrement inc = c_.model.correct(raw_part);
  const MechanizationStep& st = c_.mech.step(c_.nav, inc);
  const double dt = st.dt_s;
  c_.acc_T_s += dt;
  c_.acc_dv_n += st.dv_sf_n_mps;
  if (m_ > 0) accumulate_effect_inputs(st, dt);
  if (st.crossed_pole) turn_error_frame_over_pole();
}

void NavFilter::accumulate_effect_inputs(const MechanizationStep& st, double dt) {
  LinearizationPoint lp;
  lp.C_b_n = c_.nav.C_b_n();
  lp.omega_ib_b_rad_s = st.omega_ib_b_rad_s;
  lp.f_b_mps2 = st.f_b_mps2;
  const Mat3 Cdt = lp.C_b_n * dt;
  const auto& blocks = layout_.blocks();
  for (size_t i = 0; i < blocks.size(); ++i) {
    const StateBlock& b = blocks[i];
    const bool g = b.effect->drives_gyro(), a = b.effect->drives_accel();
    if (!g && !a) continue;
    b.effect->imu_jacobians(lp, J_gyro_[i], J_accel_[i]);
    const int o = b.offset - kNavDim;
    if (g) c_.acc_B.block(kAtt, o, 3, b.dim).noalias() -= Cdt * J_gyro_[i];
    if (a) c_.acc_B.block(kVel, o, 3, b.dim).noalias() += Cdt * J_accel_[i];
  }
}

// Over a pole the n frame turned 180 deg about down: the north and east parts of the position, velocity and attitude
// errors change sign (the covariance accumulated so far is brought in first, in the frame it was built in).
void NavFilter::turn_error_frame_over_pole() {
  flush_covariance();
  for (const int i : {kPos, kPos + 1, kVel, kVel + 1, kAtt, kAtt + 1}) {
    c_.P.row(i) *= -1.0;
    c_.P.col(i) *= -1.0;
  }
}

void NavFilter::flush_covariance() {
  const double T = c_.acc_T_s;
  if (T <= 0.0) return;
  // Nominal effect dynamics (e.g. a ramp integrating its rate).
  bool nominal_changed = false;
  for (const auto& b : layout_.blocks()) {
    auto seg = c_.x_eff.segment(b.offset - kNavDim, b.dim);
    const Eigen::VectorXd before = seg;
    b.effect->propagate_nominal(seg, T);
    nominal_changed |= (seg != before);
  }
  if (nominal_changed) rebuild_error_model();

  GravityCache& gc = c_.mech.gravity();
  Mat9 A = nav_error_F(c_.nav, Vec3::Zero(), gc.dg_dlat(), gc.dg_dh()) * T;
  A.block<3, 3>(kVel, kAtt) = skew(c_.acc_dv_n);  // sum of [f_n x] dt, exact under rotation
  Eigen::Matrix<double, 9, Eigen::Dynamic>& B = c_.acc_B;
  for (const auto& b : layout_.blocks())
    if (b.effect->drives_velocity_n()) {
      Mat3X J = Mat3X::Zero(3, b.dim);
      b.effect->velocity_n_jacobian(J);
      B.block(kVel, b.offset - kNavDim, 3, b.dim) += J * T;
    }

  // Phi = I + F T + (F T)^2 / 2 with F = [[A, B], [0, D]]; D, E = D + D^2/2 kept sparse.
  std::vector<Triplet> E;
  for (const Triplet& t : F_ee_) E.push_back({t.row, t.col, t.value * T});
  for (const Triplet& t1 : F_ee_)
    for (const Triplet& t2 : F_ee_)
      if (t1.col == t2.row) E.push_back({t1.row, t2.col, 0.5 * t1.value * t2.value * T * T});
  const Mat9 Phi_nn = Mat9::Identity() + A + 0.5 * A * A;
  Eigen::Matrix<double, 9, Eigen::Dynamic> Phi_ne = B + 0.5 * A * B;
  for (const Triplet& t : F_ee_) Phi_ne.col(t.col) += 0.5 * t.value * T * B.col(t.row);

  Eigen::MatrixXd& P = c_.P;
  const int m = m_;
  const Mat9 Pnn = P.topLeftCorner<9, 9>();
  const Eigen::Matrix<double, 9, Eigen::Dynamic> Pne = P.topRightCorner(9, m);
  const Eigen::Matrix<double, 9, Eigen::Dynamic> Y = Phi_nn * Pne;
  const Eigen::Matrix<double, 9, Eigen::Dynamic> Z = Phi_ne * P.bottomRightCorner(m, m);
  Mat9 Pnn_new = Phi_nn * Pnn * Phi_nn.transpose();
  if (m > 0) {
    const Mat9 YPt = Y * Phi_ne.transpose();
    Pnn_new += YPt + YPt.transpose() + Z * Phi_ne.transpose();
  }
  Eigen::Matrix<double, 9, Eigen::Dynamic> X = Y + Z;
  Eigen::Matrix<double, 9, Eigen::Dynamic> Pne_new = X;
  for (const Triplet& t : E) Pne_new.col(t.row) += t.value * X.col(t.col);
  if (!E.empty()) {
    auto Pee = P.bottomRightCorner(m, m);
    Eigen::MatrixXd W = Pee;
    for (const Triplet& t : E) W.row(t.row) += t.value * Pee.row(t.col);
    Eigen::MatrixXd V = W;
    for (const Triplet& t : E) V.col(t.row) += t.value * W.col(t.col);
    Pee = V;
  }
  P.topLeftCorner<9, 9>() = Pnn_new;
  P.topRightCorner(9, m) = Pne_new;
  P.bottomLeftCorner(m, 9) = Pne_new.transpose();

  // Process noise: sensor white noise rotated into n, effect driving noise.
  const Mat3 C = c_.nav.C_b_n();
  Eigen::MatrixXd Qd;
  const bool want = observer_.p && observer_.p->wants_matrices();
  const ImuNoiseScale q_scale = imu_noise_psd_scale();
  Mat3 Qv = C * opt_.vrw_mps_per_sqrt_s.cwiseAbs2().asDiagonal() * C.transpose() * (T * q_scale.accel);
  if (opt_.gyro_quantization_rad.any() && T > 0.0) {
    // The gyros' Q, a white error e of the integrated angle, tilts the specific force: each IMU sample of
    // tau0 adds f x e tau0 to the velocity error, a random walk of density [f x] Sigma_e [f x]^T tau0.
    const Mat3 f_cross = skew(c_.acc_dv_n / T);
    Qv += f_cross * est::attitude_quantization_cov_n(C, opt_.gyro_quantization_rad) * f_cross.transpose() *
          (T * c_.imu_interval_s);
  }
  Mat3 Qp = C * opt_.arw_rad_per_sqrt_s.cwiseAbs2().asDiagonal() * C.transpose() * (T * q_scale.gyro);
  Qv += c_.acc_jitter_vel_n;
  Qp += c_.acc_jitter_att_n;
  c_.acc_jitter_vel_n.setZero();
  c_.acc_jitter_att_n.setZero();
  P.block<3, 3>(kVel, kVel) += Qv;
  P.block<3, 3>(kAtt, kAtt) += Qp;
  P.diagonal().tail(m) += q_c_ * T;
  if (want) {
    const int n = kNavDim + m;
    Eigen::MatrixXd Phi = Eigen::MatrixXd::Identity(n, n);
    Phi.topLeftCorner<9, 9>() = Phi_nn;
    Phi.topRightCorner(9, m) = Phi_ne;
    for (const Triplet& t : E) Phi(kNavDim + t.row, kNavDim + t.col) += t.value;
    Qd = Eigen::MatrixXd::Zero(n, n);
    Qd.block<3, 3>(kVel, kVel) = Qv;
    Qd.block<3, 3>(kAtt, kAtt) = Qp;
    Qd.diagonal().tail(m) = q_c_ * T;
    observer_.p->on_propagation(c_.nav.t_s, T, Phi, Qd);
  }

  c_.acc_T_s = 0.0;
  c_.acc_dv_n.setZero();
  B.setZero();
  check_health(false);
}

LinearizationPoint NavFilter::linearization_point() const {
  LinearizationPoint lp;
  const MechanizationStep& st = c_.mech.last();
  lp.C_b_n = c_.nav.C_b_n();
  lp.omega_ib_b_rad_s = st.omega_ib_b_rad_s;
  lp.f_b_mps2 = st.f_b_mps2;
  lp.a_n_mps2 = st.a_n_mps2;
  lp.lever_arm_b_m = c_.model.lever_arm_b_m;
  lp.gnss_position_bias_n_m = c_.model.gnss_position_bias_n_m;
  lp.omega_in_n_rad_s = earth::omega_ie_n(c_.nav.pos.lat_rad) +
                        earth::omega_en_n(c_.nav.pos.lat_rad, c_.nav.pos.h_m, c_.nav.v_n_mps);
  lp.v_ant_n_mps = antenna_velocity_n(c_.nav, lp);
  lp.v_n_mps = c_.nav.v_n_mps;
  lp.omega_nb_b_rad_s = st.omega_ib_b_rad_s - lp.C_b_n.transpose() * lp.omega_in_n_rad_s;
  lp.C_b_v = C_b_v_coarse_ * C_b_n_from_euler(c_.model.vehicle_mounting_rad);
  lp.odometer_lever_arm_b_m = c_.model.odometer_lever_arm_b_m;
  lp.odometer_scale = c_.model.odometer_scale;
  return lp;
}

void NavFilter::add_gnss(const GnssFix& fix) { add_observation(std::make_shared<GnssFixObservation>(fix)); }

void NavFilter::add_observation(ObservationPtr obs) {
  if (!obs || !obs->valid()) {
    c_.status |= kStatusMeasurementRejected;
    ++faults_.measurements_rejected;
    return;
  }
  if (!c_.initialized) return;
  const Event e{next_event_id_++, 0.0, std::move(obs)};
  if (e.t_s() - c_.model.time_offset_s >= c_.nav.t_s - kSplitTolerance_s) {
    enqueue(e);
    return;
  }
  rewind_and_apply(e);
  settle_suspect_fix();
}

void NavFilter::drop_queued_gnss_after(double t_s) {
  std::erase_if(pending_, [t_s](const Event& e) {
    return e.t_s() > t_s && dynamic_cast<const GnssFixObservation*>(e.obs.get()) != nullptr;
  });
}

void NavFilter::enqueue(const Event& e) {
  const auto at =
      std::upper_bound(pending_.begin(), pending_.end(), e.t_s(), [](double t, const Event& g) { return t < g.t_s(); });
  pending_.insert(at, e);
}

void NavFilter::rewind_and_apply(const Event& event) {
  const double t_apply = event.t_s() - c_.model.time_offset_s;
  int k = static_cast<int>(snapshots_.size()) - 1;
  while (k >= 0 && snapshots_[k].nav.t_s > t_apply + kSplitTolerance_s) --k;
  if (k < 0 || opt_.history_s <= 0.0 || t_apply < c_.nav.t_s - opt_.history_s - kSplitTolerance_s) {
    c_.status |= kStatusLateDropped;
    ++faults_.late_dropped;
    return;
  }
  enqueue(event);  // applied at its epoch in the replay, with the readings applied since the snapshot
  replay_from_snapshot(k, -1);
}

void NavFilter::replay_from_snapshot(int k, long excluded_id) {
  // Readings applied now but not contained in the snapshot are applied again, in order.
  const std::deque<Event> applied_now = c_.applied;
  c_ = snapshots_[k];
  announce_restart();  // an observer's records after the snapshot no longer hold
  snapshots_.erase(snapshots_.begin() + k + 1, snapshots_.end());
  for (const Event& a : applied_now) {
    const bool in_snapshot =
        std::any_of(c_.applied.begin(), c_.applied.end(), [&](const Event& b) { return b.id == a.id; });
    if (!in_snapshot && a.id != excluded_id) enqueue(a);
  }
  const double t_snap = c_.nav.t_s;
  const bool was_replaying = replaying_;
  replaying_ = true;
  for (const ImuIncrement& raw : imu_history_)
    if (raw.t_s > t_snap + 1e-9) {
      process_imu(raw);
      take_snapshot();
    }
  replaying_ = was_replaying;
}

void NavFilter::settle_suspect_fix() {
  if (suspect_to_settle_ < 0 || trying_branch_) return;
  const long suspect = suspect_to_settle_, rejected = rejected_after_suspect_;
  suspect_to_settle_ = rejected_after_suspect_ = -1;
  if (retract_suspect_fix(suspect, rejected)) ++faults_.fixes_retracted;
}

bool NavFilter::retract_suspect_fix(long suspect_id, long rejected_id) {
  // A GNSS fix taken in at the edge of the gate (NIS above its 99 % quantile) or right after a rejected one, and
  // the next one rejected: either
  // the state has left the fixes (the ones after will confirm it and re-synchronise), or the edge fix was an
  // outlier that moved the state (a MEMS IMU's tilt, wide after a rejected fix, took a 1.2 m jump as 2.4 deg of
  // pitch, and drifted 6 m before the re-synchronisation). Try the state without it: if the rejected fix fits
  // there (NIS within the 99 % quantile, not just the gate), the edge fix was the outlier; keep that branch.
  int k = static_cast<int>(snapshots_.size()) - 1;
  const auto holds_suspect = [&](const Core& snap) {
    return std::any_of(snap.applied.begin(), snap.applied.end(), [&](const Event& e) { return e.id == suspect_id; });
  };
  while (k >= 0 && holds_suspect(snapshots_[k])) --k;
  const bool suspect_applied =
      std::any_of(c_.applied.begin(), c_.applied.end(), [&](const Event& e) { return e.id == suspect_id; });
  if (k < 0 || !suspect_applied) return false;  // beyond the history kept
  // The trial, on a copy of everything a replay changes, with no observer and no records kept.
  const Core saved = c_, saved_last_good = last_good_;
  const std::deque<Core> saved_snapshots = snapshots_;
  const std::deque<Event> saved_pending = pending_;
  const FaultCounters saved_faults = faults_;
  const size_t saved_records = innovations_.size();
  FilterObserver* const observer = observer_.p;
  observer_.p = nullptr;
  trying_branch_ = true;
  rejected_after_suspect_ = rejected_id;
  trial_fits_ = false;
  replay_from_snapshot(k, suspect_id);
  const bool fits_without = trial_fits_;
  trying_branch_ = false;
  rejected_after_suspect_ = -1;
  c_ = saved, last_good_ = saved_last_good, snapshots_ = saved_snapshots, pending_ = saved_pending;
  faults_ = saved_faults;
  innovations_.resize(saved_records);
  observer_.p = observer;
  if (!fits_without) return false;
  replay_from_snapshot(k, suspect_id);                // for real: the observer sees the restart and the replay
  suspect_to_settle_ = rejected_after_suspect_ = -1;  // one retraction per rejection, not a cascade from the replay
  return true;
}

void NavFilter::apply_next_pending() {
  flush_covariance();
  const Event event = pending_.front();
  pending_.pop_front();
  apply_event(event);
}

void NavFilter::apply_event(const Event& e) {
  applying_event_id_ = e.id;
  Event applied = e;
  applied.t_apply_s = c_.nav.t_s;
  c_.applied.push_back(applied);
  while (!c_.applied.empty() && c_.applied.front().t_apply_s < c_.nav.t_s - kept_history_s()) c_.applied.pop_front();
  const int n = e.obs->measurement_count(opt_);
  for (int i = 0; i < n; ++i) {
    const LinearizationPoint lp = linearization_point();
    apply_measurement(e.obs->measurement(i, MeasurementContext{c_.nav, lp, layout_, opt_}));
  }
}

void NavFilter::reopen_accel_errors_to_prior() {
  for (const StateBlock& b : layout_.blocks()) {
    if (!b.effect->drives_accel()) continue;
    Eigen::VectorXd mean(b.dim), std(b.dim);
    block_prior(b, mean, std);  // as configured, ldv.priors included
    for (int i = 0; i < b.dim; ++i) {
      double& var = c_.P(b.offset + i, b.offset + i);
      var = std::max(var, std[i] * std[i]);  // a larger diagonal keeps P positive definite
    }
  }
}

NavFilter::RejectRun& NavFilter::reject_run(SensorName sensor) {
  for (RejectRun& r : c_.reject_runs)
    if (r.sensor == sensor) return r;
  c_.reject_runs.push_back(RejectRun{sensor, 0, 0.0, {}, {}});
  return c_.reject_runs.back();
}

void NavFilter::apply_measurement(const Measurement& given) {
  // The GNSS position variance as configured (gnss_variance_scale) and adapted (split_noise_adaptation): the gate
  // judges against it too.
  const bool gnss_position = given.sensor == sensors::kGnssPosition;
  const bool split = opt_.adapt_imu_noise && opt_.split_noise_adaptation && gnss_position;
  const int gnss_class = std::clamp(given.gnss_class, 0, NoiseAdaptation::kGnssClasses - 1);
  const double variance_scale = (gnss_position ? opt_.gnss_variance_scale[gnss_class] : 1.0) *
                                (split ? c_.noise_adaptation.gnss_scale(gnss_class) : 1.0);
  std::optional<Measurement> rescaled;
  if (variance_scale != 1.0) {
    rescaled = given;
    rescaled->R *= variance_scale;
  }
  const Measurement& m = rescaled ? *rescaled : given;
  RejectRun& run = reject_run(m.sensor);
  if (run.last_y.size() != m.y.size()) run.last_y = Eigen::VectorXd::Zero(m.y.size());
  const double gate = opt_.gate_measurements ? gate_threshold(m.rows()) : std::numeric_limits<double>::infinity();
  // Robust: a step is confirmed by two or more measurements beyond the gate in a row, spanning
  // step_confirm_s (a spike of multipath is shorter); KF-GINS: after a count of rejections. Only sensors
  // whose measured quantity can step (m.step_block) are ever forced.
  const bool due =
      m.step_block >= 0 &&
      (opt_.robust_update ? run.count >= 2 && c_.nav.t_s - run.first_t_s >= opt_.step_confirm_s - kSplitTolerance_s
                          : run.count >= opt_.gate_max_consecutive_rejects);
  // Re-synchronise only on a measurement that agrees with the rejected stream: a stream the state has left
  // repeats itself (the innovation changes by the drift since), a lone outlier arriving when it is due does not.
  // The reference is the last rejection before it was due (frozen then, so that outlier does not become it), or
  // the one held back just before this one: a state that keeps drifting away (an initial tilt stated 100x too
  // small: the position error grows as t^2) soon leaves the frozen reference behind, and two in a row that agree
  // are the stream.
  const auto agrees_with = [&](const Eigen::VectorXd& reference) {
    return reference.size() == m.y.size() &&
           (m.y - reference).norm() <= 0.5 * reference.norm() + 3.0 * std::sqrt(m.R.trace());
  };
  const bool force = due && (agrees_with(run.last_y) || agrees_with(run.held_y));
  InnovationRecord rec;
  rec.t_s = c_.nav.t_s;
  rec.replayed = replaying_;
  const bool want = observer_.p && observer_.p->wants_matrices();
  const Eigen::VectorXd var_before = (force && want) ? Eigen::VectorXd(c_.P.diagonal()) : Eigen::VectorXd();
  if (force) {
    // Re-synchronise: the state has diverged from a measurement stream it kept rejecting, so open the
    // measured block's variance by the innovation before accepting.
    c_.P.diagonal().segment(m.step_block, m.rows()) += m.y.cwiseAbs2();
    if (m.sensor == sensors::kGnssPosition) {
      // A position error y that built up over the T seconds since the last accepted fix comes from velocity
      // errors of order 2 y / T or tilt errors of order 2 |y| / (g T^2): open those too, or the state leaves
      // the measurements again at once.
      const double T = std::max(c_.nav.t_s - c_.last_gnss_t_s, 0.1);
      const double y_h_m = m.y.head<2>().norm();
      c_.P.diagonal().segment<3>(kVel) += (2.0 * m.y / T).cwiseAbs2();
      const double tilt_rad = std::min(2.0 * y_h_m / (earth::kStandardGravity_mps2 * T * T), 0.1);
      c_.P(kAtt, kAtt) += tilt_rad * tilt_rad;
      c_.P(kAtt + 1, kAtt + 1) += tilt_rad * tilt_rad;
      // A heading error psi turns the horizontal velocity change dv since then into an error psi x dv, a position
      // error of order psi |dv| T / 2. Opened where a heading error up to the re-alignment's threshold explains y
      // (without it, a heading 5 deg off stated 0.05 deg left the fixes again and again, and each forced fix
      // tilted the attitude instead: 1 deg).
      const double dv_h_mps = (c_.nav.v_n_mps - c_.v_n_at_last_gnss_mps).head<2>().norm();
      const double heading_rad = 2.0 * y_h_m / std::max(dv_h_mps * T, 1e-9);
      // Beyond the threshold y needs more than a heading error; but where a heading error at the threshold moves the
      // position measurably (beyond 3 sigma of the fix), part of y may still be one: opened so that its 3 sigma
      // reaches the threshold, beyond which the session's heading check re-aligns (a 27 deg heading error stated
      // 0.05 deg, with the tilt and along-track errors in y too, was left at 2 deg sigma 30 deg off: 25 fixes
      // rejected over the drive with the split adaptation, 15 since).
      const double heading_reach_m = kMaxResyncHeading_rad * dv_h_mps * T / 2.0;
      const bool heading_measurable = heading_reach_m > 3.0 * std::sqrt(m.R(0, 0) + m.R(1, 1));
      if (heading_rad <= kMaxResyncHeading_rad)
        c_.P(kAtt + 2, kAtt + 2) += heading_rad * heading_rad;
      else if (heading_measurable)
        c_.P(kAtt + 2, kAtt + 2) += std::pow(kMaxResyncHeading_rad / 3.0, 2);
      // Where no heading error explains y, a tilt does: until the fixes were rejected they were explained with the
      // tilt held at its stated variance, and the accelerometer errors took its specific force (g tilt) in its
      // place. What those blocks learnt then goes back to their turn-on uncertainty, or the attitude settles where
      // the wrong biases put it (a 0.8 deg roll stated 0.01 deg: 0.16 deg off at the end of a drive). Not where a
      // heading explains y: a reopened lateral bias would take the heading's acceleration error (psi a) instead.
      if (heading_rad > kMaxResyncHeading_rad) reopen_accel_errors_to_prior();
    }
    if (want) {  // to an observer, the opened variance is process noise of an instant
      const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(c_.P.rows(), c_.P.cols());
      observer_.p->on_propagation(c_.nav.t_s, 0.0, I, Eigen::MatrixXd((c_.P.diagonal() - var_before).asDiagonal()));
    }
  }
  const bool ok = kalman_update(c_.P, m, {gate, opt_.robust_update, force}, rec, dx_, want ? &K_ : nullptr);
  const bool beyond_gate = !force && rec.nis > gate;
  if (ok) correct(dx_);
  // A fix beyond the gate that repeats the one before it is a state the fixes have left (a step, a misstated
  // initial attitude drifting away: the re-synchronisation's to take up), not a sample of their noise.
  const bool repeats_a_rejection = beyond_gate && run.count > 0 && (agrees_with(run.last_y) || agrees_with(run.held_y));
  // (Split, such a fix moves neither factor; it once fell through to the one-factor rule, which took the IMU noise
  // to 6x for a fix interval on a MEMS drive whose fixes stated a fifth of their std.)
  if (split) {
    if (!force && !repeats_a_rejection) adapt_noise(rec, m.R, m.gnss_class);
  } else if (opt_.adapt_imu_noise && m.sensor == sensors::kGnssPosition && !force) {
    adapt_imu_noise(rec);
  }
  if (ok && force) {
    c_.status |= kStatusGateResync;
    ++faults_.gate_resyncs;
  }
  // Used: within the gate, forced, or kept by the robust update with at least a quarter of its weight.
  const bool used = rec.used();
  if (ok && beyond_gate) ++faults_.downweighted;
  if (m.sensor == sensors::kGnssPosition && opt_.robust_update) note_gnss_position_outcome(rec, force, beyond_gate);
  if (used && m.gnss) {
    c_.last_gnss_t_s = c_.nav.t_s;
    c_.v_n_at_last_gnss_mps = c_.nav.v_n_mps;
    c_.status &= ~(kStatusGnssRejected | kStatusGateResync);
  }
  if (!beyond_gate) {
    run.count = 0;
    run.held_y.resize(0);
  } else {
    if (run.count++ == 0) run.first_t_s = c_.nav.t_s;
    if (!due) run.last_y = m.y;  // an outlier held back must not become the reference
    run.held_y = due ? m.y : Eigen::VectorXd();
  }
  if (!used) {
    ++faults_.gate_rejections;
    if (m.gnss) c_.status |= kStatusGnssRejected;
  }
  innovations_.push_back(rec);
  if (want) observer_.p->on_update(rec, m.H, K_);
  check_health(false);
}

void NavFilter::note_gnss_position_outcome(const InnovationRecord& rec, bool forced, bool beyond_gate) {
  const bool at_edge = rec.nis > gate_edge(static_cast<int>(rec.innovation.size()));
  if (trying_branch_) {
    if (applying_event_id_ == rejected_after_suspect_) trial_fits_ = !beyond_gate && !at_edge;
    return;
  }
  if (beyond_gate && c_.gnss_suspect_id >= 0)
    suspect_to_settle_ = c_.gnss_suspect_id, rejected_after_suspect_ = applying_event_id_;
  // Suspect: taken in at the gate's edge, or right after a rejected fix (outliers come in runs, and the state is
  // a fix interval more uncertain then: a 0.8 m jump at NIS 9 wrecked a MEMS solution as one at NIS 15 did).
  c_.gnss_suspect_id =
      (!forced && !beyond_gate && (at_edge || c_.last_gnss_position_rejected)) ? applying_event_id_ : -1;
  c_.last_gnss_position_rejected = beyond_gate && !forced;
}

void NavFilter::adapt_imu_noise(const InnovationRecord& rec) {
  // Hold the position NIS at its expectation (3) by scaling the IMU white noise: a stochastic
  // approximation in ln(scale), each fix nudging it by kNoiseAdaptGain (NIS / 3 - 1). The NIS is capped
  // at the gate so that an outlier, which the robust update already discounts, moves it little; the
  // scale never drops below 1 (the configured noise is the floor) nor exceeds kMaxImuNoiseScale.
  const double nis = std::min(rec.nis, gate_threshold(3));
  const double step = kNoiseAdaptGain * (nis / 3.0 - 1.0);
  c_.imu_noise_scale = std::clamp(c_.imu_noise_scale * std::exp(step), 1.0, kMaxImuNoiseScale);
  note_imu_noise_peak();
}

void NavFilter::note_imu_noise_peak() {
  if (c_.imu_noise_scale > imu_noise_peak_.scale) imu_noise_peak_ = {c_.imu_noise_scale, c_.nav.t_s};
}

void NavFilter::adapt_noise(const InnovationRecord& rec, const Eigen::MatrixXd& R_used, int gnss_class) {
  // The prediction's part of S (rec.S is H P H^T + R before any robust inflation); the innovation capped at the
  // gate, so that an outlier the robust update discounts moves the factors little.
  const Eigen::MatrixXd A = rec.S - R_used;
  const double gate = gate_threshold(static_cast<int>(rec.innovation.size()));
  const double cap = rec.nis > gate ? std::sqrt(gate / rec.nis) : 1.0;
  c_.noise_adaptation.add_fix(c_.nav.t_s, A, R_used, rec.innovation * cap, gnss_class);
  c_.imu_noise_scale = c_.noise_adaptation.imu_scale();
  note_imu_noise_peak();
}

bool NavFilter::fill_unset_white_noise(const Vec3& arw_rad_per_sqrt_s, const Vec3& vrw_mps_per_sqrt_s) {
  bool filled = false;
  for (int axis = 0; axis < 3; ++axis) {
    for (auto [configured, given] : {std::pair{&opt_.arw_rad_per_sqrt_s(axis), arw_rad_per_sqrt_s(axis)},
                                     std::pair{&opt_.vrw_mps_per_sqrt_s(axis), vrw_mps_per_sqrt_s(axis)}}) {
      if (*configured == 0.0 && std::isfinite(given) && given > 0.0) *configured = given, filled = true;
    }
  }
  return filled;
}

void NavFilter::set_imu_noise_floor(const ImuNoiseScale& psd_floor) {
  if (std::isfinite(psd_floor.gyro)) c_.imu_noise_floor.gyro = std::clamp(psd_floor.gyro, 1.0, kMaxImuNoiseScale);
  if (std::isfinite(psd_floor.accel)) c_.imu_noise_floor.accel = std::clamp(psd_floor.accel, 1.0, kMaxImuNoiseScale);
  if (std::isfinite(psd_floor.gyro) || std::isfinite(psd_floor.accel)) c_.noise_adaptation.set_imu_noise_measured();
  reset_static_detector();
}

void NavFilter::set_standstill_f_scatter(double f_scatter_mps2) {
  if (std::isfinite(f_scatter_mps2) && f_scatter_mps2 >= 0.0) c_.standstill_f_scatter_mps2 = f_scatter_mps2;
  reset_static_detector();
}

void NavFilter::reset_static_detector() {
  // The ZUPT's static detector allows for the IMU's noise as installed (the floor, and the scatter of |f| a
  // standstill showed): with the datasheet's, an IMU vibrating at 10x never looked static, and a tactical one
  // stopped in a GNSS outage drifted 80 m in 30 s.
  c_.detector = StaticDetector(opt_.zupt.window_s, opt_.zupt.f_std_mps2, opt_.zupt.omega_max_rad_s,
                               opt_.vrw_mps_per_sqrt_s.maxCoeff() * std::sqrt(c_.imu_noise_floor.accel),
                               opt_.arw_rad_per_sqrt_s.maxCoeff() * std::sqrt(c_.imu_noise_floor.gyro),
                               c_.standstill_f_scatter_mps2);
}

void NavFilter::correct(const Eigen::VectorXd& dx) {
  c_.nav.pos = earth::offset_ned(c_.nav.pos, -dx.segment<3>(kPos));
  c_.nav.v_n_mps -= dx.segment<3>(kVel);
  // C_hat = (I - [phi x]) C  =>  C = exp([phi x]) C_hat
  c_.nav.q_b_n = (quat_from_rotvec(dx.segment<3>(kAtt)) * c_.nav.q_b_n).normalized();
  if (m_ > 0) {
    c_.x_eff -= dx.tail(m_);
    rebuild_error_model();
  }
}

namespace {
// Positive semi-definite: the states with a variance hold a positive definite block, and a state with none (a
// term the configuration states as exactly known, std 0 and no process noise) is uncorrelated with all.
bool positive_semidefinite(const Eigen::MatrixXd& P) {
  std::vector<int> uncertain;
  for (int i = 0; i < P.rows(); ++i) {
    if (P(i, i) > 0.0)
      uncertain.push_back(i);
    else if ((P.row(i).array() != 0.0).any())
      return false;
  }
  return Eigen::LLT<Eigen::MatrixXd>(P(uncertain, uncertain)).info() == Eigen::Success;
}
}  // namespace

void NavFilter::check_health(bool full) {
  const Eigen::MatrixXd& P = c_.P;
  bool ok = P.diagonal().allFinite() && (P.diagonal().array() >= 0.0).all();
  if (ok && full) {
    c_.last_health_t_s = c_.nav.t_s;
    ok = P.allFinite() && positive_semidefinite(P);
    if (ok && usable(c_.nav)) last_good_ = c_;
  }
  if (!ok) reset_covariance();
}

void NavFilter::reset_covariance() {
  // Keep each variance that is still usable, otherwise fall back to the prior; drop the correlations.
  const int n = kNavDim + m_;
  Eigen::VectorXd var(n);
  const NavStd fallback;
  Eigen::VectorXd prior(n);
  prior << Vec3::Constant(10.0), Vec3::Constant(1.0), Vec3::Constant(5.0 * kDegToRad), prior_std_;
  for (int i = 0; i < n; ++i) {
    const double d = c_.P(i, i);
    // A state known exactly (prior std 0) stays so; any other lost variance falls back to the prior.
    var(i) = (std::isfinite(d) && d > 0.0) ? std::max(d, 1e-12) : prior(i) * prior(i);
  }
  c_.P = var.asDiagonal();
  c_.status |= kStatusCovarianceReset;
  ++faults_.covariance_resets;
  announce_restart();
}

void NavFilter::announce_restart() {
  // P belongs to the last covariance epoch, which lags the state by the samples accumulated since.
  if (observer_.p && observer_.p->wants_matrices()) observer_.p->on_restart(c_.nav.t_s - c_.acc_T_s, c_.P);
}

void NavFilter::set_covariance(const Eigen::MatrixXd& P) {
  const int n = kNavDim + m_;
  if (P.rows() != n || P.cols() != n) throw std::invalid_argument("covariance of the wrong size");
  c_.P = P;
  announce_restart();
  check_health(true);
}

NavStd NavFilter::nav_std() const {
  NavStd s;
  const Eigen::Matrix<double, kNavDim, 1> var = c_.P.diagonal().head<kNavDim>().cwiseMax(0.0);
  s.pos_ned_m = var.segment<3>(kPos).cwiseSqrt();
  s.vel_n_mps = var.segment<3>(kVel).cwiseSqrt();
  s.att_rad = (var.segment<3>(kAtt) + attitude_quantization_cov_n().diagonal()).cwiseSqrt();
  return s;
}

Mat3 attitude_quantization_cov_n(const Mat3& C_b_n, const Vec3& gyro_quantization_rad) {
  return C_b_n * gyro_quantization_rad.cwiseAbs2().asDiagonal() * C_b_n.transpose();
}

Mat3 NavFilter::attitude_quantization_cov_n() const {
  return est::attitude_quantization_cov_n(c_.nav.C_b_n(), opt_.gyro_quantization_rad);
}

std::vector<InnovationRecord> NavFilter::take_innovations() {
  std::vector<InnovationRecord> out;
  out.swap(innovations_);
  return out;
}

}  // namespace ldv::est
