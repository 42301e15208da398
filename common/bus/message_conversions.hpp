#pragma once
// Bus messages <-> the plain records of common/formats/nav_types.hpp, in one place so the live
// services and the offline log readers convert identically (the same data gives the same result).
#include <ldv_lcm/gnss_solution_t.hpp>
#include <ldv_lcm/imu_sample_t.hpp>
#include <ldv_lcm/wheel_speed_t.hpp>
#include <optional>
#include <string>

#include "common/formats/gnss_solution.hpp"
#include "common/formats/nav_types.hpp"

namespace ldv {

ImuIncrement imu_from_message(const ldv_lcm::imu_sample_t& m);
ldv_lcm::imu_sample_t message_from_imu(const ImuIncrement& s, int gps_week, int64_t seq);

// Position std is the square root of the covariance diagonal (NED).
GnssFix gnss_from_message(const ldv_lcm::gnss_solution_t& m);
// With its week and full covariance, as the decoders give it (gnss_solution.hpp).
gnss::GnssSolution solution_from_message(const ldv_lcm::gnss_solution_t& m);
ldv_lcm::gnss_solution_t message_from_gnss(const GnssFix& g, int gps_week, int64_t seq);

// imu_sample_t.status bit 0: the stamp is extrapolated from the host clock (no PPS fit yet), so the
// sample is not on the GPS time scale: navigation and exports skip it. (Bit 2, holdover from a previous or
// saved fit, is GPS time.)
constexpr int32_t kImuStatusTimeExtrapolated = 1 << 0;
// imu_sample_t.status bit 1: the device flagged this sample in error (saturation, failed built-in test):
// its increments are not measurements, so navigation does not integrate them.
constexpr int32_t kImuStatusDeviceError = 1 << 1;
inline bool has_gps_time(const ldv_lcm::imu_sample_t& m) { return (m.status & kImuStatusTimeExtrapolated) == 0; }

// wheel_speed_t.status bits (lcmtypes/wheel_speed_t.lcm).
constexpr int32_t kWheelStatusSpeedsValid = 1 << 0;
constexpr int32_t kWheelStatusSlipping = 1 << 2;
// The forward speed of the rear-axle centre [m/s] (the odometer point of estimator/update/odometer.hpp): the
// odometer's own (wheel 0), else the mean of the rear wheels (3, 4), else the mean of every wheel. Nothing when
// the speeds are not flagged valid or a wheel is flagged locked or slipping (its speed is not the vehicle's).
std::optional<double> odometer_speed_from_message(const ldv_lcm::wheel_speed_t& m);
// One odometer speed as a one-wheel message (wheel 0), speeds valid.
ldv_lcm::wheel_speed_t message_from_odometer(double t_s, double speed_mps, int gps_week, int64_t seq);

// The bus-input contract: why a message cannot be a real reading (nullopt when it can). IMU: a plausible GPS
// week and seconds of week (unless host-clock stamped), an interval in (0, 1) s, rates an IMU can sense
// (imu_sample_checks.hpp). GNSS: what gnss::implausibility refuses in decoded files and streams (week, time
// of week, latitude, height, a positive-definite covariance within bounds, a speed below 1000 m/s) and a
// known fix quality. Wheel speed: 1-8 wheels with arrays of that length, speeds within +-150 m/s, GPS time.
std::optional<std::string> implausibility(const ldv_lcm::imu_sample_t& m);
std::optional<std::string> implausibility(const ldv_lcm::gnss_solution_t& m);
std::optional<std::string> implausibility(const ldv_lcm::wheel_speed_t& m);
bool is_valid(const ldv_lcm::imu_sample_t& m);
bool is_valid(const ldv_lcm::gnss_solution_t& m);
bool is_valid(const ldv_lcm::wheel_speed_t& m);

}  // namespace ldv
