#pragma once
// A time-tagged reading of an external sensor (a GNSS fix, a wheel speed): the filter queues it, applies it
// at its epoch (time tag - time_offset, the IMU interval split there) and, when it came late, rewinds and
// applies it at that epoch all the same. One queue for every sensor (NavFilter::add_observation).
//
// A new sensor: one file with an Observation subclass (its reading, validity, and measurement models);
// feed it with NavFilter::add_observation. Example: estimator/update/odometer.cpp.
#include <memory>

#include "estimator/ins/nav_state.hpp"
#include "estimator/options.hpp"
#include "estimator/update/measurement.hpp"

namespace ldv::est {

// What a measurement model may look at: the state at the epoch and its linearisation point.
struct MeasurementContext {
  const NavState& nav;
  const LinearizationPoint& lp;
  const StateLayout& layout;
  const FilterOptions& options;
};

class Observation {
 public:
  explicit Observation(double t_s) : t_s(t_s) {}
  virtual ~Observation() = default;
  const double t_s;  // time tag [s], on the GNSS (GPS) time scale
  // Finite, with positive stds: an invalid reading is counted and dropped before it is queued.
  virtual bool valid() const = 0;
  // How many measurements this reading gives with these options (GNSS: position, then velocity); each is
  // built on the state left by the previous one.
  virtual int measurement_count(const FilterOptions& options) const = 0;
  virtual Measurement measurement(int index, const MeasurementContext& ctx) const = 0;
};

using ObservationPtr = std::shared_ptr<const Observation>;

}  // namespace ldv::est
