#pragma once
// Normal gravity without calling GeographicLib every IMU sample: a first-order Taylor model of
// earth::gravity_n around a reference point, re-expanded when the position moves more than
// kRefreshDistance_m away. tests/estimator/test_gravity_cache.cpp measures the error this accepts
// (< 1e-7 m/s^2 = 10 uGal inside the refresh radius, far below any IMU's bias).
#include "common/geo/geodetic.hpp"
#include "common/math/rotation.hpp"

namespace ldv::est {

class GravityCache {
 public:
  static constexpr double kRefreshDistance_m = 500.0;

  // Normal gravity in NED [m/s^2] at (lat, h).
  Vec3 gravity_n(double lat_rad, double h_m);
  // d(g_n)/dh [1/s^2] at the last expansion point (used by the error-state F).
  const Vec3& dg_dh() const { return dg_dh_; }
  const Vec3& dg_dlat() const { return dg_dlat_; }  // [m/s^2 per rad]

 private:
  void expand_at(double lat_rad, double h_m);
  bool valid_ = false;
  double lat0_rad_ = 0.0, h0_m_ = 0.0;
  Vec3 g0_ = Vec3::Zero(), dg_dlat_ = Vec3::Zero(), dg_dh_ = Vec3::Zero();
};

}  // namespace ldv::est
