#include "estimator/update/gnss_fix.hpp"

#include <cmath>

#include "estimator/update/gnss_position.hpp"
#include "estimator/update/gnss_velocity.hpp"

namespace ldv::est {

bool GnssFixObservation::valid() const {
  return std::isfinite(fix.t_s) && std::isfinite(fix.pos.lat_rad) && std::isfinite(fix.pos.lon_rad) &&
         std::isfinite(fix.pos.h_m) && fix.pos_std_ned_m.allFinite() && (fix.pos_std_ned_m.array() > 0).all() &&
         (!fix.has_velocity || (fix.vel_n_mps.allFinite() && (fix.vel_std_n_mps.array() > 0).all()));
}

Measurement GnssFixObservation::measurement(int index, const MeasurementContext& c) const {
  return index == 0 ? gnss_position_measurement(c.nav, c.lp, c.layout, fix)
                    : gnss_velocity_measurement(c.nav, c.lp, c.layout, fix);
}

}  // namespace ldv::est
