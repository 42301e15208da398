#include "estimator/ins/gravity_cache.hpp"

#include <algorithm>
#include <cmath>

#include "common/geo/earth_model.hpp"

namespace ldv::est {

void GravityCache::expand_at(double lat_rad, double h_m) {
  // Central differences over 10 m / 1e-5 rad: the model is smooth, truncation error ~1e-12 m/s^2.
  // Within 1e-5 rad (64 m) of a pole the difference stays on the Earth's side: the model refuses a latitude beyond
  // 90 deg with NaN (issue 46: a vehicle 55 m from the North Pole navigated on NaN).
  const double dlat = 1e-5, dh = 10.0;
  const double lat_hi = std::min(lat_rad + dlat, kHalfPi), lat_lo = std::max(lat_rad - dlat, -kHalfPi);
  g0_ = earth::gravity_n(lat_rad, h_m);
  dg_dlat_ = (earth::gravity_n(lat_hi, h_m) - earth::gravity_n(lat_lo, h_m)) / (lat_hi - lat_lo);
  dg_dh_ = (earth::gravity_n(lat_rad, h_m + dh) - earth::gravity_n(lat_rad, h_m - dh)) / (2.0 * dh);
  lat0_rad_ = lat_rad;
  h0_m_ = h_m;
  valid_ = true;
}

Vec3 GravityCache::gravity_n(double lat_rad, double h_m) {
  const double dlat = lat_rad - lat0_rad_, dh = h_m - h0_m_;
  // 6.4e6 m per rad of latitude (order of magnitude is all the refresh test needs).
  if (!valid_ || std::abs(dlat) * 6.4e6 > kRefreshDistance_m || std::abs(dh) > kRefreshDistance_m) {
    expand_at(lat_rad, h_m);
    return g0_;
  }
  return g0_ + dg_dlat_ * dlat + dg_dh_ * dh;
}

}  // namespace ldv::est
