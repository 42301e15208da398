#pragma once
// What every GNSS protocol decoder here produces: the project's GnssFix plus what the fix itself
// does not carry (the GPS week and the full position covariance), and the PPS time labels.
#include "common/formats/nav_types.hpp"
#include "common/time/gps_time.hpp"

namespace ldv::gnss {

// One solution epoch. fix.t_s is the seconds of week of `time`; fix.pos_std_ned_m is the square
// root of the diagonal of pos_cov_ned_m2.
struct GnssSolution {
  GpsTime time;
  GnssFix fix;
  Mat3 pos_cov_ned_m2 = Mat3::Identity();
};

// Which GPS second a PPS edge is, as the receiver tells it (DESIGN.md section 4).
struct PpsTimeLabel {
  enum class Refers {
    kNextPulse,  // announced before the edge (u-blox TIM-TP)
    kLastPulse,  // reported after the edge (NMEA ZDA / RMC on a whole second)
  };
  GpsTime pulse_time;                // GPS time of the pulse the label refers to
  Refers refers = Refers::kLastPulse;
  double quantization_error_s = 0.0;  // receiver's pulse quantisation error, 0 when unknown
  bool quantization_error_valid = false;
};

// Sets fix.pos_std_ned_m from the covariance diagonal.
inline void sync_std_from_cov(GnssSolution& s) {
  s.fix.pos_std_ned_m = s.pos_cov_ned_m2.diagonal().cwiseMax(0.0).cwiseSqrt();
}

}  // namespace ldv::gnss
