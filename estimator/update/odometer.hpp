#pragma once
// Odometer / wheel speed ("odometer"): the forward speed of the rear-axle centre, z = (1 + k) v_v_x, k the
// odometer's scale error (effect odometer_scale). One reading: y = (1 + k_hat) v_v_x_hat - z, one row;
// H = (1 + k_hat) (row x of vehicle_velocity.hpp) + the effects' columns. Time-tagged on GPS time like a
// GNSS fix (queued, applied at its epoch, rewound when late).
#include "estimator/update/observation.hpp"

namespace ldv::est {

class OdometerObservation final : public Observation {
 public:
  OdometerObservation(double t_s, double speed_mps) : Observation(t_s), speed_mps(speed_mps) {}
  const double speed_mps;  // forward speed (negative when reversing)
  bool valid() const override;
  int measurement_count(const FilterOptions&) const override { return 1; }
  Measurement measurement(int index, const MeasurementContext& ctx) const override;
};

}  // namespace ldv::est
