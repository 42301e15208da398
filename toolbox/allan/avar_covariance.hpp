#pragma once
// Covariance of fully overlapping Allan variance estimates at several averaging factors, for a
// Gaussian noise model: white PM (Q), white FM (N), flicker FM (B), random-walk FM (K) and a
// first-order Gauss-Markov rate (sigma, T), and a deterministic rate ramp R (whose constant second
// difference multiplies the noise: + 4 mu1 mu2 Cov(mean D1, mean D2), mu = R tau / sqrt(2)). A
// sinusoid is not modelled.
//
// With D_i = (x[i+2m] - 2x[i+m] + x[i]) / (sqrt(2) tau), the estimate is avar(m) = mean of D_i^2
// over n = N - 2m terms, and for a Gaussian process (Isserlis)
//   Cov(avar(m1), avar(m2)) = 2 / (n1 n2) sum_k cnt(k) r12(k)^2,   r12(k) = Cov(D1_i, D2_{i+k}),
// cnt(k) the number of index pairs with that lag. r12 comes from the generalized autocovariance of
// the phase G(t) (a second difference annihilates the polynomial part), term by term:
//   Q: Q^2 [t = 0];  N: -N^2 |t| / 2;  B: B^2 t^2 ln|t| / (2 pi);  K: K^2 |t|^3 / 12;
//   GM: -sigma^2 T^2 (|t|/T - 1 + exp(-|t|/T))
// (each reproduces the term's Allan variance of noise_model.hpp on the diagonal). r12 is smooth
// between the nine lags where two of the difference points coincide; the sum over k is exact on
// short stretches and Gauss-Legendre with an Euler-Maclaurin end correction on long ones, so a
// full matrix over 40 taus of hours of data costs milliseconds, independent of N.
#include <vector>

namespace ldv::allan {

struct NoiseLevels {  // coefficients, not squared (SI of the rate, as noise_fit.hpp)
  double q = 0.0, n = 0.0, b = 0.0, k = 0.0;
  double gm_sigma = 0.0, gm_t_s = 0.0;
  double r = 0.0;  // rate ramp, unit/s
};

// Row-major ms.size() x ms.size() covariance of the overlapping Allan variance estimates at the
// averaging factors ms (each with N - 2m >= 1 terms) of n_phase phase points sampled every tau0_s.
std::vector<double> oavar_covariance(const NoiseLevels& levels, const std::vector<long>& ms, double tau0_s,
                                     long n_phase);

}  // namespace ldv::allan
