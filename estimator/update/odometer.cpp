#include "estimator/update/odometer.hpp"

#include <cmath>

#include "estimator/update/gyro_coupling.hpp"
#include "estimator/update/vehicle_velocity.hpp"

namespace ldv::est {

bool OdometerObservation::valid() const { return std::isfinite(t_s) && std::isfinite(speed_mps); }

Measurement OdometerObservation::measurement(int, const MeasurementContext& c) const {
  const VehicleVelocity vv = vehicle_velocity(c.nav, c.lp, c.layout);
  const double gain = 1.0 + c.lp.odometer_scale;
  Measurement m(sensors::kOdometer, 1, c.layout.size());
  m.y(0) = gain * vv.v_v_mps.x() - speed_mps;
  m.H.row(0) = gain * vv.H.row(0);
  add_gyro_error_columns(c.layout, c.lp, m);
  add_effect_columns(c.layout, c.lp, m);
  const double sd = c.options.aids.odometer_std_mps;
  m.R(0, 0) = sd * sd;
  return m;
}

}  // namespace ldv::est
