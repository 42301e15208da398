#pragma once
// Maximum-likelihood noise terms from the raw data (Whittle's approximation of the Gaussian
// likelihood in the frequency domain), the refinement of the Allan-curve fit.
//
// Why: an Allan variance curve condenses the data into a few dozen strongly correlated numbers and
// loses information about the terms that dominate only a short stretch of tau (README.md, Cramer-Rao
// table: 28 % on K for the tactical gyro from the curve). The periodogram of the differenced block
// means keeps it: every Fourier ordinate is an independent exponential variable with mean
// S(nu) = sum of coefficient^2 x block_difference_density (block_spectrum.hpp), and the likelihood
// weighs each of them by what it says.
//
// Terms: Q, N, B (flat) or the Gauss-Markov bias (sigma, T), K are estimated together (Q is not held at the
// curve fit's value: where it is weak against N, no record pins it, and N's interval must be over Q too); R,
// a ramp, is a constant in the differences: estimated from their taper-weighted mean against the noise the
// other terms put there. Not with a sinusoid in the model (a spectral line, not a density).
#include "toolbox/allan/avar_covariance.hpp"
#include "toolbox/allan/noise_fit.hpp"
#include "toolbox/allan/phase_series.hpp"

namespace ldv::allan {

struct WhittleSummary {
  double block_s = 0.0;  // tau_b: the rate is averaged over blocks of this length
  // The finest time scale at which a Gauss-Markov's shape can be told from white noise: block_s, or longer
  // where Q hides N above some frequency. T is searched from kGaussMarkovMinResolution times it.
  double gm_resolution_s = 0.0;
  long ordinates = 0;    // Fourier ordinates used (frequency 0 and Nyquist excluded)
  double log_likelihood = 0.0;
  int iterations = 0;  // scoring iterations at the final Gauss-Markov time constant
  // Free parameters of the model as fitted: the estimated densities (Q, N, B or GM sigma, K) plus the
  // GM time constant when the model has a GM (counted even when the GM came out absent / folded:
  // the model searched over it). R (not a density) is not counted.
  int parameters = 0;
  // The taper's variance factor (n sum h^4 / (sum h^2)^2, about 1.12): the tapered log-likelihood is
  // that much sharper than the information it holds, so likelihood ratios are divided by it.
  double taper_variance_factor = 1.0;
};

// `curve`: the Allan-curve fit of the same series (start values, Q and R, slope lines, misfit).
// Returns `curve` with Q, N, B / GM, K and R replaced by their likelihood estimates (value, sigma,
// interval, resolved; sigmas from the Fisher information, intervals from the profile likelihood). Throws
// std::invalid_argument when the series gives fewer than 64 blocks or the model has a sinusoid.
NoiseFit whittle_fit(const PhaseSeries& s, const NoiseFit& curve, const FitOptions& opt, double block_s,
                     WhittleSummary* summary = nullptr);

// Cramer-Rao bound of the likelihood fit: the expected 1-sigma of each term a sensor with these
// noise levels has, relative to its value, from `samples` samples at tau0 (the expected Fisher
// information of the tapered Whittle likelihood, the information the raw record holds). Terms at 0
// are not in the model and get 0; R is not a density (0). `gm_t` is the relative sd of T.
struct RelativeBounds {
  double q = 0.0, n = 0.0, b = 0.0, k = 0.0, gm_sigma = 0.0, gm_t = 0.0;
};
RelativeBounds whittle_cramer_rao(const NoiseLevels& truth, double tau0_s, long samples, double block_s);

// What a record of this sensor tells about its terms, taking the fit as the truth: the bound now
// and the record length [h] at which each resolved term reaches `target` (relative 1-sigma);
// 0: not resolved here, infinity: beyond 1000 h.
struct RecordInformation {
  RelativeBounds now;
  double target = 0.1;
  double hours_n = 0.0, hours_b = 0.0, hours_k = 0.0;  // hours_b: B or the GM sigma
};
RecordInformation record_information(const NoiseFit& fit, double tau0_s, long samples, double block_s, double target);

}  // namespace ldv::allan
