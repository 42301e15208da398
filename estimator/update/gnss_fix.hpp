#pragma once
// A GNSS solution as an observation: its position (gnss_position.hpp), then its velocity when it has one
// and options.use_gnss_velocity (gnss_velocity.hpp).
#include "common/formats/nav_types.hpp"
#include "estimator/update/observation.hpp"

namespace ldv::est {

class GnssFixObservation final : public Observation {
 public:
  explicit GnssFixObservation(const GnssFix& fix) : Observation(fix.t_s), fix(fix) {}
  const GnssFix fix;
  bool valid() const override;
  int measurement_count(const FilterOptions& o) const override {
    return fix.has_velocity && o.use_gnss_velocity ? 2 : 1;
  }
  Measurement measurement(int index, const MeasurementContext& ctx) const override;
};

}  // namespace ldv::est
