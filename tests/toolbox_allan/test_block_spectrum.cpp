// The densities of the differenced block means (block_spectrum.hpp) against two independent truths:
// their integral over frequency is twice the published Allan variance of each term at tau_b
// (IEEE Std 952), and the mean periodogram of simulated data follows them.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <unsupported/Eigen/FFT>
#include <vector>

#include "tests/toolbox_allan/sensor_sim.hpp"
#include "toolbox/allan/block_spectrum.hpp"

using namespace ldv::allan;

namespace {

double integral_over_band(ModelTerm t, double tau_b, double shape) {
  // Midpoint rule on [0, 1/2] (the density is even), fine enough for 1e-6.
  const int n = 200000;
  double s = 0.0;
  for (int i = 0; i < n; ++i) s += block_difference_density(t, (i + 0.5) / (2.0 * n), tau_b, shape);
  return 2.0 * s / (2.0 * n);
}

}  // namespace

TEST(BlockSpectrum, IntegralIsTwiceTheAllanVarianceOfEachTerm) {
  for (double tau_b : {0.005, 0.1, 2.0}) {
    for (ModelTerm t : {ModelTerm::kQ, ModelTerm::kN, ModelTerm::kB, ModelTerm::kK}) {
      EXPECT_NEAR(integral_over_band(t, tau_b, 0.0) / (2.0 * term_avar(t, tau_b)), 1.0, 1e-5)
          << model_term_name(t) << " at tau_b " << tau_b;
    }
    for (double gm_t : {0.01, 1.0, 50.0, 5000.0}) {
      EXPECT_NEAR(integral_over_band(ModelTerm::kGaussMarkov, tau_b, gm_t) /
                      (2.0 * term_avar(ModelTerm::kGaussMarkov, tau_b, gm_t)),
                  1.0, 1e-5)
          << "GM T " << gm_t << " at tau_b " << tau_b;
    }
  }
}

TEST(BlockSpectrum, SimulatedPeriodogramFollowsTheDensity) {
  // N + K + GM at 100 Hz, blocks of 0.1 s, 200 records of 2^12 blocks each: the averaged
  // periodogram in 8 frequency bands against the model (each band mean within 4 % ~ 4 sigma).
  test::SensorTruth truth;
  truth.n = 1e-3;
  truth.k = 2e-4;
  truth.gm_sigma = 3e-3;
  truth.gm_t_s = 2.0;
  const double dt = 0.01, tau_b = 0.1;
  const int m = 10, blocks = 4097, records = 200;
  std::vector<double> band_data(8, 0.0), band_model(8, 0.0);
  Eigen::FFT<double> fft;
  for (int rec = 0; rec < records; ++rec) {
    const auto y = test::simulate_rate(truth, dt, static_cast<long>(blocks) * m, 77u + rec);
    std::vector<double> ybar(blocks, 0.0), d(blocks - 1);
    for (int j = 0; j < blocks; ++j)
      for (int i = 0; i < m; ++i) ybar[j] += y[j * m + i] / m;
    for (int j = 0; j + 1 < blocks; ++j) d[j] = ybar[j + 1] - ybar[j];
    std::vector<std::complex<double>> spec;
    fft.fwd(spec, d);
    const int n = blocks - 1;
    for (int k = 1; k < n / 2; ++k) {
      const int band = std::min(7, static_cast<int>(16.0 * k / n));
      band_data[band] += std::norm(spec[k]) / n;
      const double nu = static_cast<double>(k) / n;
      band_model[band] +=
          truth.n * truth.n * block_difference_density(ModelTerm::kN, nu, tau_b) +
          truth.k * truth.k * block_difference_density(ModelTerm::kK, nu, tau_b) +
          truth.gm_sigma * truth.gm_sigma * block_difference_density(ModelTerm::kGaussMarkov, nu, tau_b, truth.gm_t_s);
    }
  }
  for (int b = 0; b < 8; ++b) EXPECT_NEAR(band_data[b] / band_model[b], 1.0, 0.04) << "band " << b;
}
