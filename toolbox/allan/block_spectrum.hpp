#pragma once
// Spectral density of each noise term as the likelihood fit sees the data: the rate averaged over
// blocks of tau_b (ybar_j, exactly what integrated increments or a block mean give) and differenced,
// d_j = ybar_{j+1} - ybar_j. Differencing makes a rate random walk stationary, so every term of the
// model has a proper spectrum; block averaging folds everything above 1/(2 tau_b) in exactly.
//
// Convention: two-sided density in cycles per block, nu in (0, 1/2], Var(d) = integral over
// [-1/2, 1/2] of S(nu) dnu = 2 AVAR(tau_b). The rate's two-sided PSD of each term is IEEE Std 952's:
// N^2, B^2/(2 pi f), K^2/(2 pi f)^2, 2 sigma^2 T/(1 + (2 pi f T)^2); Q is white phase noise of
// variance Q^2 on each phase point. Each density multiplies the squared coefficient.
#include "toolbox/allan/noise_model.hpp"

namespace ldv::allan {

// Density of term `t` with unit coefficient at nu (cycles per block), blocks of tau_b_s;
// `shape` is the Gauss-Markov time constant [s]. R (a ramp: a constant d, frequency 0 only) and the
// sinusoid (a line, not a density) have none: 0.
double block_difference_density(ModelTerm t, double nu, double tau_b_s, double shape = 0.0);

}  // namespace ldv::allan
