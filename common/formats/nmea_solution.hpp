#pragma once
// One navigation solution epoch as the NMEA 0183 sentences a GNSS/INS receiver prints for it: GGA, RMC, GST (when
// its sigma is known), VTG and HDT (the INS heading). Shared by `ldv convert --to nmea` (a solution file) and
// tspi_pub's NMEA output (live TSPI), so a downstream device reads the same sentences from either.
#include <string>
#include <string_view>

#include "common/geo/geodetic.hpp"
#include "common/math/rotation.hpp"
#include "common/time/gps_time.hpp"

namespace ldv::nmea {

struct SolutionEpoch {
  enum class Source { kInvalid, kInsOnly, kGnssAided, kUnknown };
  GpsTime gps;
  Geodetic pos;
  Vec3 vel_n_mps = Vec3::Zero();
  double heading_rad = 0.0;
  Vec3 pos_std_ned_m = Vec3::Constant(NAN);  // NaN: not known (no GST)
  Source source = Source::kUnknown;
};

// GGA quality: 0 invalid; 6 (dead reckoning) where the INS ran alone; where GNSS aided it, from the horizontal
// 1-sigma as an INS/GNSS receiver reports its blended solution: 4 (RTK fixed) up to 5 cm, 5 (RTK float) up to 50 cm,
// else 2 (differential); 1 where neither the aiding nor the sigma is known.
int gga_quality(const SolutionEpoch& e);

// GGA, RMC, GST, VTG, HDT for the epoch, UTC from its GPS time with the leap seconds, CR LF each.
std::string solution_sentences(const SolutionEpoch& e, std::string_view talker = "GN");

}  // namespace ldv::nmea
