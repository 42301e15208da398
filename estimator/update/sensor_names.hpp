#pragma once
// The name every measurement and innovation record carries: which sensor (or aid) it came from. Names are
// string literals (static storage), compared as text. A new sensor may declare its name in its own file;
// the built-in ones are here because effects test for them.
#include <string_view>

namespace ldv::est {

using SensorName = std::string_view;

namespace sensors {
inline constexpr SensorName kGnssPosition = "gnss_position";
inline constexpr SensorName kGnssVelocity = "gnss_velocity";
inline constexpr SensorName kZeroVelocity = "zupt";
inline constexpr SensorName kZeroAngularRate = "zaru";
inline constexpr SensorName kNonHolonomic = "nhc";
inline constexpr SensorName kOdometer = "odometer";
}  // namespace sensors

}  // namespace ldv::est
