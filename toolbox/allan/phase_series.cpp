#include "toolbox/allan/phase_series.hpp"

#include <algorithm>

namespace ldv::allan {

PhaseSeries phase_from_rates(std::vector<double>&& y, double tau0_s, std::string name, std::string unit) {
  PhaseSeries s;
  s.name = std::move(name);
  s.unit = std::move(unit);
  s.tau0_s = tau0_s;
  s.source = DataKind::kFrequency;
  // Two-level mean (blocks of 4096) so the mean of hours of data keeps full precision.
  double mean = 0.0;
  const size_t n = y.size();
  for (size_t b = 0; b < n; b += 4096) {
    double block = 0.0;
    const size_t e = std::min(n, b + 4096);
    for (size_t i = b; i < e; ++i) block += y[i];
    mean += block;
  }
  mean = n ? mean / static_cast<double>(n) : 0.0;
  s.mean_rate = mean;
  double phase = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double yi = y[i];
    y[i] = phase;
    phase += (yi - mean) * tau0_s;
  }
  y.push_back(phase);
  s.x = std::move(y);
  return s;
}

PhaseSeries phase_from_phase(std::vector<double>&& x, double tau0_s, std::string name, std::string unit) {
  PhaseSeries s;
  s.name = std::move(name);
  s.unit = std::move(unit);
  s.tau0_s = tau0_s;
  s.source = DataKind::kPhase;
  const size_t n = x.size();
  if (n >= 2) {
    const double x0 = x.front();
    const double slope = (x.back() - x0) / static_cast<double>(n - 1);
    s.mean_rate = slope / tau0_s;
    for (size_t i = 0; i < n; ++i) x[i] -= x0 + slope * static_cast<double>(i);
  }
  s.x = std::move(x);
  return s;
}

}  // namespace ldv::allan
