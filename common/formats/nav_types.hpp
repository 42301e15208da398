#pragma once
// Plain data records exchanged between the simulator, the estimator, the file formats and the bus.
#include "common/geo/geodetic.hpp"
#include "common/math/rotation.hpp"

namespace ldv {

// One IMU output: increments over (t_s - dt_s, t_s], body front-right-down axes.
struct ImuIncrement {
  double t_s = 0.0;   // GPS seconds of week at the end of the interval
  double dt_s = 0.0;  // interval length
  Vec3 dtheta_b_rad = Vec3::Zero();
  Vec3 dvel_b_mps = Vec3::Zero();
};

enum class GnssQuality : int { kFixed = 1, kFloat = 2, kSbas = 3, kDgps = 4, kSingle = 5, kPpp = 6 };

// One GNSS position (and optionally velocity) solution at the antenna phase centre.
struct GnssFix {
  double t_s = 0.0;  // GPS seconds of week of the measurement epoch
  Geodetic pos;
  Vec3 pos_std_ned_m = Vec3::Constant(1.0);
  bool has_velocity = false;
  Vec3 vel_n_mps = Vec3::Zero();
  Vec3 vel_std_n_mps = Vec3::Constant(1.0);
  GnssQuality quality = GnssQuality::kFixed;
  int num_sats = 0;
  double age_s = 0.0;
  double ratio = 0.0;
};

// An interval between two kept IMU records much longer than the nominal one, found by a reader (the record
// after it is kept; its dt_s spans the whole hole: an integrator must not take it as one increment).
struct ImuTimeGap {
  double t_before_s = 0.0, t_after_s = 0.0;  // GPS seconds of week of the records either side
  long line = 0;                             // file line of the record after the gap
  double length_s() const { return t_after_s - t_before_s; }
};

// A navigation solution record (the KF-GINS .nav layout).
struct NavRecord {
  int week = 0;
  double sow_s = 0.0;
  Geodetic pos;
  Vec3 vel_n_mps = Vec3::Zero();
  Vec3 rpy_rad = Vec3::Zero();
};

}  // namespace ldv
