#include "toolbox/assess/nav_inputs.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "common/config/config_section.hpp"
#include "common/formats/imu_calibration.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/formats/odometer_text.hpp"
#include "common/formats/rtklib_solution.hpp"
#include "common/formats/tagged_imu_csv.hpp"
#include "common/io/input_error.hpp"
#include "common/math/chi_square.hpp"
#include "common/math/device_axes.hpp"
#include "estimator/calibrate/gnss_velocity_check.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"
#include "estimator/update/odometer.hpp"
#include "input/tables/gnss_table.hpp"
#include "input/tables/imu_table.hpp"

namespace ldv::assess {
namespace {

void check_axes(const std::vector<int>& axes) {
  if (!is_device_axes(axes))
    throw InputError("--csv-axes", 0, "expected a permutation of 1 2 3 with signs, e.g. 1 -2 -3");
}

bool ends_with(const std::string& s, const char* suffix) {
  const std::string x(suffix);
  return s.size() >= x.size() && s.compare(s.size() - x.size(), x.size(), x) == 0;
}

// The calibration file: the command line's, else the configuration's ldv.calibration (resolved like imupath).
// Seconds since the start of GPS week `ref_week`: continuous across a week rollover (sow restarts at 0,
// this goes on past 604800), so time order is the order of this number.
double continuous_seconds(const GpsTime& t, int ref_week) { return (t.week - ref_week) * kSecondsPerWeek + t.sow_s; }

// A .pos file's solutions in time order. Each record stands on its own time tag: one record stamped
// ahead (a glitch, or a real forward jump) is placed at its time instead of making every later one look
// repeated. Records at the same epoch as the one before are dropped (kept: the first in the file).
struct PosTimeOrder {
  std::vector<const gnss::GnssSolution*> solutions;
  long repeated = 0, out_of_order = 0;
};
PosTimeOrder in_time_order(const std::vector<gnss::GnssSolution>& sols, int& ref_week) {
  // The drive's first week (KF-GINS files count on from it past a rollover): the earliest week next to the
  // median one. One record of a far week (a corrupted date) must not move every other record's time (the
  // earliest week did: a record of 1980 put all the others 2300 weeks ahead of the IMU).
  std::vector<int> weeks;
  weeks.reserve(sols.size());
  for (const auto& s : sols) weeks.push_back(s.time.week);
  std::nth_element(weeks.begin(), weeks.begin() + weeks.size() / 2, weeks.end());
  const int median_week = weeks[weeks.size() / 2];
  ref_week = median_week;
  for (const auto& s : sols)
    if (s.time.week == median_week - 1) ref_week = median_week - 1;
  PosTimeOrder o;
  for (std::size_t i = 0; i < sols.size(); ++i) {
    if (i > 0 && sols[i].time.total_seconds() < sols[i - 1].time.total_seconds()) ++o.out_of_order;
    o.solutions.push_back(&sols[i]);
  }
  const auto t = [](const gnss::GnssSolution* s) { return s->time.total_seconds(); };
  std::stable_sort(o.solutions.begin(), o.solutions.end(), [&](auto* x, auto* y) { return t(x) < t(y); });
  constexpr double kSameEpoch_s = 1e-6;  // .pos prints milliseconds
  std::vector<const gnss::GnssSolution*> kept;
  for (const auto* s : o.solutions) {
    if (!kept.empty() && t(s) - t(kept.back()) < kSameEpoch_s) {
      ++o.repeated;
      continue;
    }
    kept.push_back(s);
  }
  o.solutions = std::move(kept);
  return o;
}

std::string calibration_path(const NavInputArgs& a, const KfGinsConfig& cfg) {
  if (!a.calibration.empty()) return a.calibration;
  if (!cfg.ldv.IsDefined() || cfg.ldv.IsNull() || !cfg.ldv["calibration"]) return "";
  const YAML::Node n = cfg.ldv["calibration"];
  if (!n.IsScalar() || n.Scalar().empty())
    throw InputError(cfg.config_path, n.Mark().line + 1, "key 'ldv.calibration': expected the path of a calibration file");
  return resolve_data_path(n.Scalar(), cfg.config_path);
}

// After the calibration, what is left of the bias and scale errors is its uncertainty: that becomes the
// filter's prior, unless the configuration gives one or the calibration does not know it (a zero sigma).
std::string take_priors_from(const calib::ImuCalibration& cal, const KfGinsConfig& cfg, est::FilterOptions& o) {
  std::string taken;
  const auto take = [&](est::BlockOptions& block, const std::optional<Vec3>& configured, const Vec3& sigma,
                        const char* name) {
    if (configured || !(sigma.array() > 0.0).all()) return false;
    block.init_std = sigma;
    taken += (taken.empty() ? "" : ", ") + std::string(name);
    return true;
  };
  // options_from_kfgins gives the moving bias's constant part the bias prior: keep them together.
  if (take(o.gyro_bias, cfg.init_gyro_bias_std_rad_s, cal.gyro.bias_sigma, "gyro_bias"))
    o.gyro_moving_bias.constant_std = o.gyro_bias.init_std;
  if (take(o.accel_bias, cfg.init_accel_bias_std_mps2, cal.accel.bias_sigma, "accel_bias"))
    o.accel_moving_bias.constant_std = o.accel_bias.init_std;
  take(o.gyro_scale, cfg.init_gyro_scale_std, cal.gyro.scale_sigma, "gyro_scale");
  take(o.accel_scale, cfg.init_accel_scale_std, cal.accel.scale_sigma, "accel_scale");
  return taken;
}

}  // namespace

NavInputs load_nav_model(const NavInputArgs& a) {
  NavInputs in;
  if (!a.config.empty()) {
    in.config = load_kfgins_config(a.config);
    in.options = est::options_from_kfgins(in.config);
  } else {
    in.config.output_path = ".";
  }
  if (a.lever.size() == 3) in.options.lever_arm.init = Vec3(a.lever[0], a.lever[1], a.lever[2]);
  if (a.kfgins_compatible) {  // KF-GINS's update, and its alignment: body x along the course
    est::make_kfgins_compatible(in.options, in.config);
    if (!has_ldv_key(in.config, "align_hypotheses")) in.options.align_hypotheses = 1;
  }
  if (!a.aids.empty()) in.options.aids.enabled = a.aids;
  if (!a.model.empty()) in.options.model = a.model;
  in.options.add.insert(in.options.add.end(), a.add.begin(), a.add.end());
  in.options.drop.insert(in.options.drop.end(), a.drop.begin(), a.drop.end());
  return in;
}

namespace {

// The odometer's readings when the odometer aid is on: --odometer, else ldv.odopath (resolved like imupath).
void load_odometer(const NavInputArgs& a, NavInputs& in) {
  if (!in.options.aids.has("odometer")) return;
  std::string path = a.odometer;
  if (path.empty() && has_ldv_key(in.config, "odopath")) {
    try {
      path = resolve_data_path(in.config.ldv["odopath"].as<std::string>(), in.config.config_path);
    } catch (const YAML::Exception&) {
      throw InputError(in.config.config_path, in.config.ldv["odopath"].Mark().line + 1,
                       "key 'ldv.odopath': expected a path");
    }
  }
  if (path.empty())
    throw InputError(in.config.config_path.empty() ? "--aid odometer" : in.config.config_path, 0,
                     "the odometer aid needs its readings: --odometer FILE or ldv.odopath (lines 'sow speed_mps')");
  const std::vector<OdometerSample> samples = read_odometer_text(path);
  if (samples.empty()) throw InputError(path, 0, "no odometer readings");
  for (const OdometerSample& o : samples)
    in.other_observations.push_back(std::make_shared<est::OdometerObservation>(o.t_s, o.speed_mps));
  in.file_counts.push_back({"odometer", path, static_cast<long>(samples.size()), {}});
  in.description += " + " + path;
}

std::vector<ImuIncrement> shifted(std::vector<ImuIncrement> imu, double lag_s) {
  for (ImuIncrement& s : imu) s.t_s -= lag_s;
  return imu;
}

// How much IMU noise the filter needs to follow the fixes over these IMU samples: the geometric mean over the
// run of the adapted noise scale, from the configured noise up (FilterOptions::adapt_imu_noise holds the
// position NIS at its expectation, so a model that misses something shows as noise). Positions only (a GNSS
// velocity's own lag would take sides); a run that cannot start counts as the largest scale.
double imu_noise_needed(const NavInputs& in, const std::vector<ImuIncrement>& imu) {
  est::FilterOptions o = in.options;
  o.use_gnss_velocity = false;
  o.adapt_imu_noise = true;
  o.installed_noise_floor = false;  // the adapted factor alone: a floor above what both runs need would tie them
  est::NavFilter filter(o);
  double sum_log = 0.0;
  long n = 0;
  est::RunCallbacks cb;
  cb.on_epoch = [&](const est::NavFilter& f) {
    sum_log += std::log(f.imu_noise_scale());
    ++n;
  };
  try {
    est::run_navigation(imu, in.gnss, in.config, filter, cb);
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
constexpr double kLagLikelihoodGain = 10.83;

// -2 ln L of the GNSS positions as a function of a shift of the IMU stamps: sum over the fixes of NIS + ln det S
// (positions only, an outlier counted as at the filter's gate), each pass with the IMU shifted exactly and the IMU
// noise held at what a pass at the current stamps adapted to. The fixes compared are the first pass's: a fix a
// later pass did not update with (it lost the track and waited to align again: the real walk at the turns' 406
// ms) counts as an outlier at the gate with the first pass's ln det S, so a pass that fails is worse, not
// incomparable.
class ShiftLikelihood {
 public:
  explicit ShiftLikelihood(const NavInputs& in) : in_(in), o_(in.options) {
    o_.use_gnss_velocity = false;  // positions only: a GNSS velocity's own lag would take sides
    gate_ = math::chi_square_quantile(o_.gate_probability, 3);
    est::ImuNoiseScale q;
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
  const est::FilterOptions& options() const { return o_; }
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
    const est::FilterOptions plain = o_;
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
  bool pass(double lag_s, est::ImuNoiseScale* noise) {
    terms_.clear();
    est::RunCallbacks cb;
    cb.on_innovation = [&](const est::InnovationRecord& r) {
      if (r.sensor != est::sensors::kGnssPosition || r.replayed) return;
      const Eigen::LLT<Eigen::MatrixXd> llt(r.S);
      if (llt.info() != Eigen::Success) return;
      const Eigen::MatrixXd L = llt.matrixL();
      terms_.push_back({r.t_s, std::min(r.nis, gate_), 2.0 * L.diagonal().array().log().sum()});
    };
    try {
      est::NavFilter filter(o_);
      est::run_navigation(shifted(in_.imu, lag_s), in_.gnss, in_.config, filter, cb);
      if (noise) *noise = filter.imu_noise_psd_scale();
    } catch (const std::exception&) {
      return false;
    }
    return !terms_.empty();
  }

  const NavInputs& in_;
  est::FilterOptions o_;
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
void refine_latency_with_filter(const NavInputArgs& a, NavInputs& in) {
  if (!a.refine_latency_in_filter) return;
  const std::vector<std::string> model = est::resolve_model(in.options.model, in.options.add, in.options.drop);
  if (std::find(model.begin(), model.end(), "time_offset") != model.end()) return;  // the user's own
  if (std::find(in.options.drop.begin(), in.options.drop.end(), "time_offset") != in.options.drop.end()) return;
  // The prior: 0 with twice the turns' sigma, which under vibration is about half their real scatter (3DM-GX2
  // at 10x, 24 drives: rms error / sigma 2.0); the scan steps by the turns' sigma.
  const double turns_s = std::max(in.imu_latency.sigma_s, 0.002), prior_s = 2.0 * turns_s;
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
    const bool have = std::any_of(pts.begin(), pts.end(), [&](const auto& p) { return std::abs(p.first - l) < 0.01 * h; });
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
    in.imu_latency_refined = {true, in.imu_latency.lag_s + lag_s, sigma_s};
    std::snprintf(note, sizeof note,
                  "; refined by the GNSS likelihood over IMU shifts (%zu filter passes) to %.1f +- %.1f ms, taken out",
                  pts.size(), 1e3 * in.imu_latency_refined.lag_s, 1e3 * sigma_s);
  } else {
    std::snprintf(note, sizeof note,
                  "; the GNSS likelihood over IMU shifts did not refine it (%+.1f +- %.1f ms left)", 1e3 * lag_s,
                  1e3 * sigma_s);
  }
  in.imu_note += note;
}

// IMU stamps late against GNSS time (a consumer IMU behind a USB or serial buffer): found from the data
// and taken out before the filter sees them, unless the user set the shift or asked for KF-GINS's behaviour.
void estimate_and_remove_imu_latency(const NavInputArgs& a, bool shift_given, NavInputs& in) {
  const bool wanted = est::imu_latency_wanted(in.config, in.options, a.imu_latency, shift_given || a.kfgins_compatible);
  if (!wanted || in.imu.empty() || in.gnss.empty()) return;
  in.imu_latency = est::estimate_imu_latency(in.imu, in.gnss);
  const est::ImuLatencyEstimate& e = in.imu_latency;
  char note[768];
  if (!e.valid) {
    std::snprintf(note, sizeof note, "; IMU latency not estimated (%d turning GNSS intervals)", e.turning_intervals);
  } else if (e.significant()) {
    in.imu = shifted(in.imu, e.lag_s);
    in.imu_latency_applied = true;
    std::snprintf(note, sizeof note, "; IMU stamps late by %.1f +- %.1f ms (found from the turns, taken out)",
                  1e3 * e.lag_s, 1e3 * e.sigma_s);
  } else if (std::abs(e.lag_s) > 2.0 * e.sigma_s) {
    // A lag or a forward lever arm, or a lag the turns know only to 20 ms or worse (few or gentle turns: a
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
    const bool model_has_lever = [&] {
      const auto m = est::resolve_model(in.options.model, in.options.add, in.options.drop);
      return std::find(m.begin(), m.end(), "lever_arm") != m.end();
    }();
    const double cost_lever = model_has_lever ? NAN : likelihood.cost_with("lever_arm");
    const bool lever_explains = std::isfinite(cost_lever) && !(cost_lag + kLagLikelihoodGain < cost_lever);
    const bool take = (noise_with < kLagNoiseGain * noise_without || fall > kLagLikelihoodGain) && !lever_explains;
    if (take) {
      in.imu = std::move(lagged);
      in.imu_latency_applied = true;
    }
    in.imu_latency_lever_explains = lever_explains;
    in.imu_latency_likelihood_gain = fall;
    char why[160];
    if (e.sigma_s >= est::ImuLatencyEstimate::kMaxSigma_s)
      std::snprintf(why, sizeof why, "known by the turns to %.0f ms only", 1e3 * e.sigma_s);
    else if (std::abs(e.lag_s) <= e.lever_arm_equivalent_lag_s())
      std::snprintf(why, sizeof why, "within what a forward antenna lever arm of %.1f m explains at %.1f m/s (%.0f ms)",
                    est::ImuLatencyEstimate::kMaxLeverArmAlong_m, e.median_speed_mps,
                    1e3 * e.lever_arm_equivalent_lag_s());
    else
      std::snprintf(why, sizeof why, "only %.1f of the turns' sigmas", std::abs(e.lag_s) / e.sigma_s);
    // A lag the fixes refute (the real walk: the turns' 406 ms raises -2 ln L by 5800, the pass loses the track).
    const bool refuted = fall < -kLagLikelihoodGain;
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
  in.imu_note += note;
  if (in.imu_latency_applied) refine_latency_with_filter(a, in);
}

// GNSS velocities are fused only where they agree with the positions, unless the configuration says
// (ldv.use_gnss_velocity) or KF-GINS's behaviour is asked for.
void decide_gnss_velocity_use(const NavInputArgs& a, NavInputs& in) {
  const bool configured = has_ldv_key(in.config, "use_gnss_velocity");
  const bool any_velocity =
      std::any_of(in.gnss.begin(), in.gnss.end(), [](const GnssFix& f) { return f.has_velocity; });
  const bool kfgins = a.kfgins_compatible || !in.options.robust_update;
  if (configured || kfgins || !any_velocity || !in.options.use_gnss_velocity) return;
  const est::GnssVelocityCheck c = est::check_gnss_velocity(in.gnss);
  in.gnss_velocity_check = c;
  char note[220];
  if (c.consistent()) {
    std::snprintf(note, sizeof note, "GNSS velocity used (agrees with the positions: misfit %.1fx its sigma^2 over %d fixes)",
                  c.normalised_mse, c.compared);
  } else {
    in.options.use_gnss_velocity = false;
    std::snprintf(note, sizeof note,
                  "GNSS velocity not used: misfit %.1fx its stated sigma^2 against the positions over %d fixes "
                  "(best aligned %.0f ms late: %.1fx%s); positions only",
                  c.normalised_mse, c.compared, 1e3 * c.best_lag_s, c.normalised_mse_at_lag,
                  c.lagged() ? ", a significant lag" : "");
  }
  in.gnss_velocity_note = note;
}

}  // namespace

NavInputs load_nav_inputs(const NavInputArgs& a) {
  NavInputs in = load_nav_model(a);
  const auto setting = [&](double given, const char* key) {
    return given != NavInputArgs::kUnset ? given : (a.config.empty() ? 0.0 : est::ldv_number(in.config, key, 0.0));
  };
  const double height_offset_m = setting(a.pos_height_offset_m, "pos_height_offset_m");
  const double float_std_min_m = setting(a.float_std_min_m, "float_std_min_m");
  const double imu_time_shift_s = setting(a.imu_time_shift_s, "imu_time_shift_s");
  if (!a.imu.empty()) in.config.imu_path = a.imu;
  if (!a.imu_csv.empty()) in.config.imu_path = a.imu_csv;
  if (!a.gnss.empty()) in.config.gnss_path = a.gnss;
  if (!a.rtklib_pos.empty()) in.config.gnss_path = a.rtklib_pos;

  // A user's own tables (ldv.imu_table / ldv.gnss_table: input/tables/) unless the command line names a file.
  const auto table_section = [&](const char* key) {
    return config::ConfigSection(in.config.ldv[key], in.config.config_path, std::string("ldv.") + key + ".");
  };
  std::optional<input::ImuTable> imu_table;
  std::optional<input::GnssTable> gnss_table;
  if (a.imu.empty() && a.imu_csv.empty() && has_ldv_key(in.config, "imu_table")) {
    imu_table = input::ImuTable::from(table_section("imu_table"), in.config.config_path);
    in.config.imu_path = imu_table->path;
  }
  if (a.gnss.empty() && a.rtklib_pos.empty() && has_ldv_key(in.config, "gnss_table")) {
    gnss_table = input::GnssTable::from(table_section("gnss_table"), in.config.config_path);
    in.config.gnss_path = gnss_table->path;
  }

  const std::string& imu_path = in.config.imu_path;
  if (imu_path.empty()) throw InputError("ldv", 0, "give --kfgins-config FILE, or --imu FILE (or --imu-csv FILE)");
  // Loaded before the IMU file so a bad calibration is reported before a long read.
  const std::string cal_path = calibration_path(a, in.config);
  std::optional<calib::ImuCalibration> cal;
  if (!cal_path.empty()) cal = calib::load_calibration(cal_path);
  const auto calibrate = [&] {
    if (cal)
      for (ImuIncrement& s : in.imu) s = calib::apply_calibration(*cal, s);
  };
  if (imu_table) {
    input::ImuTableReport rep;
    in.imu = input::read_imu_table(*imu_table, &rep);
    in.file_counts.push_back({"IMU", imu_path, static_cast<long>(in.imu.size()), rep.dropped});
    in.imu_gaps = rep.long_gaps;
    calibrate();  // the table's rows are in front-right-down already
    in.imu_note = "ldv.imu_table: " + rep.layout.describe() + "; time " + imu_table->time.describe() + "; " +
                  std::to_string(rep.long_gaps.size()) + " gaps";
  } else if (!a.imu_csv.empty() || ends_with(imu_path, ".csv")) {
    check_axes(a.csv_axes);
    TaggedImuCsvReport rep;
    in.imu = read_tagged_imu_csv(imu_path, a.imu_tag.empty() ? imu_path + ".tag" : a.imu_tag, {}, &rep);
    in.file_counts.push_back({"IMU", imu_path, rep.samples, rep.dropped});
    in.imu_gaps = rep.long_gaps;
    // The tags' jitter from the rows themselves: the trapezoid's increments no longer show which rows repeated.
    // Measured here or not at all: the run would read the reads' scatter in the increments, not the samples'.
    if (in.options.imu_stamp_jitter_from_tags) {
      in.imu_stamp_jitter = est::measure_imu_stamp_jitter(rep.distinct_sample_tags_s, rep.samples, rep.repeated_rows);
      if (in.imu_stamp_jitter.found) in.options.imu_stamp_jitter_s = in.imu_stamp_jitter.sigma_s;
      in.options.imu_stamp_jitter_from_tags = false;
    }
    calibrate();  // in the device axes, as `ldv calib static` saw them
    for (ImuIncrement& s : in.imu) {
      s.dtheta_b_rad = device_to_frd(s.dtheta_b_rad, a.csv_axes);
      s.dvel_b_mps = device_to_frd(s.dvel_b_mps, a.csv_axes);
    }
    in.imu_note = std::to_string(rep.skipped_lines) + " malformed lines and " + std::to_string(rep.skipped_counter) +
                  " bad counters skipped, " + std::to_string(rep.gaps) + " gaps; counter rate from " + rep.rate_source +
                  "; tag positions count line ends " + rep.line_ends;
    if (rep.counter_wraps > 0)
      in.imu_note += "; " + std::to_string(rep.counter_wraps) + " counter wraps at " + std::to_string(rep.counter_bits) +
                     " bits unwrapped";
  } else {
    ImuReadReport rep;
    ImuReadOptions ro;
    if (!a.config.empty()) {  // the configuration declares the layout (KF-GINS imudatalen, imudatarate)
      ro.columns = in.config.imu_data_columns;
      ro.rate_hz = in.config.imu_rate_hz;
      ro.declared_by = "imudatalen in " + a.config;
    } else {
      ro.declared_by = "the KF-GINS layout; a config's imudatalen";
    }
    in.imu = read_kfgins_imu(imu_path, &rep, ro);
    in.file_counts.push_back({"IMU", imu_path, rep.rows, rep.dropped});
    in.imu_gaps = rep.long_gaps;
    calibrate();
    in.imu_note = std::to_string(rep.dropped.total()) + " records dropped, " + std::to_string(rep.gaps) + " gaps";
  }
  if (cal) {
    in.imu_note += "; calibration " + cal_path + " applied";
    const std::string priors = take_priors_from(*cal, in.config, in.options);
    if (!priors.empty()) in.imu_note += " (its sigmas are the prior std of " + priors + ")";
  }
  for (ImuIncrement& s : in.imu) s.t_s += imu_time_shift_s;
  in.description = imu_path;

  const std::string& gnss_path = in.config.gnss_path;
  if (gnss_path.empty()) throw InputError("ldv", 0, "give --kfgins-config FILE, or --gnss FILE (or --pos FILE)");
  if (gnss_table) {
    input::GnssTableReport rep;
    in.gnss = input::read_gnss_table(*gnss_table, &rep);
    in.file_counts.push_back({"GNSS", gnss_path, static_cast<long>(in.gnss.size()), rep.dropped});
    in.gnss_note = "ldv.gnss_table: " + rep.layout.describe() + "; " + std::to_string(rep.repeated_rows) +
                   " sample-and-hold rows dropped (each repeats the fix before it)";
  } else if (!a.rtklib_pos.empty() || ends_with(gnss_path, ".pos")) {
    gnss::RtklibReadReport rep;
    const auto sols = gnss::read_rtklib_pos(gnss_path, {}, &rep);
    if (sols.empty()) throw InputError(gnss_path, 0, "no solutions in the RTKLIB .pos file");
    const PosTimeOrder order = in_time_order(sols, in.gps_week);
    for (const gnss::GnssSolution* s : order.solutions) {
      GnssFix f = s->fix;
      f.t_s = continuous_seconds(s->time, in.gps_week);
      f.pos.h_m += height_offset_m;
      if (f.quality != GnssQuality::kFixed && float_std_min_m > 0) f.pos_std_ned_m = f.pos_std_ned_m.cwiseMax(float_std_min_m);
      in.gnss.push_back(f);
    }
    DroppedRecords pos_dropped;  // the reader's malformed lines by reason, then the ordering's repeats
    for (const auto& [why, count] : rep.malformed_by_reason) {
      const auto first = rep.first_line_by_reason.find(why);
      const long line = first != rep.first_line_by_reason.end() ? first->second : 0;
      for (long k = 0; k < count; ++k) pos_dropped.add(DropReason::kMalformed, gnss_path, line, why);
    }
    for (long k = 0; k < order.repeated; ++k) pos_dropped.add(DropReason::kRepeated, gnss_path, 0, "repeated epoch");
    in.file_counts.push_back({"GNSS", gnss_path, static_cast<long>(in.gnss.size()), pos_dropped});
    in.gnss_note = rep.summary() + "; " + std::to_string(order.repeated) + " repeated epochs dropped, " +
                   std::to_string(order.out_of_order) + " out of file order";
  } else {
    GnssReadReport rep;
    in.gnss = read_kfgins_gnss(gnss_path, &rep);
    in.file_counts.push_back({"GNSS", gnss_path, rep.rows, rep.dropped});
  }
  in.description += " + " + gnss_path;
  load_odometer(a, in);
  estimate_and_remove_imu_latency(a, imu_time_shift_s != 0.0, in);
  decide_gnss_velocity_use(a, in);
  if (a.strict) {
    const std::vector<std::string> w = input_warnings(in);
    if (!w.empty()) {
      std::string all;
      for (const auto& x : w) all += "\n  " + x;
      throw InputError("--strict", 0, "the inputs are not clean:" + all);
    }
  }
  return in;
}

std::vector<std::string> input_count_lines(const NavInputs& in) {
  std::vector<std::string> out;
  for (const InputFileCounts& c : in.file_counts) {
    char pct[32];
    std::snprintf(pct, sizeof pct, "%.2f %%", 100.0 * c.dropped_fraction());
    out.push_back(c.role + " " + c.path + ": " + std::to_string(c.kept) + " records kept, " +
                  std::to_string(c.dropped.total()) + " dropped (" + pct + ")" +
                  (c.dropped.total() ? ": " + c.dropped.describe() : std::string()));
  }
  return out;
}

std::vector<std::string> input_warnings(const NavInputs& in) {
  std::vector<std::string> out;
  for (const InputFileCounts& c : in.file_counts) {
    if (c.dropped_fraction() <= kMaxDroppedFraction) continue;
    char msg[160];
    std::snprintf(msg, sizeof msg, "%s file dropped %.1f %% of its records (more than %.0f %%): ", c.role.c_str(),
                  100.0 * c.dropped_fraction(), 100.0 * kMaxDroppedFraction);
    out.push_back(msg + c.path + ": " + c.dropped.describe());
  }
  long long_gaps = 0;
  const ImuTimeGap* longest = nullptr;
  for (const ImuTimeGap& g : in.imu_gaps) {
    if (g.length_s() <= kMaxImuGap_s) continue;
    ++long_gaps;
    if (!longest || g.length_s() > longest->length_s()) longest = &g;
  }
  if (longest) {
    char msg[200];
    std::snprintf(msg, sizeof msg, "IMU has %ld gaps longer than %g s; the longest %.3f s from %.3f to %.3f s (line %ld)",
                  long_gaps, kMaxImuGap_s, longest->length_s(), longest->t_before_s, longest->t_after_s, longest->line);
    out.push_back(msg);
  }
  // GNSS that does not cover the IMU's time (wrong week, another day's file, a time-base mix-up) would
  // give a pure-inertial run that looks like a navigation result.
  if (!in.imu.empty() && !in.gnss.empty()) {
    const double imu_t0 = in.imu.front().t_s, imu_t1 = in.imu.back().t_s;
    long inside = 0;
    for (const GnssFix& f : in.gnss) inside += f.t_s >= imu_t0 && f.t_s <= imu_t1;
    const double covered = static_cast<double>(inside) / static_cast<double>(in.gnss.size());
    if (covered < 0.5) {
      char msg[240];
      std::snprintf(msg, sizeof msg,
                    "only %ld of %zu GNSS fixes (%.0f %%) fall within the IMU's time span %.3f - %.3f s (GNSS %.3f - %.3f s): "
                    "check the GPS week and time base of both files",
                    inside, in.gnss.size(), 100.0 * covered, imu_t0, imu_t1, in.gnss.front().t_s, in.gnss.back().t_s);
      out.push_back(msg);
    }
  }
  return out;
}

}  // namespace ldv::assess
