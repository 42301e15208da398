#pragma once
// Whether a GNSS solution's velocities agree with its own positions. RTKLIB's .pos velocity, for one,
// lags its positions by about 0.1 s and scatters three times its stated sigma; fused as given it pulls
// the filter off the positions at every acceleration. The check compares each reported horizontal
// velocity with the chord of the neighbouring positions (exact for constant acceleration) against
// their combined stated sigmas; the lag that best aligns them is reported for the record.
#include <algorithm>
#include <cmath>
#include <vector>

#include "common/formats/nav_types.hpp"

namespace ldv::est {

struct GnssVelocityCheck {
  int compared = 0;             // fixes with a velocity and two close neighbours
  double normalised_mse = 0.0;  // mean of e^T (Sv + Sc)^-1 e / 2 over them: about 1 when consistent
  // Its 1-sigma: each term is exponential (chi-square with 2 dof over 2), whose sd is its mean, so the mean of
  // `compared` of them has the mean over sqrt(compared).
  double normalised_mse_sigma() const { return normalised_mse / std::sqrt(std::max(compared, 1)); }
  double best_lag_s = 0.0;      // velocity time tag minus the time it is true at, best fit in [-0.5, 0.5] s
  double normalised_mse_at_lag = 0.0;
  // Likelihood-ratio statistic of that lag against none, 2 n (mse(0) - mse(lag)): chi-square with one
  // degree of freedom when there is no lag. Where the chord's own noise dominates the misfit (a precise
  // velocity, fixes close together) the lag still shows here.
  double lag_statistic = 0.0;
  bool lagged() const { return std::abs(best_lag_s) >= 0.02 && lag_statistic > 25.0; }
  // The velocities may be fused: enough compared, their misfit at most 2x their stated sigma, no lag.
  bool consistent() const { return compared >= 20 && normalised_mse <= 4.0 && !lagged(); }
};

GnssVelocityCheck check_gnss_velocity(const std::vector<GnssFix>& gnss);

}  // namespace ldv::est
