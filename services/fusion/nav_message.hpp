#pragma once
// Filter outputs -> NAV and NAV_INNOVATION messages.
#include <ldv_lcm/nav_innovation_t.hpp>
#include <ldv_lcm/nav_state_t.hpp>

#include "estimator/filter/records.hpp"
#include "services/fusion/fusion_engine.hpp"

namespace ldv {

ldv_lcm::nav_state_t nav_message(const FusionOutput& o, int64_t seq);
ldv_lcm::nav_innovation_t innovation_message(const est::InnovationRecord& r, int gps_week, int64_t seq);

}  // namespace ldv
