// The covariance of overlapping Allan variance estimates across tau (the metric of the GLS noise
// fit) against a Monte Carlo of the estimator itself: white PM + white FM + random-walk FM +
// Gauss-Markov, short series, variances within 8 % and correlations within 0.05.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "toolbox/allan/avar_covariance.hpp"

using namespace ldv::allan;

TEST(AvarCovariance, MatchesMonteCarloOfTheEstimator) {
  const long n_phase = 400;
  const double tau0 = 0.5;
  NoiseLevels lv;
  lv.q = 0.3, lv.n = 1.0, lv.k = 0.05, lv.gm_sigma = 0.7, lv.gm_t_s = 6.0;
  const std::vector<long> ms = {1, 3, 10, 30, 90};
  const size_t p = ms.size();
  const std::vector<double> c = oavar_covariance(lv, ms, tau0, n_phase);

  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  const int reps = 6000;
  const double phi = std::exp(-tau0 / lv.gm_t_s);
  std::vector<double> mean(p, 0.0), m2(p * p, 0.0), est(p), x(n_phase);
  std::vector<std::vector<double>> all(reps, std::vector<double>(p));
  for (int r = 0; r < reps; ++r) {
    double phase = 0.0, rw = 0.0, gm = lv.gm_sigma * g(rng);
    for (long i = 0; i < n_phase; ++i) {
      x[i] = phase + lv.q * g(rng);
      phase += (lv.n / std::sqrt(tau0) * g(rng) + rw + gm) * tau0;
      rw += lv.k * std::sqrt(tau0) * g(rng);
      gm = phi * gm + lv.gm_sigma * std::sqrt(1 - phi * phi) * g(rng);
    }
    for (size_t a = 0; a < p; ++a) {
      const long m = ms[a], n = n_phase - 2 * m;
      double s = 0.0;
      for (long i = 0; i < n; ++i) s += std::pow(x[i + 2 * m] - 2 * x[i + m] + x[i], 2);
      all[r][a] = s / (2.0 * n * std::pow(m * tau0, 2));
      mean[a] += all[r][a] / reps;
    }
  }
  for (int r = 0; r < reps; ++r)
    for (size_t a = 0; a < p; ++a)
      for (size_t b = 0; b < p; ++b) m2[a * p + b] += (all[r][a] - mean[a]) * (all[r][b] - mean[b]) / (reps - 1);
  for (size_t a = 0; a < p; ++a) {
    EXPECT_NEAR(c[a * p + a] / m2[a * p + a], 1.0, 0.08) << "m " << ms[a];
    for (size_t b = a + 1; b < p; ++b) {
      const double rc = c[a * p + b] / std::sqrt(c[a * p + a] * c[b * p + b]);
      const double rm = m2[a * p + b] / std::sqrt(m2[a * p + a] * m2[b * p + b]);
      EXPECT_NEAR(rc, rm, 0.05) << "m " << ms[a] << ", " << ms[b];
    }
  }
}

TEST(AvarCovariance, WhiteFmDiagonalIsGreenhallVariance) {
  // White FM, overlapping ADEV at m << N: var(avar) = 2 avar^2 / edf with the known
  // edf = (3(N-1)/(2m) - 2(N-2)/N) 4m^2 / (4m^2 + 5) (NIST SP 1065 table 5).
  const long n_phase = 100001;
  NoiseLevels lv;
  lv.n = 2.0;
  const std::vector<long> ms = {2, 20, 200};
  const std::vector<double> c = oavar_covariance(lv, ms, 1.0, n_phase);
  for (size_t a = 0; a < ms.size(); ++a) {
    const double m = static_cast<double>(ms[a]), n = static_cast<double>(n_phase);
    const double edf = (3.0 * (n - 1) / (2 * m) - 2.0 * (n - 2) / n) * 4 * m * m / (4 * m * m + 5);
    const double avar = lv.n * lv.n / m;
    EXPECT_NEAR(c[a * ms.size() + a] / (2 * avar * avar / edf), 1.0, 0.01) << "m " << ms[a];
  }
}
