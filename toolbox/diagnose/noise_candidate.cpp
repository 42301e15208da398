#include "toolbox/diagnose/noise_candidate.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <exception>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"

namespace ldv::diag {

std::optional<MeasuredNoise> measure_noise(const DiagnoseInputs& in, const est::FilterOptions& model) {
  est::FilterOptions o = model;
  o.adapt_imu_noise = o.split_noise_adaptation = true;
  try {
    est::NavFilter filter(o);
    est::run_navigation(in.imu, in.gnss, in.cfg, filter, est::RunCallbacks{}, nullptr, &in.others);
    return MeasuredNoise{filter.noise_adaptation(), filter.imu_noise_psd_scale()};
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<Confirmation> confirm_gnss_noise(const DiagnoseInputs& in, const est::FilterOptions& model,
                                               const FilterRun& base, const est::NoiseAdaptation& measured,
                                               double long_run_factor, double effective_n) {
  Confirmation c;
  c.effect = kGnssNoiseCandidate;
  c.options = model;
  std::vector<double> factors, sigmas;
  for (int k = 0; k < est::NoiseAdaptation::kGnssClasses; ++k) {
    const double factor = measured.gnss_scale(k), sigma = measured.gnss_scale_sigma(k);
    if (measured.gnss_fixes(k) == 0 || !(factor - 2.0 * sigma > 1.0)) continue;
    c.options.gnss_variance_scale[k] *= factor;
    factors.push_back(factor);
    sigmas.push_back(sigma);
    c.estimate.state_names.push_back(est::NoiseAdaptation::gnss_class_name(k));
  }
  if (factors.empty()) return std::nullopt;
  c.estimate.name = kGnssNoiseCandidate;
  c.estimate.unit = est::PrintUnit{1.0, "x the stated variance"};
  c.estimate.value_si = Eigen::Map<const Eigen::VectorXd>(factors.data(), static_cast<Eigen::Index>(factors.size()));
  c.estimate.std_si = Eigen::Map<const Eigen::VectorXd>(sigmas.data(), static_cast<Eigen::Index>(sigmas.size()));
  c.run = run_filter(in, c.options);
  judge_rerun(c, base, static_cast<int>(factors.size()), long_run_factor, effective_n);
  return c;
}

namespace {

constexpr double kLnStep = 1.0986122886681098;      // ln 3
constexpr double kMaxLnFactor = 9.210340371976184;  // ln 1e4, the adaptation's cap

// The maximum of the fixes' log-likelihood over u = ln k in [lo, hi]: from u0 uphill in steps of ln 3, then a parabola
// through the best three; the curvature there (NaN where no three points bracket a maximum).
struct LineMaximum {
  double u = 0.0, curvature = NAN;
  Confirmation best;
  int runs = 0;
};
LineMaximum maximise_over_ln_factor(double u0, double lo, double hi,
                                    const std::function<Confirmation(double)>& rerun_at) {
  std::deque<std::pair<double, Confirmation>> tried;  // a deque: a reference at() returned survives the next run
  const auto at = [&](double u) -> const Confirmation& {
    for (const auto& [v, c] : tried)
      if (std::abs(v - u) < 1e-9) return c;
    tried.emplace_back(u, rerun_at(u));
    return tried.back().second;
  };
  double u = std::clamp(u0, lo, hi);
  const double up = std::min(u + kLnStep, hi);
  const double direction = up > u && at(up).loglik_gain > at(u).loglik_gain ? kLnStep : -kLnStep;
  for (int i = 0; i < 8; ++i) {
    const double next = std::clamp(u + direction, lo, hi);
    if (next == u || at(next).loglik_gain <= at(u).loglik_gain) break;
    u = next;
  }
  LineMaximum m;
  if (u - kLnStep >= lo && u + kLnStep <= hi) {
    const double lm = at(u - kLnStep).loglik_gain, l0 = at(u).loglik_gain, lp = at(u + kLnStep).loglik_gain;
    const double second = lp - 2.0 * l0 + lm;
    if (second < 0.0) {
      m.curvature = second / (kLnStep * kLnStep);
      at(u + std::clamp(-0.5 * kLnStep * (lp - lm) / second, -kLnStep, kLnStep));
    }
  }
  m.u = u;
  m.best = at(u);
  for (const auto& [v, c] : tried)  // the parabola's vertex where it is the best seen
    if (c.loglik_gain > m.best.loglik_gain) m.best = c, m.u = v;
  m.runs = static_cast<int>(tried.size());
  return m;
}

}  // namespace

std::optional<Confirmation> confirm_imu_noise(const DiagnoseInputs& in, const est::FilterOptions& model,
                                              const FilterRun& base, const MeasuredNoise& measured,
                                              double long_run_factor, double effective_n) {
  const double alpha = measured.adaptation.imu_scale(), alpha_sigma = measured.adaptation.imu_scale_sigma();
  if (!(alpha - 2.0 * alpha_sigma > 1.0)) return std::nullopt;
  // The adaptation's factor is a MAP step against a prior centred on the configured noise (narrow once a standstill
  // measured it) over the drive's last window, one factor for both sensors: vibration on the move 100x the
  // standstill's read as 14x. The rerun's factors are those that maximise the fixes' likelihood: a common factor on
  // both PSDs first (from the adaptation's), then the gyros' and the accelerometers' in turn, never below the floor
  // a standstill measured (the pass's floor; 1 without one).
  const double floor_gyro = measured.imu_psd_scale.gyro / alpha, floor_accel = measured.imu_psd_scale.accel / alpha;
  const auto rerun = [&](double ln_gyro, double ln_accel) {
    Confirmation c;
    c.effect = kImuNoiseCandidate;
    c.options = model;
    c.options.arw_rad_per_sqrt_s *= std::sqrt(floor_gyro * std::exp(ln_gyro));
    c.options.vrw_mps_per_sqrt_s *= std::sqrt(floor_accel * std::exp(ln_accel));
    c.run = run_filter(in, c.options);
    judge_rerun(c, base, 2, long_run_factor, effective_n);
    return c;
  };
  const LineMaximum both =
      maximise_over_ln_factor(std::log(alpha), 0.0, kMaxLnFactor, [&](double u) { return rerun(u, u); });
  // Coordinate ascent, two rounds: the two factors trade against each other (a noisier gyro tilts the prediction
  // as a noisier accelerometer does), one round leaves the second where the first's start put it.
  LineMaximum gyro, accel;
  accel.u = both.u;
  int runs = both.runs;
  for (int round = 0; round < 2; ++round) {
    gyro = maximise_over_ln_factor(round == 0 ? both.u : gyro.u, 0.0, kMaxLnFactor,
                                   [&](double u) { return rerun(u, accel.u); });
    accel = maximise_over_ln_factor(accel.u, 0.0, kMaxLnFactor, [&](double u) { return rerun(gyro.u, u); });
    runs += gyro.runs + accel.runs;
  }
  Confirmation c = accel.best;
  c.filter_runs = runs;
  c.estimate.name = kImuNoiseCandidate;
  c.estimate.state_names = {"gyro", "accel"};
  c.estimate.unit = est::PrintUnit{1.0, "x the PSD"};
  c.estimate.value_si = Eigen::Vector2d(floor_gyro * std::exp(gyro.u), floor_accel * std::exp(accel.u));
  // 1-sigma of each ln factor from the likelihood's curvature, the information deflated by the innovations' long-run
  // factor (NaN where the search ended at a bound)
  const auto sigma_ln = [&](const LineMaximum& m) {
    return std::isfinite(m.curvature) ? std::sqrt(std::max(1.0, long_run_factor) / -m.curvature) : NAN;
  };
  c.estimate.std_si = c.estimate.value_si.cwiseProduct(Eigen::Vector2d(sigma_ln(gyro), sigma_ln(accel)));
  return c;
}

}  // namespace ldv::diag
