#include "estimator/calibrate/imu_latency.hpp"

#include <algorithm>
#include <cmath>

#include "common/geo/earth_model.hpp"
#include "estimator/calibrate/gnss_track.hpp"

namespace ldv::est {
namespace {

double wrap_pi(double a) { return std::remainder(a, 2.0 * M_PI); }

// Cumulative heading angle about the vertical sensed by the gyros, at every IMU stamp (piecewise linear).
// Also its running time integral (area), so that the mean heading over any span costs two look-ups. The lag
// search asks for ~10^7 of them on an hour's drive: a look-up starts at the index the nominal sample interval
// points to and steps from there (the stamps are near uniform), falling back to a binary search over gaps.
struct HeadingIntegral {
  std::vector<double> t_s, psi_rad, area_rad_s;
  double dt_nominal_s = 0.0;  // set once the stamps are in (finish())
  void finish() { dt_nominal_s = t_s.size() > 1 ? (t_s.back() - t_s.front()) / (t_s.size() - 1) : 0.0; }
  // The first i with t_s[i] > t, for t inside (t_s.front(), t_s.back()) (std::upper_bound's answer).
  size_t upper_index(double t) const {
    const size_t n = t_s.size();
    if (dt_nominal_s > 0.0) {
      const double guess = 1.0 + std::floor((t - t_s.front()) / dt_nominal_s);
      size_t i = static_cast<size_t>(std::clamp(guess, 1.0, static_cast<double>(n - 1)));
      for (int steps = 0; steps < 8; ++steps) {
        if (t_s[i] <= t && i + 1 < n)
          ++i;
        else if (t_s[i - 1] > t && i > 1)
          --i;
        else if (t_s[i - 1] <= t && t < t_s[i])
          return i;
      }
    }
    return static_cast<size_t>(std::upper_bound(t_s.begin(), t_s.end(), t) - t_s.begin());
  }
  double area(double t) const {
    if (t <= t_s.front()) return 0.0;
    if (t >= t_s.back()) return area_rad_s.back();
    const size_t i = upper_index(t);
    const double dt = t - t_s[i - 1];
    const double psi_t = psi_rad[i - 1] + dt / (t_s[i] - t_s[i - 1]) * (psi_rad[i] - psi_rad[i - 1]);
    return area_rad_s[i - 1] + dt * 0.5 * (psi_rad[i - 1] + psi_t);
  }
  // The mean heading over [a, b]: what a chord's course over that span sees.
  double mean(double a, double b) const { return (area(b) - area(a)) / (b - a); }
};

// The course change between two chords' courses, each the mean heading over its span [a, b].
struct CourseInterval {
  double a0_s, b0_s, a1_s, b1_s, dchi_rad;
  double dt_s() const { return 0.5 * (a1_s + b1_s - a0_s - b0_s); }
};

}  // namespace

ImuLatencyEstimate estimate_imu_latency(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                                        const ImuLatencyOptions& o) {
  ImuLatencyEstimate out;
  if (imu.size() < 100 || gnss.size() < 10) return out;
  // The vertical (down) in body axes: against the mean specific force, which points up.
  Vec3 sum_dv = Vec3::Zero();
  for (const ImuIncrement& s : imu) sum_dv += s.dvel_b_mps;
  if (!(sum_dv.norm() > 0.0) || !sum_dv.allFinite()) return out;
  const Vec3 down_b = -sum_dv.normalized();
  HeadingIntegral h;
  h.t_s.reserve(imu.size() + 1);
  h.psi_rad.reserve(imu.size() + 1);
  h.t_s.push_back(imu.front().t_s - imu.front().dt_s);
  h.psi_rad.push_back(0.0);
  h.area_rad_s.push_back(0.0);
  for (const ImuIncrement& s : imu) {
    if (!(s.t_s > h.t_s.back()) || !s.dtheta_b_rad.allFinite()) continue;
    const double psi = h.psi_rad.back() + s.dtheta_b_rad.dot(down_b);
    h.area_rad_s.push_back(h.area_rad_s.back() + (s.t_s - h.t_s.back()) * 0.5 * (h.psi_rad.back() + psi));
    h.t_s.push_back(s.t_s);
    h.psi_rad.push_back(psi);
  }
  h.finish();
  // Course at each fix from the chord of its neighbours; course change over consecutive fixes.
  std::vector<double> chi(gnss.size(), NAN);
  const double nominal_dt = median_fix_interval_s(gnss);
  if (!(nominal_dt > 0.0)) return out;
  for (size_t k = 1; k + 1 < gnss.size(); ++k) {
    const double span = gnss[k + 1].t_s - gnss[k - 1].t_s;
    if (span > 3.0 * nominal_dt || !(span > 0.0)) continue;
    const Vec3 d = earth::ned_between(gnss[k - 1].pos, gnss[k + 1].pos);
    if (d.head<2>().norm() / span < o.min_speed_mps) continue;
    chi[k] = std::atan2(d.y(), d.x());
  }
  std::vector<CourseInterval> iv;
  std::vector<double> speeds;
  for (size_t k = 1; k + 2 < gnss.size(); ++k) {
    if (std::isnan(chi[k]) || std::isnan(chi[k + 1])) continue;
    if (gnss[k - 1].t_s - o.max_lag_s < h.t_s.front() || gnss[k + 2].t_s + o.max_lag_s > h.t_s.back()) continue;
    iv.push_back({gnss[k - 1].t_s, gnss[k + 1].t_s, gnss[k].t_s, gnss[k + 2].t_s, wrap_pi(chi[k + 1] - chi[k])});
    speeds.push_back(earth::ned_between(gnss[k].pos, gnss[k + 1].pos).head<2>().norm() /
                     (gnss[k + 1].t_s - gnss[k].t_s));
  }
  out.median_speed_mps = median_in_place(speeds);
  out.intervals = static_cast<int>(iv.size());
  for (const CourseInterval& c : iv) out.turning_intervals += std::abs(c.dchi_rad) / c.dt_s() > o.min_turn_rad_s;
  if (out.turning_intervals < o.min_intervals) return out;
  // The course change the track shows minus the one the gyros sensed over the same spans shifted by the lag.
  auto course_change_error = [&](const CourseInterval& c, double lag_s) {
    return c.dchi_rad - (h.mean(c.a1_s + lag_s, c.b1_s + lag_s) - h.mean(c.a0_s + lag_s, c.b0_s + lag_s));
  };
  // Residuals at a lag, with the constant gyro bias (rate about the vertical) fitted by least squares.
  auto residuals = [&](const std::vector<CourseInterval>& set, double lag_s) {
    std::vector<double> e(set.size());
    double sxy = 0, sxx = 0;
    for (size_t k = 0; k < set.size(); ++k) {
      e[k] = course_change_error(set[k], lag_s);
      sxy += e[k] * set[k].dt_s(), sxx += set[k].dt_s() * set[k].dt_s();
    }
    for (size_t k = 0; k < set.size(); ++k) e[k] -= sxy / sxx * set[k].dt_s();
    return e;
  };
  // The misfit at each of a set of lags at once, with the bias fitted per lag from running sums
  // (sum (e - b t)^2 at the best b is S_ee - S_et^2 / S_tt). Intervals outer, lags inner: each interval's
  // look-ups then stay within a few hundred IMU samples of each other, in cache (lags outer walked the
  // whole file once per lag: a third of `ldv nav`'s time on an hour's drive).
  auto misfits = [&](const std::vector<CourseInterval>& set, const std::vector<double>& lags_s) {
    std::vector<double> s_ee(lags_s.size(), 0.0), s_et(lags_s.size(), 0.0);
    double s_tt = 0.0;
    for (const CourseInterval& c : set) {
      const double t = c.dt_s();
      s_tt += t * t;
      for (size_t j = 0; j < lags_s.size(); ++j) {
        const double e = course_change_error(c, lags_s[j]);
        s_ee[j] += e * e;
        s_et[j] += e * t;
      }
    }
    std::vector<double> cost(lags_s.size());
    for (size_t j = 0; j < lags_s.size(); ++j) cost[j] = std::max(0.0, s_ee[j] - s_et[j] * s_et[j] / s_tt);
    return cost;
  };
  auto misfit = [&](const std::vector<CourseInterval>& set, double lag_s) { return misfits(set, {lag_s})[0]; };
  // Coarse grid (10 ms) over the whole range, then 1 ms around its best (the misfit is smooth in the lag:
  // the chords' mean headings average the gyro noise, which would otherwise make it rough on the scale of
  // an IMU sample and its curvature there, the sigma, 10x too confident).
  auto search = [&](const std::vector<CourseInterval>& set, ImuLatencyEstimate& est) {
    const double coarse_s = 1e-2, step_s = 1e-3;
    // The coarse grid itself in two passes: every 4th lag (40 ms: a chord spans 200 ms or more, so the
    // minimum is several of them wide), then 10 ms around the best of those.
    const int n_coarse = static_cast<int>(std::lround(o.max_lag_s / coarse_s));
    auto best_of = [&](const std::vector<int>& grid) {
      std::vector<double> lags_s;
      for (int i : grid) lags_s.push_back(i * coarse_s);
      const std::vector<double> cost = misfits(set, lags_s);
      size_t best = 0;
      for (size_t j = 1; j < cost.size(); ++j)
        if (cost[j] < cost[best] || (cost[j] == cost[best] && std::abs(grid[j]) < std::abs(grid[best]))) best = j;
      return grid[best];
    };
    std::vector<int> sparse;
    for (int i = -n_coarse; i <= n_coarse; i += 4) sparse.push_back(i);
    const int sparse_best = best_of(sparse);
    std::vector<int> dense;
    for (int i = std::max(-n_coarse, sparse_best - 6); i <= std::min(n_coarse, sparse_best + 6); ++i)
      dense.push_back(i);
    const double coarse_best_s = best_of(dense) * coarse_s;
    if (std::abs(coarse_best_s) >= o.max_lag_s - coarse_s) return false;  // at the edge of the search
    const int n = 20;                                                     // fine grid: coarse best +- 20 ms
    std::vector<double> fine_lags_s(2 * n + 1);
    for (int i = 0; i <= 2 * n; ++i) fine_lags_s[i] = coarse_best_s + (i - n) * step_s;
    const std::vector<double> cost = misfits(set, fine_lags_s);
    int best = 0;
    for (int i = 0; i <= 2 * n; ++i)
      if (cost[i] < cost[best]) best = i;
    if (best == 0 || best == 2 * n) return false;
    // Parabola through the minimum and its neighbours (a few steps apart for a stable curvature).
    const int w = std::min({5, best, 2 * n - best});
    const double c0 = cost[best - w], c1 = cost[best], c2 = cost[best + w], hstep = w * step_s;
    const double curvature = (c0 - 2.0 * c1 + c2) / (hstep * hstep);  // d2 cost / d lag2
    if (!(curvature > 0.0)) return false;
    const double offset = 0.5 * hstep * (c0 - c2) / (c0 - 2.0 * c1 + c2);
    est.lag_s = coarse_best_s + (best - n) * step_s + std::clamp(offset, -hstep, hstep);
    const double dof = std::max(1.0, static_cast<double>(set.size()) - 2.0);
    const double residual_var = std::max(misfit(set, est.lag_s), 0.0) / dof;
    est.residual_rms_rad = std::sqrt(residual_var);
    // cost = sum e^2: its Hessian is 2 J^T J, so var(lag) = sigma_e^2 (J^T J)^-1 = 2 sigma_e^2 / curvature.
    est.sigma_s = std::sqrt(2.0 * residual_var / curvature);
    est.valid = std::isfinite(est.lag_s) && std::isfinite(est.sigma_s);
    return est.valid;
  };
  if (!search(iv, out)) return out;
  // Again without the course changes a GNSS outlier made (a 2 m jump turns a 0.5 s chord by 20 deg): those
  // beyond 5 robust sigma of the first fit's residuals.
  std::vector<double> e = residuals(iv, out.lag_s), abs_e(e.size());
  for (size_t k = 0; k < e.size(); ++k) abs_e[k] = std::abs(e[k]);
  const double robust_sigma = 1.4826 * median_in_place(abs_e);
  std::vector<CourseInterval> kept;
  for (size_t k = 0; k < iv.size(); ++k)
    if (std::abs(e[k]) <= 5.0 * robust_sigma) kept.push_back(iv[k]);
  out.outlier_intervals = static_cast<int>(iv.size() - kept.size());
  const std::vector<CourseInterval>* used = &iv;
  if (kept.size() < iv.size() && static_cast<int>(kept.size()) >= o.min_intervals) {
    ImuLatencyEstimate again = out;
    if (search(kept, again)) out = again, used = &kept;  // else the first estimate stands
  }
  // Delete-a-group jackknife: var = (g-1)/g sum (lag_i - mean)^2 over the estimates without group i.
  const int g = o.jackknife_groups;
  if (g > 1 && static_cast<int>(used->size()) >= g * 4) {
    std::vector<double> lags;
    const size_t n = used->size();
    for (int i = 0; i < g; ++i) {
      const size_t begin = n * i / g, end = n * (i + 1) / g;
      std::vector<CourseInterval> rest(used->begin(), used->begin() + static_cast<long>(begin));
      rest.insert(rest.end(), used->begin() + static_cast<long>(end), used->end());
      ImuLatencyEstimate part = out;
      if (search(rest, part)) lags.push_back(part.lag_s);
    }
    if (static_cast<int>(lags.size()) == g) {
      double mean = 0.0, ss = 0.0;
      for (const double l : lags) mean += l / g;
      for (const double l : lags) ss += (l - mean) * (l - mean);
      out.sigma_s = std::sqrt((g - 1.0) / g * ss);
    }
  }
  return out;
}

}  // namespace ldv::est
