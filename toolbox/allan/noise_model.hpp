#pragma once
// The inertial-sensor noise model in Allan-variance form (IEEE Std 952/1293; DESIGN.md section 5):
//   sigma^2(tau) = 3Q^2/tau^2 + N^2/tau + (2 ln2/pi) B^2 + K^2 tau/3 + R^2 tau^2/2
//                  [+ Gauss-Markov bias (sigma, T)] [+ sinusoid (amplitude, frequency)]
// Each term is linear in its squared coefficient, so a fit is linear least squares once the
// Gauss-Markov time constant (and the sinusoid frequency) are fixed.
#include <string>

namespace ldv::allan {

enum class ModelTerm { kQ, kN, kB, kK, kR, kGaussMarkov, kSinusoid };
inline constexpr int kModelTermCount = 7;
const char* model_term_name(ModelTerm t);  // "Q", "N", "B", "K", "R", "GM", "sine"

// Allan variance of one term with unit coefficient (coefficient^2 multiplies it). `shape` is the
// Gauss-Markov time constant T [s] or the sinusoid frequency [Hz]; unused for the others.
double term_avar(ModelTerm t, double tau_s, double shape = 0.0);

// Slope of the term's Allan deviation on log-log axes (-1, -1/2, 0, +1/2, +1), 0 for GM/sinusoid.
double term_adev_slope(ModelTerm t);

}  // namespace ldv::allan
