#pragma once
// GNSS antenna velocity: z = v_n + C_b_n (w_ib_b x l) - w_in_n x (C_b_n l).
#include "common/formats/nav_types.hpp"
#include "estimator/ins/nav_state.hpp"
#include "estimator/update/measurement.hpp"

namespace ldv::est {
// Antenna velocity predicted from the state (also what time_offset needs).
Vec3 antenna_velocity_n(const NavState& s, const LinearizationPoint& lp);
// J_gyro_per_block: the gyro-error Jacobians of the blocks (delta_w through the lever arm).
Measurement gnss_velocity_measurement(const NavState& s, const LinearizationPoint& lp, const StateLayout& layout,
                                      const GnssFix& fix);
}  // namespace ldv::est
