#pragma once
// Plausibility of a decoded GNSS solution or PPS label: what no real receiver output can be (a week of
// 5,114,391, a time of week past the end of the week, a height of 1e308 m, a negative variance). Every
// decoder's output passes here before it is published, so one corrupt record is counted and dropped
// instead of reaching the filter.
#include <optional>
#include <string>

#include "common/formats/gnss_solution.hpp"

namespace ldv::gnss {

// Full GPS weeks: 1042 is January 2000; 8191 is the largest the 13-bit week of the modern signals holds.
constexpr int kMinPlausibleGpsWeek = 1042;
constexpr int kMaxPlausibleGpsWeek = 8191;
// Ellipsoidal heights: the geoid lies within ~110 m of the ellipsoid; above, aircraft and balloons.
constexpr double kMinPlausibleHeight_m = -1000.0;
constexpr double kMaxPlausibleHeight_m = 100000.0;
constexpr double kMaxPlausibleSpeed_mps = 1000.0;
// The best a receiver can know its antenna's place and speed: the phase centre alone wanders by millimetres.
// A smaller std (a receiver's 1e-150 m) is held to this in the filter, never trusted to the last bit (the
// covariance loses its positive-definiteness after such an update).
constexpr double kMinCredibleGnssPositionStd_m = 1e-3;
constexpr double kMinCredibleGnssVelocityStd_mps = 1e-3;
// Variances beyond this say nothing (a 1e6 m std): no receiver means it as a position.
constexpr double kMaxPlausiblePositionVariance_m2 = 1e12;

// Why `s` cannot be a real solution ("time of week 3085367 s not in [0, 604800)"), nullopt when plausible.
std::optional<std::string> implausibility(const GnssSolution& s);
// The same of a fix without a GPS week (a KF-GINS gnss.txt row: seconds only), its covariance the stated std
// squared: one check for every reader of GNSS solutions, files and bus alike.
std::optional<std::string> implausibility(const GnssFix& fix);
std::optional<std::string> implausibility(const PpsTimeLabel& label);
// The GPS time part of the above.
std::optional<std::string> implausibility(const GpsTime& t);

}  // namespace ldv::gnss
