#include "estimator/calibrate/gnss_velocity_check.hpp"

#include <algorithm>
#include <cmath>

#include "common/geo/earth_model.hpp"
#include "estimator/calibrate/gnss_track.hpp"

namespace ldv::est {

GnssVelocityCheck check_gnss_velocity(const std::vector<GnssFix>& gnss) {
  GnssVelocityCheck out;
  if (gnss.size() < 5) return out;
  const double nominal_dt = median_fix_interval_s(gnss);
  if (!(nominal_dt > 0.0)) return out;
  // Chord velocity and its variance at every fix with close neighbours (NAN elsewhere).
  struct Chord {
    double t_s;
    Eigen::Vector2d v, var;
    bool ok;
  };
  std::vector<Chord> chord(gnss.size(), Chord{0, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), false});
  for (size_t k = 1; k + 1 < gnss.size(); ++k) {
    const double span = gnss[k + 1].t_s - gnss[k - 1].t_s;
    chord[k].t_s = gnss[k].t_s;
    if (!(span > 0.0) || span > 3.0 * nominal_dt) continue;
    chord[k].v = earth::ned_between(gnss[k - 1].pos, gnss[k + 1].pos).head<2>() / span;
    chord[k].var = (gnss[k - 1].pos_std_ned_m.head<2>().cwiseAbs2() + gnss[k + 1].pos_std_ned_m.head<2>().cwiseAbs2()) /
                   (span * span);
    chord[k].ok = true;
  }
  // Misfit with the reported velocity taken as true at t_k - lag (chord interpolated between fixes).
  auto misfit = [&](double lag_s, int* count) {
    double sum = 0.0;
    int n = 0;
    for (size_t k = 2; k + 2 < gnss.size(); ++k) {
      if (!gnss[k].has_velocity || !chord[k].ok) continue;
      const double t = gnss[k].t_s - lag_s;
      size_t j = k;
      while (j > 1 && chord[j].t_s > t) --j;
      while (j + 2 < gnss.size() && chord[j + 1].t_s <= t) ++j;
      if (!chord[j].ok || !chord[j + 1].ok || chord[j + 1].t_s - chord[j].t_s > 3.0 * nominal_dt) continue;
      const double a = std::clamp((t - chord[j].t_s) / (chord[j + 1].t_s - chord[j].t_s), 0.0, 1.0);
      const Eigen::Vector2d vc = (1 - a) * chord[j].v + a * chord[j + 1].v;
      const Eigen::Vector2d var = gnss[k].vel_std_n_mps.head<2>().cwiseAbs2() + chord[k].var;
      const Eigen::Vector2d e = gnss[k].vel_n_mps.head<2>() - vc;
      if (!e.allFinite() || !(var.minCoeff() > 0.0)) continue;
      sum += 0.5 * (e.array().square() / var.array()).sum();
      ++n;
    }
    if (count) *count = n;
    return n > 0 ? sum / n : 0.0;
  };
  out.normalised_mse = misfit(0.0, &out.compared);
  out.normalised_mse_at_lag = out.normalised_mse;
  for (int i = -100; i <= 100; ++i) {
    const double m = misfit(0.005 * i, nullptr);
    if (m < out.normalised_mse_at_lag) {
      out.normalised_mse_at_lag = m;
      out.best_lag_s = 0.005 * i;
    }
  }
  out.lag_statistic = 2.0 * out.compared * (out.normalised_mse - out.normalised_mse_at_lag);
  return out;
}

}  // namespace ldv::est
