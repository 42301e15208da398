#include "estimator/calibrate/installed_imu_noise.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <unsupported/Eigen/FFT>
#include <vector>

#include "common/geo/earth_model.hpp"
#include "estimator/calibrate/gnss_track.hpp"

namespace ldv::est {
namespace {

double median3(Vec3 v) {
  std::sort(v.data(), v.data() + 3);
  return v(1);
}

// The white part of bin powers p_j whose mean is a (1 + rho g_j): white noise a plus the quantisation's
// a rho g_j (g = 4 sin^2(pi f dt), rising as f^2). For the right rho the powers divided by (1 + rho g_j) are
// white: their median is the same over the lower and the upper half of the band. rho by bisection on that
// balance (the lower half's median over the upper's grows with rho), a = the median of the divided powers over
// ln 2. Medians, not means or a likelihood: an engine's harmonics put their power into a few bins. A flat
// spectrum (the upper half's median within `rising` of the lower half's) or too few bins to tell: every bin
// counts as white (rho 0: a second part fitted to a flat spectrum only adds scatter).
double white_part(const std::vector<double>& p, const std::vector<double>& g, double rising) {
  std::vector<double> divided(p.size());
  const auto white_at = [&](double rho) {
    for (size_t j = 0; j < p.size(); ++j) divided[j] = p[j] / (1.0 + rho * g[j]);
    return median_in_place(divided) / std::log(2.0);
  };
  const size_t half = p.size() / 2;
  std::vector<double> low(half), high(p.size() - half);
  auto imbalance = [&](double rho) {  // ln(median of the upper half / median of the lower half), divided
    for (size_t j = 0; j < half; ++j) low[j] = p[j] / (1.0 + rho * g[j]);
    for (size_t j = half; j < p.size(); ++j) high[j - half] = p[j] / (1.0 + rho * g[j]);
    return std::log(median_in_place(high) / median_in_place(low));
  };
  if (p.size() < 32 || !(imbalance(0.0) > std::log(rising))) return white_at(0.0);
  double lo = 1e-3 / g.back(), hi = 1e12 / std::max(g.front(), 1e-300);  // rho from negligible to all-Q
  if (imbalance(hi) >= 0.0) lo = hi;                                    // rising faster than f^2: all Q
  for (int k = 0; k < 80 && hi / lo > 1.0001; ++k) {
    const double mid = std::sqrt(lo * hi);
    (imbalance(mid) > 0.0 ? lo : hi) = mid;
  }
  return white_at(std::sqrt(lo * hi));
}

// The white-noise density N^2 [unit^2 s] of a rate series (dt apart), from its periodogram's bins from
// kBandLow_Hz to kBandHigh_Hz or 0.4 of the sample rate (Hann-windowed segments, half overlapping, each
// detrended): the median of the bins over ln 2 (a noise's bin powers are exponential: median = ln 2 x mean).
// The median, not the mean or the sample-to-sample scatter: an engine's harmonics (25 Hz and up at idle) put
// their power into a few bins, and counted as white they made a vibrating car's accelerometer floor 3x its true
// noise; they integrate to nothing. When the upper half of the band stands above the lower half by more than
// kRising (a white spectrum's halves agree to about 10 %), the quantisation's part (a white error of the
// integrated angle or velocity, rate density rising as f^2, integrating to nothing too) is split off
// (white_part). Counted as white, the paper's HG1700 gyro quantisation (6-17 arcsec at 100 Hz) read as 700x its
// ARW. NaN when the series is too short for one segment with bins in the band. bins_used: how many bins the
// median was taken over (its sigma, psd_relative_sigma).
double white_psd(const std::vector<double>& r, double dt, size_t& bins_used) {
  constexpr double kBandLow_Hz = 0.5, kBandHigh_Hz = 40.0, kSegment_s = 4.0, kRising = 1.3;
  constexpr int kMaxSegments = 8;  // 18 s of standstill: ~1,300 bins, 4 % on the PSD (and a bounded cost)
  const size_t n = r.size();
  const size_t seg = std::min(n, static_cast<size_t>(std::lround(kSegment_s / dt)));
  if (seg < 16) return NAN;
  const double df = 1.0 / (seg * dt);
  const size_t j0 = static_cast<size_t>(std::ceil(std::max(kBandLow_Hz, 2.0 * df) / df));
  const size_t j1 = static_cast<size_t>(std::floor(std::min(kBandHigh_Hz, 0.4 / dt) / df));
  if (j1 < j0) return NAN;
  std::vector<double> w(seg), x(seg);
  std::vector<std::pair<double, double>> bins;  // (frequency, power)
  std::vector<std::complex<double>> spectrum;
  Eigen::FFT<double> fft;
  double sum_w2 = 0.0;
  for (size_t k = 0; k < seg; ++k) {
    w[k] = 0.5 - 0.5 * std::cos(2.0 * M_PI * (k + 0.5) / seg);
    sum_w2 += w[k] * w[k];
  }
  int segments = 0;
  for (size_t start = 0; start + seg <= n && segments < kMaxSegments; start += seg / 2, ++segments) {
    // Least-squares line through the segment taken out (the mean rate and a slow drift).
    double st = 0, sy = 0, stt = 0, sty = 0;
    for (size_t k = 0; k < seg; ++k) {
      const double t = static_cast<double>(k), y = r[start + k];
      st += t, sy += y, stt += t * t, sty += t * y;
    }
    const double slope = (seg * sty - st * sy) / (seg * stt - st * st), offset = (sy - slope * st) / seg;
    for (size_t k = 0; k < seg; ++k) x[k] = w[k] * (r[start + k] - offset - slope * static_cast<double>(k));
    fft.fwd(spectrum, x);
    // Two-sided PSD: mean N^2 for white rate noise of density N (per-sample variance N^2 / dt).
    for (size_t j = j0; j <= j1; ++j) bins.emplace_back(j * df, dt * std::norm(spectrum[j]) / sum_w2);
  }
  std::sort(bins.begin(), bins.end());
  std::vector<double> p(bins.size()), g(bins.size());
  for (size_t j = 0; j < bins.size(); ++j) {
    p[j] = bins[j].second;
    g[j] = 4.0 * std::pow(std::sin(M_PI * bins[j].first * dt), 2);
  }
  bins_used = p.size();
  return white_part(p, g, kRising);
}

// The median over consecutive windows of window_s of the std of |f| (the rates' last three components).
double windowed_norm_scatter(const std::vector<Eigen::Matrix<double, 6, 1>>& rates, double dt, double window_s) {
  const size_t n = std::max<size_t>(2, static_cast<size_t>(std::lround(window_s / dt)));
  std::vector<double> stds;
  for (size_t start = 0; start + n <= rates.size(); start += n) {
    double sum = 0.0, sum2 = 0.0;
    for (size_t k = start; k < start + n; ++k) {
      const double f = rates[k].tail<3>().norm();
      sum += f;
      sum2 += f * f;
    }
    const double mean = sum / static_cast<double>(n);
    stds.push_back(std::sqrt(std::max(0.0, sum2 / static_cast<double>(n) - mean * mean)));
  }
  return stds.empty() ? 0.0 : median_in_place(stds);
}

// The relative 1-sigma of a white PSD taken as the median of n periodogram bins over ln 2. The sample median of n
// independent exponential powers of mean m has the sigma m / sqrt(n) (1 / (2 sqrt(n) f(median)), f = e^-ln2 / m),
// a relative sigma of 1 / (ln 2 sqrt(n)). The bins are not independent: a Hann window correlates a bin's complex
// value with its neighbour's by -2/3 and the next by 1/6 (powers: 4/9 and 1/36), and half-overlapping segments the
// same bin's by 1/6 (power: 1/36); n counts as n / ((1 + 2 (4/9 + 1/36)) (1 + 2/36)) independent bins.
double psd_median_relative_sigma(size_t bins) {
  if (bins == 0) return NAN;
  constexpr double kCorrelatedBins = (1.0 + 2.0 * (4.0 / 9.0 + 1.0 / 36.0)) * (1.0 + 2.0 / 36.0);
  return std::sqrt(kCorrelatedBins / static_cast<double>(bins)) / std::log(2.0);
}

}  // namespace

ImuNoiseScale InstalledImuNoise::psd_scale_sigma(const Vec3& arw_configured, const Vec3& vrw_configured) const {
  if (!found) return {NAN, NAN};
  const ImuNoiseScale raw = psd_scale_unbounded(arw_configured, vrw_configured);
  return {raw.gyro * psd_relative_sigma, raw.accel * psd_relative_sigma};
}

ImuNoiseScale InstalledImuNoise::psd_scale_unbounded(const Vec3& arw_configured, const Vec3& vrw_configured) const {
  const Vec3 g = arw_rad_per_sqrt_s.cwiseQuotient(arw_configured.cwiseMax(1e-12)).cwiseAbs2();
  const Vec3 a = vrw_mps_per_sqrt_s.cwiseQuotient(vrw_configured.cwiseMax(1e-12)).cwiseAbs2();
  return {median3(g), median3(a)};
}

ImuNoiseScale InstalledImuNoise::psd_scale(const Vec3& arw_configured, const Vec3& vrw_configured) const {
  if (!found) return {};
  const ImuNoiseScale raw = psd_scale_unbounded(arw_configured, vrw_configured);
  return {std::max(1.0, raw.gyro), std::max(1.0, raw.accel)};
}

InstalledImuNoise measure_installed_imu_noise(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                                              double min_standstill_s, double max_speed_mps) {
  InstalledImuNoise out;
  if (imu.size() < 100 || gnss.size() < 3) return out;
  // The longest run of fixes that each stay within max_speed_mps of where the track is kStillWindow_s later,
  // horizontally, beyond the fixes' own noise (kNoiseSigmas of the chord's stated std). The window, not the chord
  // to the next fix: at 4 Hz, RTK's centimetre noise alone makes a 0.1 m/s chord; at 1 Hz the 1 s chord of a
  // 2 cm RTK moves at 3 cm/s, and over 5 cm/s in one window in five.
  constexpr double kStillWindow_s = 1.0, kMaxWindow_s = 3.0, kNoiseSigmas = 4.0;
  double best_t0 = 0, best_t1 = 0, run_t0 = gnss.front().t_s;
  bool in_run = false;
  size_t later = 0;
  for (size_t k = 0; k + 1 < gnss.size(); ++k) {
    later = std::max(later, k + 1);
    while (later < gnss.size() && gnss[later].t_s - gnss[k].t_s < kStillWindow_s) ++later;
    if (later == gnss.size()) break;
    const double dt = gnss[later].t_s - gnss[k].t_s;
    const double chord_std_m =
        std::hypot(gnss[k].pos_std_ned_m.head<2>().maxCoeff(), gnss[later].pos_std_ned_m.head<2>().maxCoeff());
    const double moved_m = earth::ned_between(gnss[k].pos, gnss[later].pos).head<2>().norm();
    const bool still = dt <= kMaxWindow_s && moved_m < max_speed_mps * dt + kNoiseSigmas * chord_std_m;
    if (still && !in_run) run_t0 = gnss[k].t_s;
    in_run = still;
    if (still && gnss[later].t_s - run_t0 > best_t1 - best_t0) best_t0 = run_t0, best_t1 = gnss[later].t_s;
  }
  if (best_t1 - best_t0 < min_standstill_s) return out;
  // The rates over the standstill (1 s margins: the stop's settling).
  std::vector<Eigen::Matrix<double, 6, 1>> rates;
  double sum_dt = 0.0;
  for (const ImuIncrement& s : imu) {
    if (s.t_s < best_t0 + 1.0 || s.t_s > best_t1 - 1.0 || !(s.dt_s > 0)) continue;
    Eigen::Matrix<double, 6, 1> rate;
    rate << s.dtheta_b_rad / s.dt_s, s.dvel_b_mps / s.dt_s;
    if (!rate.allFinite()) continue;
    rates.push_back(rate);
    sum_dt += s.dt_s;
  }
  if (rates.size() < 50) return out;
  const double dt = sum_dt / static_cast<double>(rates.size());
  Eigen::Matrix<double, 6, 1> density;
  for (int axis = 0; axis < 6; ++axis) {
    std::vector<double> r(rates.size());
    for (size_t k = 0; k < r.size(); ++k) r[k] = rates[k](axis);
    size_t bins = 0;
    const double psd = white_psd(r, dt, bins);
    if (!(psd >= 0.0)) return out;
    out.psd_relative_sigma = psd_median_relative_sigma(bins);
    density(axis) = std::sqrt(psd);
  }
  out.f_norm_scatter_mps2 = windowed_norm_scatter(rates, dt, InstalledImuNoise::kSpecificForceWindow_s);
  out.arw_rad_per_sqrt_s = density.head<3>();
  out.vrw_mps_per_sqrt_s = density.tail<3>();
  out.standstill_s = best_t1 - best_t0;
  out.found = true;
  return out;
}

}  // namespace ldv::est
