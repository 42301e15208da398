#include "toolbox/allan/noise_model.hpp"

#include <cmath>

namespace ldv::allan {

const char* model_term_name(ModelTerm t) {
  switch (t) {
    case ModelTerm::kQ: return "Q";
    case ModelTerm::kN: return "N";
    case ModelTerm::kB: return "B";
    case ModelTerm::kK: return "K";
    case ModelTerm::kR: return "R";
    case ModelTerm::kGaussMarkov: return "GM";
    case ModelTerm::kSinusoid: return "sine";
  }
  return "?";
}

double term_avar(ModelTerm t, double tau, double shape) {
  switch (t) {
    case ModelTerm::kQ: return 3.0 / (tau * tau);
    case ModelTerm::kN: return 1.0 / tau;
    case ModelTerm::kB: return 2.0 * std::log(2.0) / M_PI;
    case ModelTerm::kK: return tau / 3.0;
    case ModelTerm::kR: return tau * tau / 2.0;
    case ModelTerm::kGaussMarkov: {
      // First-order Gauss-Markov rate, unit variance, time constant T:
      // (2T/tau) [1 - T/(2 tau) (3 - 4 e^{-tau/T} + e^{-2 tau/T})]; for tau << T a series avoids the
      // cancellation (-> 2tau/(3T), a random walk), for tau >> T it tends to 2T/tau (white noise).
      const double T = shape, u = tau / T;
      if (u < 1e-3) return 2.0 * u / 3.0 - u * u / 2.0;
      const double e = std::exp(-u);
      return (2.0 / u) * (1.0 - (3.0 - 4.0 * e + e * e) / (2.0 * u));
    }
    case ModelTerm::kSinusoid: {
      // Amplitude A (coefficient) at frequency f0: A^2 (sin^2(pi f0 tau) / (pi f0 tau))^2.
      const double z = M_PI * shape * tau;
      const double s = std::sin(z);
      return std::pow(s * s / z, 2);
    }
  }
  return 0.0;
}

double term_adev_slope(ModelTerm t) {
  switch (t) {
    case ModelTerm::kQ: return -1.0;
    case ModelTerm::kN: return -0.5;
    case ModelTerm::kB: return 0.0;
    case ModelTerm::kK: return 0.5;
    case ModelTerm::kR: return 1.0;
    default: return 0.0;
  }
}

}  // namespace ldv::allan
