#pragma once
// Identification of the inertial-sensor noise terms from an overlapping Allan deviation:
//  - weighted non-negative least squares of the Allan variance model (noise_model.hpp), weights
//    from the variance of each Allan variance estimate, 2 sigma^4 / edf, evaluated at the model
//    (iteratively re-weighted, so low points are not over-weighted);
//  - parameter covariance, a 95 % interval and a resolved / not-resolved flag per term;
//  - the paper's slope lines (-1, -1/2, 0, +1/2, +1) as a second opinion;
//  - a misfit per decade of tau, and which excluded term would close it.
// Everything in SI units of the rate (unit = rad/s, m/s^2, ...): Q unit*s, N unit*s^0.5,
// B unit, K unit/s^0.5, R unit/s, Gauss-Markov sigma unit and T s, sinusoid amplitude unit.
#include <array>
#include <string>
#include <vector>

#include "toolbox/allan/confidence.hpp"
#include "toolbox/allan/noise_model.hpp"

namespace ldv::allan {

struct FitOptions {
  bool q = true, n = true, b = true, k = true, r = true;
  bool gauss_markov = false;  // model the bias as Gauss-Markov (sigma, T) in place of the flat B
  // With gauss_markov false: analyze() fits both bias models (flat B and Gauss-Markov) and keeps the
  // one the data prefer (AIC of the likelihood fits, when the GM stands out; rate input with the likelihood fit only, else
  // the flat B). false: the flat B as asked (`ldv allan --bias-model flat`).
  bool choose_bias_model = true;
  bool sinusoid = false;      // add a sinusoid (amplitude, frequency)
  double interval_confidence = 0.95;
  // Generalized least squares with the full covariance of overlapping Allan variance estimates
  // (avar_covariance.hpp) when the points allow it; false: independent-points weights (+ inflation).
  bool gls = true;
  // Refine N, B / GM and K by the likelihood of the raw data (whittle_fit.hpp) for rate input;
  // false: the Allan-curve fit only.
  bool likelihood = true;
  double likelihood_block_s = 0.02;  // the rate is averaged over blocks of this length first (>= tau0)
  double target_precision = 0.1;     // record length reported for this relative 1-sigma per term
};

struct TermEstimate {
  bool in_model = false;
  double value = 0.0;      // the coefficient (>= 0)
  double sigma = 0.0;      // 1-sigma uncertainty of the coefficient
  double lo = 0.0, hi = 0.0;  // interval at FitOptions::interval_confidence
  bool resolved = false;   // significant (> 2 sigma in variance) and dominant somewhere in tau
  double shape = 0.0;      // GM time constant T [s] / sinusoid frequency [Hz]
  double shape_sigma = 0.0;  // its 1-sigma uncertainty
  // The GM T's interval at FitOptions::interval_confidence, from its profile likelihood (likelihood fit
  // only; 0 and 0 otherwise).
  double shape_lo = 0.0, shape_hi = 0.0;
};

struct SlopeLine {
  double value = 0.0;   // coefficient of the tangent line: an upper bound on the term
  double tau_s = 0.0;   // where the line touches the curve
};

struct DecadeMisfit {
  double tau_lo_s = 0.0, tau_hi_s = 0.0;
  int points = 0;
  double chi2_per_point = 0.0;   // mean squared normalized residual (about 1 when the model fits)
  double log_ratio = 0.0;        // mean ln(data/model) of the Allan variance: > 0 model too low
  std::string closing_term;      // excluded term whose addition lowers this decade's misfit most ("" none)
  double chi2_per_point_with_term = 0.0;
};

struct NoiseFit {
  std::array<TermEstimate, kModelTermCount> terms;  // indexed by ModelTerm
  double b_tau_s = 0.0;           // tau of the minimum (flat part) of the measured deviation
  double chi2 = 0.0;              // weighted residual sum of squares
  int points = 0;
  double covariance_inflation = 1.0;  // 1 with GLS; else for correlated overlapping estimates (noise_fit.cpp)
  bool gls = false;               // fitted by generalized least squares (full covariance across tau)
  // "allan_gls" / "allan_wls": fitted to the Allan variance curve (generalized / weighted LS);
  // "whittle": N, B or GM, K by the likelihood of the raw data (whittle_fit.hpp), the rest as fitted
  // to the curve; chi2, points and misfit always describe the curve fit.
  std::string method;
  std::array<SlopeLine, 5> slope_lines;  // Q N B K R
  std::vector<DecadeMisfit> misfit;

  const TermEstimate& operator[](ModelTerm t) const { return terms[static_cast<int>(t)]; }
  TermEstimate& operator[](ModelTerm t) { return terms[static_cast<int>(t)]; }
  double model_avar(double tau_s) const;  // fitted total Allan variance
};

// Shortest Gauss-Markov time constant a fit accepts, in units of its resolution (the shortest tau of
// the Allan-curve fit; in the likelihood fit the block length, or longer where a quantisation noise Q
// hides N: whittle_fit.cpp, gm_resolution). A GM with T well below the
// resolution is white noise there: flat spectrum up to 1/(2 pi T), Allan variance 2 sigma^2 T / tau
// at tau >> T, i.e. white noise of density 2 sigma^2 T, so it can only trade against N (on white
// noise alone it took 25-65 % of N^2 at T of a few samples). At 5 resolution steps its Allan hump
// (1.89 T) sits a decade above the resolution and its spectral corner 1/(2 pi T) at 3 % of the
// sampling band, so its shape is visible over the rest. A fit still pulled to this bound folds the
// term into N (refit without it) and reports the GM absent (value 0, not resolved, T at the bound).
constexpr double kGaussMarkovMinResolution = 5.0;
double gm_min_time_constant(double resolution_s);
// T within 2 % of that bound: the fit was pulled to it (folded into N, or a T interval that reaches it).
bool gm_time_constant_at_bound(double t_s, double resolution_s);

// Value, 1-sigma and interval of a term from its squared coefficient c >= 0 and the 1-sigma
// sigma_c of c; z: the normal quantile of the interval.
void set_term_interval(TermEstimate& t, double c, double sigma_c, double z);

// pts: an overlapping (or any Allan-type) deviation with EDFs. Points without EDF are skipped.
// Throws std::invalid_argument with fewer than 3 usable points.
NoiseFit fit_noise_model(const std::vector<StabilityPoint>& pts, const FitOptions& opt = {});

}  // namespace ldv::allan
