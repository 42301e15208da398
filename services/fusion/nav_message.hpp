#pragma once
// Filter outputs -> NAV and NAV_INNOVATION messages.
#include <ldv_lcm/nav_innovation_t.hpp>
#include <ldv_lcm/nav_state_t.hpp>
#include <string>

#include "estimator/filter/records.hpp"
#include "services/fusion/fusion_engine.hpp"

namespace ldv {

ldv_lcm::nav_state_t nav_message(const FusionOutput& o, int64_t seq);
// nav_innovation_t.sensor: 1 gnss_position, 2 gnss_velocity, 3 zupt, 4 zaru, 5 nhc, 6 odometer, 0 other.
int8_t sensor_code(est::SensorName sensor);
// The sensor's name for a code ("sensor N" for an unknown one).
std::string sensor_of_code(int8_t code);
// t: the record's epoch as week + seconds of week (FusionEngine::week_time of r.t_s).
ldv_lcm::nav_innovation_t innovation_message(const est::InnovationRecord& r, const GpsTime& t, int64_t seq);

}  // namespace ldv
