#pragma once
// Simulated inertial sensor rates with known noise terms (DESIGN.md section 5 oracles):
// white noise of std N/sqrt(dt) per sample, a rate random walk with increments K sqrt(dt), a
// first-order Gauss-Markov bias (sigma, T) and a ramp R t.
#include <cmath>
#include <random>
#include <vector>

namespace ldv::allan::test {

struct SensorTruth {
  double n = 0.0;         // unit/sqrt(Hz)  (unit = rad/s, m/s^2, ...)
  double k = 0.0;         // unit/sqrt(s)
  double gm_sigma = 0.0;  // unit
  double gm_t_s = 1.0;    // s
  double r = 0.0;         // unit/s
  double bias = 0.0;      // unit, constant
};

inline std::vector<double> simulate_rate(const SensorTruth& t, double dt, long samples, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> y(samples);
  const double white = t.n / std::sqrt(dt), walk = t.k * std::sqrt(dt);
  const double phi = std::exp(-dt / t.gm_t_s), drive = t.gm_sigma * std::sqrt(1.0 - phi * phi);
  double rw = 0.0, gm = t.gm_sigma * g(rng);
  for (long i = 0; i < samples; ++i) {
    y[i] = t.bias + white * g(rng) + rw + gm + t.r * i * dt;
    rw += walk * g(rng);
    gm = phi * gm + drive * g(rng);
  }
  return y;
}

// The paper's Q: an additive white error of std q on the integrated quantity (each sample's rate gets
// (e_k - e_{k-1}) / dt; Allan variance 3 q^2 / tau^2).
inline void add_quantisation(std::vector<double>& y, double dt, double q, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, q);
  double previous = g(rng);
  for (double& v : y) {
    const double e = g(rng);
    v += (e - previous) / dt;
    previous = e;
  }
}

}  // namespace ldv::allan::test
