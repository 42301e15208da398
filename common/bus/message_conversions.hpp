#pragma once
// Bus messages <-> the plain records of common/formats/nav_types.hpp, in one place so the live
// services and the offline log readers convert identically (the same data gives the same result).
#include <ldv_lcm/gnss_solution_t.hpp>
#include <ldv_lcm/imu_sample_t.hpp>

#include "common/formats/nav_types.hpp"

namespace ldv {

ImuIncrement imu_from_message(const ldv_lcm::imu_sample_t& m);
ldv_lcm::imu_sample_t message_from_imu(const ImuIncrement& s, int gps_week, int64_t seq);

// Position std is the square root of the covariance diagonal (NED).
GnssFix gnss_from_message(const ldv_lcm::gnss_solution_t& m);
ldv_lcm::gnss_solution_t message_from_gnss(const GnssFix& g, int gps_week, int64_t seq);

// imu_sample_t.status bit 0: the stamp is extrapolated from the host clock (no PPS fit yet), so the
// sample is not on the GPS time scale: navigation and exports skip it. (Bit 2, holdover from a previous or
// saved fit, is GPS time.)
constexpr int32_t kImuStatusTimeExtrapolated = 1 << 0;
// imu_sample_t.status bit 1: the device flagged this sample in error (saturation, failed built-in test):
// its increments are not measurements, so navigation does not integrate them.
constexpr int32_t kImuStatusDeviceError = 1 << 1;
inline bool has_gps_time(const ldv_lcm::imu_sample_t& m) { return (m.status & kImuStatusTimeExtrapolated) == 0; }

// True when every number in the message is finite and the std/quality fields are plausible.
bool is_valid(const ldv_lcm::imu_sample_t& m);
bool is_valid(const ldv_lcm::gnss_solution_t& m);

}  // namespace ldv
