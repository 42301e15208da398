#include "toolbox/allan/deviation.hpp"

#include <cmath>
#include <stdexcept>

namespace ldv::allan {
namespace {

// Sums of squared differences. Four accumulators break the floating-point dependency chain
// (the compiler may not reassociate), which roughly triples the throughput of these loops.

// sum_{i in [0, n) step s} (x[i+2m] - 2 x[i+m] + x[i])^2
double sum_sq_second_difference(const double* x, long n, long m, long step) {
  double a0 = 0, a1 = 0, a2 = 0, a3 = 0;
  const double* p0 = x;
  const double* p1 = x + m;
  const double* p2 = x + 2 * m;
  long i = 0;
  if (step == 1) {
    for (; i + 4 <= n; i += 4) {
      const double d0 = p2[i] - 2.0 * p1[i] + p0[i];
      const double d1 = p2[i + 1] - 2.0 * p1[i + 1] + p0[i + 1];
      const double d2 = p2[i + 2] - 2.0 * p1[i + 2] + p0[i + 2];
      const double d3 = p2[i + 3] - 2.0 * p1[i + 3] + p0[i + 3];
      a0 += d0 * d0;
      a1 += d1 * d1;
      a2 += d2 * d2;
      a3 += d3 * d3;
    }
  }
  for (; i < n; i += step) {
    const double d = p2[i] - 2.0 * p1[i] + p0[i];
    a0 += d * d;
  }
  return (a0 + a1) + (a2 + a3);
}

// sum_{i in [0, n) step s} (x[i+3m] - 3 x[i+2m] + 3 x[i+m] - x[i])^2
double sum_sq_third_difference(const double* x, long n, long m, long step) {
  double a0 = 0, a1 = 0, a2 = 0, a3 = 0;
  const double* p0 = x;
  const double* p1 = x + m;
  const double* p2 = x + 2 * m;
  const double* p3 = x + 3 * m;
  long i = 0;
  if (step == 1) {
    for (; i + 4 <= n; i += 4) {
      const double d0 = p3[i] - 3.0 * (p2[i] - p1[i]) - p0[i];
      const double d1 = p3[i + 1] - 3.0 * (p2[i + 1] - p1[i + 1]) - p0[i + 1];
      const double d2 = p3[i + 2] - 3.0 * (p2[i + 2] - p1[i + 2]) - p0[i + 2];
      const double d3 = p3[i + 3] - 3.0 * (p2[i + 3] - p1[i + 3]) - p0[i + 3];
      a0 += d0 * d0;
      a1 += d1 * d1;
      a2 += d2 * d2;
      a3 += d3 * d3;
    }
  }
  for (; i < n; i += step) {
    const double d = p3[i] - 3.0 * (p2[i] - p1[i]) - p0[i];
    a0 += d * d;
  }
  return (a0 + a1) + (a2 + a3);
}

// Modified Allan: sum_{j=0}^{n-1} (w_j)^2 with w_j = sum_{i=j}^{j+m-1} x[i+2m] - 2x[i+m] + x[i].
// The window is carried along j: w_j - w_{j-1} = x[j+3m-1] - 3x[j+2m-1] + 3x[j+m-1] - x[j-1], a third
// difference of x (O(N) per m, and unlike a cumulative sum of x it never subtracts huge numbers).
// Four windows walk four quarters of the range side by side: independent add chains, and the
// rounding of each running sum accumulates over a quarter of the steps only.
double sum_sq_windowed_second_difference(const double* x, long n, long m) {
  auto d2 = [x, m](long i) { return x[i + 2 * m] - 2.0 * x[i + m] + x[i]; };
  auto step = [x, m](long j) { return x[j + 3 * m - 1] - 3.0 * (x[j + 2 * m - 1] - x[j + m - 1]) - x[j - 1]; };
  constexpr int kLanes = 4;
  const long quarter = n / kLanes;
  long start[kLanes];
  double window[kLanes], acc[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    start[l] = l * quarter;
    window[l] = 0.0;
    for (long i = start[l]; i < start[l] + m; ++i) window[l] += d2(i);
    acc[l] = window[l] * window[l];
  }
  for (long k = 1; k < quarter; ++k) {
    for (int l = 0; l < kLanes; ++l) {
      window[l] += step(start[l] + k);
      acc[l] += window[l] * window[l];
    }
  }
  // The remainder (n not divisible by 4, or n < 4) continues the last lane.
  double tail = 0.0;
  long j = quarter > 0 ? start[kLanes - 1] + quarter : 0;
  double w = window[kLanes - 1];
  if (quarter == 0) {
    w = 0.0;
    for (long i = 0; i < m; ++i) w += d2(i);
    tail = w * w;
    j = 1;
  }
  for (; j < n; ++j) {
    w += step(j);
    tail += w * w;
  }
  return quarter > 0 ? (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail : tail;
}

}  // namespace

const char* deviation_name(Deviation d) {
  switch (d) {
    case Deviation::kAdev: return "adev";
    case Deviation::kOadev: return "oadev";
    case Deviation::kMdev: return "mdev";
    case Deviation::kHdev: return "hdev";
    case Deviation::kOhdev: return "ohdev";
    case Deviation::kTdev: return "tdev";
  }
  return "?";
}

Deviation parse_deviation(const std::string& name) {
  for (Deviation d : {Deviation::kAdev, Deviation::kOadev, Deviation::kMdev, Deviation::kHdev,
                      Deviation::kOhdev, Deviation::kTdev}) {
    if (name == deviation_name(d)) return d;
  }
  throw std::invalid_argument("unknown deviation '" + name + "' (expected adev, oadev, mdev, hdev, ohdev or tdev)");
}

long analysis_points(Deviation d, long n_phase, long m) {
  if (m < 1 || n_phase < 2) return 0;
  long n = 0;
  switch (d) {
    case Deviation::kAdev: n = (n_phase - 1) / m - 1; break;
    case Deviation::kOadev: n = n_phase - 2 * m; break;
    case Deviation::kMdev:
    case Deviation::kTdev: n = n_phase - 3 * m + 1; break;
    case Deviation::kHdev: n = (n_phase - 1) / m - 2; break;
    case Deviation::kOhdev: n = n_phase - 3 * m; break;
  }
  return n > 0 ? n : 0;
}

long max_averaging_factor(Deviation d, long n_phase) {
  switch (d) {
    case Deviation::kAdev:
    case Deviation::kOadev: return (n_phase - 1) / 2;
    case Deviation::kMdev:
    case Deviation::kTdev:
    case Deviation::kHdev:
    case Deviation::kOhdev: return (n_phase - 1) / 3;
  }
  return 0;
}

DeviationPoint deviation_at(const std::vector<double>& x, double tau0_s, Deviation d, long m) {
  const long n_phase = static_cast<long>(x.size());
  const long n = analysis_points(d, n_phase, m);
  if (m < 1) throw std::invalid_argument("averaging factor must be >= 1");
  if (n < 1) {
    throw std::invalid_argument(std::string(deviation_name(d)) + " at tau = " + std::to_string(m * tau0_s) +
                                " s: too few samples (" + std::to_string(n_phase) + " phase points allow m <= " +
                                std::to_string(max_averaging_factor(d, n_phase)) + ", asked m = " +
                                std::to_string(m) + ")");
  }
  const double tau = m * tau0_s;
  const double mm = static_cast<double>(m);
  double var = 0.0;
  switch (d) {
    case Deviation::kAdev:
      var = sum_sq_second_difference(x.data(), n * m, m, m) / (2.0 * n * tau * tau);
      break;
    case Deviation::kOadev:
      var = sum_sq_second_difference(x.data(), n, m, 1) / (2.0 * n * tau * tau);
      break;
    case Deviation::kMdev:
    case Deviation::kTdev:
      var = sum_sq_windowed_second_difference(x.data(), n, m) / (2.0 * mm * mm * n * tau * tau);
      break;
    case Deviation::kHdev:
      var = sum_sq_third_difference(x.data(), n * m, m, m) / (6.0 * n * tau * tau);
      break;
    case Deviation::kOhdev:
      var = sum_sq_third_difference(x.data(), n, m, 1) / (6.0 * n * tau * tau);
      break;
  }
  DeviationPoint p;
  p.m = m;
  p.tau_s = tau;
  p.n_terms = n;
  p.dev = std::sqrt(var);
  if (d == Deviation::kTdev) p.dev *= tau / std::sqrt(3.0);
  return p;
}

std::vector<DeviationPoint> deviations(const std::vector<double>& x, double tau0_s, Deviation d,
                                       const std::vector<long>& ms) {
  std::vector<DeviationPoint> out;
  out.reserve(ms.size());
  for (long m : ms) out.push_back(deviation_at(x, tau0_s, d, m));
  return out;
}

}  // namespace ldv::allan
