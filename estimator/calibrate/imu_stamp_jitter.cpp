#include "estimator/calibrate/imu_stamp_jitter.hpp"

#include <algorithm>
#include <cmath>

#include "estimator/calibrate/gnss_track.hpp"

namespace ldv::est {
namespace {

Eigen::Matrix<double, 6, 1> rates_of(const ImuIncrement& s) {
  Eigen::Matrix<double, 6, 1> r;
  r << s.dtheta_b_rad / s.dt_s, s.dvel_b_mps / s.dt_s;
  return r;
}

// The same reading under a new tag: the rates agree to rounding (the reader multiplied them by the interval).
bool same_sample(const Eigen::Matrix<double, 6, 1>& a, const Eigen::Matrix<double, 6, 1>& b) {
  for (int i = 0; i < 6; ++i)
    if (std::abs(a(i) - b(i)) > 1e-9 * std::max(std::abs(a(i)), std::abs(b(i))) + 1e-15) return false;
  return true;
}

// The residual std of tags t about the line a + T k, k the sample's count in the window. A window with a lost
// sample (its tags step by two intervals) reads large and the median over the windows passes it by; telling a lost
// sample by its longer step fails where the tags scatter by a good part of the interval (a read 16 ms after the one
// before, at 100 Hz, is one sample late, not two). NaN when the window is degenerate.
double grid_residual(const std::vector<double>& t, double& interval_s) {
  const size_t n = t.size();
  double sk = 0, st = 0, skk = 0, skt = 0;
  for (size_t j = 0; j < n; ++j) {
    const double k = static_cast<double>(j), y = t[j] - t[0];
    sk += k, st += y, skk += k * k, skt += k * y;
  }
  const double den = n * skk - sk * sk;
  if (!(den > 0.0)) return NAN;
  const double b = (n * skt - sk * st) / den, a = (st - b * sk) / n;
  double ss = 0.0;
  for (size_t j = 0; j < n; ++j) ss += std::pow(t[j] - t[0] - a - b * static_cast<double>(j), 2);
  interval_s = b;
  return b > 0.0 ? std::sqrt(ss / static_cast<double>(n - 2)) : NAN;
}

}  // namespace

ImuStampJitter measure_imu_stamp_jitter(const std::vector<ImuIncrement>& imu) {
  std::vector<double> tags;  // the first tag of each distinct sample
  tags.reserve(imu.size());
  long rows = 0, repeats = 0;
  Eigen::Matrix<double, 6, 1> previous;
  bool have_previous = false;
  for (const ImuIncrement& s : imu) {
    if (!(s.dt_s > 0.0) || !std::isfinite(s.t_s)) continue;
    const Eigen::Matrix<double, 6, 1> r = rates_of(s);
    if (!r.allFinite()) continue;
    ++rows;
    if (have_previous && same_sample(r, previous)) {
      ++repeats;
      continue;
    }
    tags.push_back(s.t_s);
    previous = r;
    have_previous = true;
  }
  return measure_imu_stamp_jitter(tags, rows, repeats);
}

ImuStampJitter measure_imu_stamp_jitter(const std::vector<double>& tags, long rows, long repeated_rows) {
  ImuStampJitter out;
  if (rows > 0) out.repeated_fraction = static_cast<double>(repeated_rows) / static_cast<double>(rows);
  std::vector<double> sigmas, intervals;
  const size_t w = ImuStampJitter::kWindowSamples;
  for (size_t start = 0; start + w <= tags.size(); start += w) {
    const std::vector<double> window(tags.begin() + start, tags.begin() + start + w);
    double interval_s = 0.0;
    const double sigma = grid_residual(window, interval_s);
    if (!std::isfinite(sigma)) continue;
    sigmas.push_back(sigma);
    intervals.push_back(interval_s);
  }
  if (sigmas.size() < 3) return out;
  out.windows = static_cast<int>(sigmas.size());
  out.sigma_s = median_in_place(sigmas);
  std::vector<double> deviation(sigmas.size());
  for (size_t j = 0; j < sigmas.size(); ++j) deviation[j] = std::abs(sigmas[j] - out.sigma_s);
  // The median's sigma: sqrt(pi/2) times the mean's, the mean's the robust spread over sqrt(windows).
  out.sigma_sigma_s = 1.2533 * 1.4826 * median_in_place(deviation) / std::sqrt(static_cast<double>(sigmas.size()));
  out.sample_interval_s = median_in_place(intervals);
  out.found = true;
  return out;
}

}  // namespace ldv::est
