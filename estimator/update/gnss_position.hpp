#pragma once
// GNSS antenna position: z = r_imu + C_b_n l (NED metres at the fix).
#include "common/formats/nav_types.hpp"
#include "estimator/ins/nav_state.hpp"
#include "estimator/update/measurement.hpp"

namespace ldv::est {
Measurement gnss_position_measurement(const NavState& s, const LinearizationPoint& lp, const StateLayout& layout,
                                      const GnssFix& fix);
}  // namespace ldv::est
