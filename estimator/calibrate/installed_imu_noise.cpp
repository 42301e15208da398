#include "estimator/calibrate/installed_imu_noise.hpp"

#include <algorithm>
#include <cmath>

#include "common/geo/earth_model.hpp"

namespace ldv::est {
namespace {

double median3(Vec3 v) {
  std::sort(v.data(), v.data() + 3);
  return v(1);
}

}  // namespace

double InstalledImuNoise::psd_scale(const Vec3& arw_configured, const Vec3& vrw_configured) const {
  if (!found) return 1.0;
  const Vec3 g = arw_rad_per_sqrt_s.cwiseQuotient(arw_configured.cwiseMax(1e-12)).cwiseAbs2();
  const Vec3 a = vrw_mps_per_sqrt_s.cwiseQuotient(vrw_configured.cwiseMax(1e-12)).cwiseAbs2();
  return std::max({1.0, median3(g), median3(a)});
}

InstalledImuNoise measure_installed_imu_noise(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                                              double min_standstill_s, double max_speed_mps) {
  InstalledImuNoise out;
  if (imu.size() < 100 || gnss.size() < 3) return out;
  // The longest run of fixes that each stay within max_speed_mps of where the track is kStillWindow_s later.
  // The window, not the chord to the next fix: at 4 Hz, RTK's centimetre noise alone makes a 0.1 m/s chord.
  constexpr double kStillWindow_s = 1.0, kMaxWindow_s = 3.0;
  double best_t0 = 0, best_t1 = 0, run_t0 = gnss.front().t_s;
  bool in_run = false;
  size_t later = 0;
  for (size_t k = 0; k + 1 < gnss.size(); ++k) {
    later = std::max(later, k + 1);
    while (later < gnss.size() && gnss[later].t_s - gnss[k].t_s < kStillWindow_s) ++later;
    if (later == gnss.size()) break;
    const double dt = gnss[later].t_s - gnss[k].t_s;
    const bool still =
        dt <= kMaxWindow_s && earth::ned_between(gnss[k].pos, gnss[later].pos).norm() / dt < max_speed_mps;
    if (still && !in_run) run_t0 = gnss[k].t_s;
    in_run = still;
    if (still && gnss[later].t_s - run_t0 > best_t1 - best_t0) best_t0 = run_t0, best_t1 = gnss[later].t_s;
  }
  if (best_t1 - best_t0 < min_standstill_s) return out;
  // The scatter of the rates about their mean over the standstill (1 s margins: the stop's settling).
  Eigen::Matrix<double, 6, 1> sum = Eigen::Matrix<double, 6, 1>::Zero(), sum2 = sum;
  double sum_dt = 0.0;
  long n = 0;
  for (const ImuIncrement& s : imu) {
    if (s.t_s < best_t0 + 1.0 || s.t_s > best_t1 - 1.0 || !(s.dt_s > 0)) continue;
    Eigen::Matrix<double, 6, 1> rate;
    rate << s.dtheta_b_rad / s.dt_s, s.dvel_b_mps / s.dt_s;
    if (!rate.allFinite()) continue;
    sum += rate;
    sum2 += rate.cwiseAbs2();
    sum_dt += s.dt_s;
    ++n;
  }
  if (n < 50) return out;
  const double dt = sum_dt / n;
  const Eigen::Matrix<double, 6, 1> mean = sum / n;
  const Eigen::Matrix<double, 6, 1> sd = (sum2 / n - mean.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
  // A white rate noise of density N has a per-sample std N / sqrt(dt).
  out.arw_rad_per_sqrt_s = sd.head<3>() * std::sqrt(dt);
  out.vrw_mps_per_sqrt_s = sd.tail<3>() * std::sqrt(dt);
  out.standstill_s = best_t1 - best_t0;
  out.found = true;
  return out;
}

}  // namespace ldv::est
