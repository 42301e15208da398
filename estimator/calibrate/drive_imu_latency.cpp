#include "estimator/calibrate/drive_imu_latency.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/math/chi_square.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"

namespace ldv::est {
namespace {

// The drive the decision is made on, and what it decides (the names the decision's steps read them by).
struct Drive {
  std::vector<ImuIncrement>& imu;  // shifted in place when a lag is taken out
  const std::vector<GnssFix>& gnss;
  const KfGinsConfig& config;
  const FilterOptions& options;
  bool refine_in_filter;
  DriveImuLatency& decision;
};

std::vector<ImuIncrement> shifted(std::vector<ImuIncrement> imu, double lag_s) {
  for (ImuIncrement& s : imu) s.t_s -= lag_s;
  return imu;
}

// How much IMU noise the filter needs to follow the fixes over these IMU samples: the geometric mean over the
// run of the adapted noise scale, from the configured noise up (FilterOptions::adapt_imu_noise holds the
// position NIS at its expectation, so a model that misses something shows as noise). Positions only (a GNSS
// velocity's own lag would take sides); a run that cannot start counts as the largest scale.
double imu_noise_needed(const Drive& in, const std::vector<ImuIncrement>& imu) {
  FilterOptions o = in.options;
  o.use_gnss_velocity = false;
  o.adapt_imu_noise = true;
  o.installed_noise_floor = false;  // the adapted factor alone: a floor above what both runs need would tie them
  NavFilter filter(o);
  double sum_log = 0.0;
  long n = 0;
  RunCallbacks cb;
  cb.on_epoch = [&](const NavFilter& f) {
    sum_log += std::log(f.imu_noise_scale());
    ++n;
  };
  try {
    run_navigation(imu, in.gnss, in.config, filter, cb);
  } catch (const std::exception&) {
    return 1e300;
  }
  return n > 0 ? std::exp(sum_log / static_cast<double>(n)) : 1e300;
}

// A lag within what a forward lever arm could explain is taken when the filter needs this much less IMU noise
// with it (a 1.5 m lever arm at 10 m/s taken for 150 ms would make the fit worse, not better),
constexpr double kLagNoiseGain = 0.7;
// or when the GNSS positions' likelihood at the noise the data need rises by more than a 1-parameter test at
// 99.9 % allows (-2 ln L falls by 10.8): under vibration both runs need the vibration's noise and the noise test
// cannot tell (a 3DM-GX2 at 10x: 69.5x with the 77 ms lag, 70.2x without), while the likelihood can (-2 ln L
// 66 lower with it; a 1.2 m forward lever arm taken for 138 ms: 162 higher).
constexpr double kLagLikelihoodGain = DriveImuLatency::kLikelihoodTest;

// -2 ln L of the GNSS positions as a function of a shift of the IMU stamps: sum over the fixes of NIS + ln det S
// (positions only, an outlier counted as at the filter's gate), each pass with the IMU shifted exactly and the IMU
// noise held at what a pass at the current stamps adapted to. The fixes compared are the first pass's: a fix a
// later pass did not update with (it lost the track and waited to align again: the real walk at the turns' 406
// ms) counts as an outlier at the gate with the first pass's ln det S, so a pass that fails is worse, not
// incomparable.
class ShiftLikelihood {
 public:
  explicit ShiftLikelihood(const Drive& in) : in_(in), o_(in.options) {
    o_.use_gnss_velocity = false;  // positions only: a GNSS velocity's own lag would take sides
    gate_ = math::chi_square_quantile(o_.gate_probability, 3);
    ImuNoiseScale q;
    if (!pass(0.0, &q)) return;  // the run itself will say what is wrong
    t0_ = terms_.front().t_s + 5.0, t1_ = terms_.back().t_s - 1.0;
    have_zero_ = !o_.adapt_imu_noise;  // the pass at 0 is then the one the scan would make
    if (o_.adapt_imu_noise) {
      o_.arw_rad_per_sqrt_s *= std::sqrt(q.gyro);
      o_.vrw_mps_per_sqrt_s *= std::sqrt(q.accel);
      o_.adapt_imu_noise = false;
    }
    ok_ = true;
  }
  bool ok() const { return ok_; }
  const FilterOptions& options() const { return o_; }
  // NaN when the pass failed.
  double cost(double lag_s) {
    if (!ok_) return NAN;
    const bool reuse = have_zero_ && lag_s == 0.0 && !zero_used_;
    if (reuse) zero_used_ = true;
    if (!reuse && !pass(lag_s, nullptr)) return NAN;
    return summed_terms();
  }
  // -2 ln L at the stamps as they are with an effect the model does not hold added (estimated by the filter on
  // the way), over the same fixes: what that effect explains instead of a lag. NaN as cost().
  double cost_with(const std::string& effect) {
    if (!ok_) return NAN;
    const FilterOptions plain = o_;
    o_.add.push_back(effect);
    const bool ran = pass(0.0, nullptr);
    o_ = plain;
    zero_used_ = true;  // the pass at 0 is no longer the plain one
    return ran ? summed_terms() : NAN;
  }

 private:
  // The last pass's -2 ln L over the first pass's fixes in the compared span.
  double summed_terms() {
    if (reference_.empty())
      for (const Term& x : terms_)
        if (x.t_s >= t0_ && x.t_s <= t1_) reference_.push_back(x);
    double sum = 0.0;
    auto it = terms_.begin();
    for (const Term& ref : reference_) {
      while (it != terms_.end() && it->t_s < ref.t_s - kSameFix_s) ++it;
      const bool used = it != terms_.end() && std::abs(it->t_s - ref.t_s) <= kSameFix_s;
      sum += used ? it->capped_nis + it->log_det_s : gate_ + ref.log_det_s;
    }
    return sum;
  }
  bool pass(double lag_s, ImuNoiseScale* noise) {
    terms_.clear();
    RunCallbacks cb;
    cb.on_innovation = [&](const InnovationRecord& r) {
      if (r.sensor != sensors::kGnssPosition || r.replayed) return;
      const Eigen::LLT<Eigen::MatrixXd> llt(r.S);
      if (llt.info() != Eigen::Success) return;
      const Eigen::MatrixXd L = llt.matrixL();
      terms_.push_back({r.t_s, std::min(r.nis, gate_), 2.0 * L.diagonal().array().log().sum()});
    };
    try {
      NavFilter filter(o_);
      run_navigation(shifted(in_.imu, lag_s), in_.gnss, in_.config, filter, cb);
      if (noise) *noise = filter.imu_noise_psd_scale();
    } catch (const std::exception&) {
      return false;
    }
    return !terms_.empty();
  }

  const Drive& in_;
  FilterOptions o_;
  double gate_ = 0.0, t0_ = 0.0, t1_ = 0.0;
  struct Term {
    double t_s, capped_nis, log_det_s;
  };
  static constexpr double kSameFix_s = 1e-4;  // a fix's time in every pass (the GNSS stamps are not shifted)
  std::vector<Term> terms_, reference_;
  bool ok_ = false, have_zero_ = false, zero_used_ = false;
};

// What is left of a latency taken out (its sigma: 1-12 ms, i.e. decimetres at road speed in every turn) is
// estimated by the likelihood of the GNSS positions as a function of a further shift of the IMU stamps: a few
// filter passes, each with the IMU shifted exactly, -2 ln L = sum over the fixes of NIS + ln det S (positions
// only, the same fixes in every pass, the IMU noise held at what a pass at the turns' lag adapted to), plus the
// prior (below); a parabola through the passes gives the lag and its sigma.
// Not a time_offset state: its Jacobian is the filter's own velocity, whose error is correlated with the
// position innovations; under vibration that drove the estimate late by 5-26 ms at a 4.6 ms sigma (a MEMS IMU
// standing still drifted 8-110 ms). The shift is taken out of the stamps when the scan knows it better than
// the turns did and agrees with its prior (4 sigma).
void refine_latency_with_filter(const Drive& in) {
  if (!in.refine_in_filter) return;
  const std::vector<std::string> model = resolve_model(in.options.model, in.options.add, in.options.drop);
  if (std::find(model.begin(), model.end(), "time_offset") != model.end()) return;  // the user's own
  if (std::find(in.options.drop.begin(), in.options.drop.end(), "time_offset") != in.options.drop.end()) return;
  // The prior: 0 with twice the turns' sigma, which under vibration is about half their real scatter (3DM-GX2
  // at 10x, 24 drives: rms error / sigma 2.0); the scan steps by the turns' sigma.
  const double turns_s = std::max(in.decision.turns.sigma_s, 0.002), prior_s = 2.0 * turns_s;
  ShiftLikelihood likelihood(in);
  if (!likelihood.ok()) return;
  std::vector<std::pair<double, double>> pts;  // (lag, -2 ln L + prior)
  const auto eval = [&](double lag_s) {
    const double j = likelihood.cost(lag_s);
    if (std::isfinite(j)) pts.push_back({lag_s, j + (lag_s / prior_s) * (lag_s / prior_s)});
    return std::isfinite(j);
  };
  // Least-squares parabola through the points within `half` of `c`: J = A (l - c)^2 + B (l - c) + C.
  const auto fit = [&](double c, double half, double& at, double& sigma) {
    Eigen::Matrix3d N = Eigen::Matrix3d::Zero();
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    int used = 0;
    for (const auto& [l, j] : pts) {
      if (std::abs(l - c) > half + 1e-9) continue;
      const Eigen::Vector3d x((l - c) * (l - c), l - c, 1.0);
      N += x * x.transpose();
      r += x * j;
      ++used;
    }
    if (used < 3) return false;
    const Eigen::Vector3d abc = N.ldlt().solve(r);
    if (!(abc(0) > 0.0)) return false;
    at = c - abc(1) / (2.0 * abc(0));
    sigma = std::sqrt(1.0 / abc(0));  // -2 ln L'' = 2A
    return std::isfinite(at) && std::isfinite(sigma);
  };
  double lag_s = NAN, sigma_s = NAN;
  // Bracket the minimum in steps of the turns' sigma (walking out to 4 prior sigma).
  const double h = turns_s;
  bool ok = eval(0.0) && eval(-h) && eval(h);
  const auto lowest = [&] {
    return *std::min_element(pts.begin(), pts.end(), [](const auto& x, const auto& y) { return x.second < y.second; });
  };
  while (ok) {
    double lo = 1e300, hi = -1e300;
    for (const auto& p : pts) lo = std::min(lo, p.first), hi = std::max(hi, p.first);
    const double best = lowest().first;
    if (best > lo + 0.5 * h && best < hi - 0.5 * h) break;  // bracketed
    const double next = best <= lo + 0.5 * h ? lo - h : hi + h;
    if (std::abs(next) > 4.0 * prior_s) {
      ok = false;
      break;
    }
    ok = eval(next);
  }
  // Two steps either side of the lowest point, and a least-squares parabola through them: a single pass's -2 ln L
  // is rough by about 1 at the millisecond scale (where a fix splits an IMU sample), the rise over a sigma is 1.
  const double best = ok ? lowest().first : 0.0;
  for (int k = -2; ok && k <= 2; ++k) {
    const double l = best + k * h;
    const bool have =
        std::any_of(pts.begin(), pts.end(), [&](const auto& p) { return std::abs(p.first - l) < 0.01 * h; });
    if (!have) ok = eval(l);
  }
  double at = 0.0, sig = 0.0;
  ok = ok && fit(best, 2.01 * h, at, sig);
  if (ok) {
    lag_s = at;
    sigma_s = sig;
  }
  char note[220];
  if (ok && sigma_s < turns_s && std::abs(lag_s) < 4.0 * prior_s) {
    in.imu = shifted(in.imu, lag_s);
    in.decision.refined = {true, in.decision.turns.lag_s + lag_s, sigma_s};
    std::snprintf(note, sizeof note,
                  "; refined by the GNSS likelihood over IMU shifts (%zu filter passes) to %.1f +- %.1f ms, taken out",
                  pts.size(), 1e3 * in.decision.refined.lag_s, 1e3 * sigma_s);
  } else {
    std::snprintf(note, sizeof note, "; the GNSS likelihood over IMU shifts did not refine it (%+.1f +- %.1f ms left)",
                  1e3 * lag_s, 1e3 * sigma_s);
  }
  in.decision.note += note;
}

bool model_has(const FilterOptions& o, const std::string& effect) {
  const auto m = resolve_model(o.model, o.add, o.drop);
  return std::find(m.begin(), m.end(), effect) != m.end();
}

// ImuLatencyEstimate::significant() stops at a 1.5 m lever arm (the live window has no filter passes to judge with);
// a 3.5 m lever arm behind a MEMS IMU at 10 m/s read as the stamps 388 ms early, was taken out unasked, and ldv
// diagnose then undid it with a time_offset.
bool a_lever_arm_could_explain(const Drive& in, const ImuLatencyEstimate& e) {
  return !model_has(in.options, "lever_arm") &&
         e.equivalent_lever_arm_along_m() <= largest_lever_arm_along_m(in.options);
}

void decide(const Drive& in) {
  if (in.imu.empty() || in.gnss.empty()) return;
  in.decision.turns = estimate_imu_latency(in.imu, in.gnss);
  const ImuLatencyEstimate& e = in.decision.turns;
  char note[768];
  if (!e.valid) {
    std::snprintf(note, sizeof note, "; IMU latency not estimated (%d turning GNSS intervals)", e.turning_intervals);
  } else if (e.significant() && !a_lever_arm_could_explain(in, e)) {
    in.imu = shifted(in.imu, e.lag_s);
    in.decision.applied = true;
    std::snprintf(note, sizeof note, "; IMU stamps late by %.1f +- %.1f ms (found from the turns, taken out)",
                  1e3 * e.lag_s, 1e3 * e.sigma_s);
  } else if (e.significant() || std::abs(e.lag_s) > 2.0 * e.sigma_s) {
    // A lag or a lever arm along the track (one within 2 sigma of its prior, however well the turns know it), or a
    // lag the turns know only to 20 ms or worse (few or gentle turns: a
    // reversing manoeuvre's 281 ms read as 274 +- 29), beyond 2 of the turns' sigmas (under vibration about half
    // their real scatter: a stop-and-go drive's 144 ms read as 142 +- 48): the filter over the whole file
    // decides, with and without the lag; it refused 531 +- 31 ms and 542 +- 88 ms read for true lags of 74 and
    // 64 ms. A residual of a lag taken out is the likelihood scan's to refine (refine_latency_with_filter).
    const double noise_without = imu_noise_needed(in, in.imu);
    std::vector<ImuIncrement> lagged = shifted(in.imu, e.lag_s);
    const double noise_with = imu_noise_needed(in, lagged);
    ShiftLikelihood likelihood(in);
    const double cost_plain = likelihood.cost(0.0), cost_lag = likelihood.cost(e.lag_s);
    const double fall = cost_plain - cost_lag;  // -2 ln L without minus with
    // The lag competes with what it can be confused with (issue 47: the main job's 0.6 m forward lever arm was
    // taken for a 50 ms lag, and the diagnosis then undid it with a time_offset): a forward lever arm moves the
    // antenna ahead on the track as a late IMU does. Unless the lag explains the fixes better than the lever
    // arm (estimated by the filter on the way) by as much as the 1-parameter test asks, it is not taken out:
    // the pair is the model's to estimate (lever_arm, time_offset) and ldv diagnose's to tell apart.
    const double cost_lever = model_has(in.options, "lever_arm") ? NAN : likelihood.cost_with("lever_arm");
    const bool lever_explains = std::isfinite(cost_lever) && !(cost_lag + kLagLikelihoodGain < cost_lever);
    const bool take = (noise_with < kLagNoiseGain * noise_without || fall > kLagLikelihoodGain) && !lever_explains;
    if (take) {
      in.imu = std::move(lagged);
      in.decision.applied = true;
    }
    in.decision.lever_explains = lever_explains;
    char why[160];
    if (e.sigma_s >= ImuLatencyEstimate::kMaxSigma_s)
      std::snprintf(why, sizeof why, "known by the turns to %.0f ms only", 1e3 * e.sigma_s);
    else if (e.significant() || std::abs(e.lag_s) <= e.lever_arm_equivalent_lag_s())
      std::snprintf(why, sizeof why, "within what an antenna lever arm of %.1f m along the track explains at %.1f m/s",
                    e.equivalent_lever_arm_along_m(), e.median_speed_mps);
    else
      std::snprintf(why, sizeof why, "only %.1f of the turns' sigmas", std::abs(e.lag_s) / e.sigma_s);
    // A lag the fixes refute (the real walk: the turns' 406 ms raises -2 ln L by 5800, the pass loses the track).
    in.decision.likelihood_gain = fall;
    const bool refuted = in.decision.refuted();
    char likelihood_said[96] = "the fixes' likelihood could not be compared (a pass failed)";
    if (refuted)
      std::snprintf(likelihood_said, sizeof likelihood_said, "-2 ln L of the fixes rises by %.1f with it: not a lag",
                    -fall);
    else if (std::isfinite(fall))
      std::snprintf(likelihood_said, sizeof likelihood_said, "-2 ln L of the fixes falls by %.1f with it", fall);
    char lever_said[200] = "";
    if (std::isfinite(cost_lever))
      std::snprintf(lever_said, sizeof lever_said,
                    "; a lever arm instead of the lag: -2 ln L %+.1f against the lag's%s", cost_lever - cost_lag,
                    !lever_explains                              ? ""
                    : cost_lever < cost_lag - kLagLikelihoodGain ? ": the lever arm explains the fixes better"
                                                                 : ": the lever arm explains the fixes as well, the "
                                                                   "pair cannot be told apart here");
    std::snprintf(note, sizeof note,
                  "; IMU latency %.1f +- %.1f ms: %s; the filter needs %.3gx the IMU noise with it, %.3gx without, "
                  "and %s%s: %s",
                  1e3 * e.lag_s, 1e3 * e.sigma_s, why, noise_with, noise_without, likelihood_said, lever_said,
                  take ? "a lag, taken out"
                       : "not applied (the time_offset and lever_arm effects can estimate it; ldv diagnose tells them "
                         "apart where the drive allows)");
  } else {
    std::snprintf(note, sizeof note, "; IMU latency %.1f +- %.1f ms (not significant, not applied)", 1e3 * e.lag_s,
                  1e3 * e.sigma_s);
  }
  in.decision.note += note;
  if (in.decision.applied) refine_latency_with_filter(in);
}

}  // namespace

double largest_lever_arm_along_m(const FilterOptions& o) { return 2.0 * o.lever_arm.init_std.x(); }

double likelihood_gain_of_lag(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                              const KfGinsConfig& config, const FilterOptions& options, double lag_s) {
  std::vector<ImuIncrement> stamps = imu;  // a Drive may shift its IMU; this one is only read
  DriveImuLatency unused;
  const Drive drive{stamps, gnss, config, options, false, unused};
  ShiftLikelihood likelihood(drive);
  const double plain = likelihood.cost(0.0), lagged = likelihood.cost(lag_s);
  return plain - lagged;
}

DriveImuLatency decide_drive_imu_latency(std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                                         const KfGinsConfig& config, const FilterOptions& options,
                                         bool refine_in_filter) {
  DriveImuLatency decision;
  decide(Drive{imu, gnss, config, options, refine_in_filter, decision});
  return decision;
}

}  // namespace ldv::est
