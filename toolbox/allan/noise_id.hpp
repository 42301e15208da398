#pragma once
// Power-law noise identification at one averaging factor (NIST SP 1065 section 5.6; W. Riley and
// C. Greenhall, "Power law noise identification using the lag 1 autocorrelation", EFTF 2004), the
// method Stable32 uses when at least 30 averaged points remain; B1 ratio (and R(n) to split white
// from flicker PM) for shorter series, as Stable32 does.
#include <vector>

#include "toolbox/allan/deviation.hpp"
#include "toolbox/allan/phase_series.hpp"

namespace ldv::allan {

struct NoiseId {
  int alpha = 0;          // integer exponent of S_y(f) ~ f^alpha: 2 white PM, 1 flicker PM, 0 white FM,
                          // -1 flicker FM, -2 random-walk FM (-3, -4 for Hadamard)
  double alpha_est = 0;   // the continuous estimate (lag-1 method) before rounding
  bool by_acf = true;     // false: B1 ratio method (fewer than 30 averaged points)
  bool valid = true;      // false: too few points for either method
};

// dev selects the maximum number of differences (2 for the Allan family, 3 for Hadamard).
NoiseId identify_noise(const PhaseSeries& s, long m, Deviation dev);

// Lag-1 autocorrelation of a series about its mean.
double lag1_autocorrelation(const std::vector<double>& z);

}  // namespace ldv::allan
