#pragma once
// Plausibility of one IMU increment: what no IMU can sense at its rate. The bounds are rates, so they hold
// whatever the sampling interval: an increment of 1000 rad in 5 ms (2e5 rad/s) or 1e30 m/s is a corrupted
// field, never a measurement. Checked on every IMU message fusion receives (common/bus/message_conversions).
// The KF-GINS file reader still has its own per-line caps (100 rad, 1e4 m/s: a line's interval is known only
// once the times are sorted out); moving it onto these rates is open.
#include <optional>
#include <string>

#include "common/formats/nav_types.hpp"

namespace ldv {

// Rate gyros of navigation IMUs span +-300 to +-4000 deg/s; 100 rad/s is 5730 deg/s.
constexpr double kMaxPlausibleAngularRate_rad_s = 100.0;
// Accelerometers span +-2 g to +-200 g; 2000 m/s^2 is 204 g.
constexpr double kMaxPlausibleSpecificForce_mps2 = 2000.0;
// An increment spans one sampling interval: 1 s at most (1 Hz; a longer one is a gap, not a sample).
constexpr double kMaxImuInterval_s = 1.0;

// Why an increment of dtheta, dvel over dt_s cannot be a measurement ("angular rate 2e5 rad/s beyond ..."),
// nullopt when an IMU could have sensed it.
std::optional<std::string> imu_increment_implausibility(const Vec3& dtheta_b_rad, const Vec3& dvel_b_mps, double dt_s);

// The rates alone, for an increment whose interval may be a gap (a file's line after missing lines): an
// increment over a long interval is a gap to bridge, not an implausible sample.
std::optional<std::string> imu_rate_implausibility(const Vec3& dtheta_b_rad, const Vec3& dvel_b_mps, double dt_s);

}  // namespace ldv
