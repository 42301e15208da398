#pragma once
// WGS84 Earth model for the local-level NED mechanisation: radii of curvature, Earth rate,
// transport rate, normal gravity (GeographicLib), and small NED offsets <-> geodetic increments.
#include "common/geo/geodetic.hpp"
#include "common/math/rotation.hpp"

namespace ldv::earth {

constexpr double kOmegaIe_rad_s = 7.2921151467e-5;  // WGS84 Earth rotation rate
constexpr double kStandardGravity_mps2 = 9.80665;  // conventional g (CGPM 1901)
double semi_major_axis_m();
double eccentricity_squared();

struct Radii {
  double meridian_m;        // R_M, north-south radius of curvature
  double prime_vertical_m;  // R_N, east-west radius of curvature
};
Radii radii(double lat_rad);

// Normal gravity (gravitation + centrifugal) in NED [m/s^2] from GeographicLib's WGS84 model.
Vec3 gravity_n(double lat_rad, double h_m);
// Earth rate expressed in NED [rad/s].
Vec3 omega_ie_n(double lat_rad);
// Transport rate (rotation of NED w.r.t. Earth) [rad/s] for NED velocity v_n [m/s].
Vec3 omega_en_n(double lat_rad, double h_m, const Vec3& v_n);

// Metres NED per (dlat [rad], dlon [rad], dh [m]) at this position: dr_n = D * dlla.
Mat3 dr_n_per_dlla(const Geodetic& at);
// Position displaced by a small NED offset dr_n [m] (first order, exact enough for < 1 km).
Geodetic offset_ned(const Geodetic& from, const Vec3& dr_n);
// NED vector [m] from `from` to `to` (first order with the radii at `from`; use for < 1 km; above 89 deg of
// latitude the straight line through ECEF, valid across the pole).
Vec3 ned_between(const Geodetic& from, const Geodetic& to);

// Exact conversions through ECEF (GeographicLib), for tests and long baselines.
Vec3 ecef_from_geodetic(const Geodetic& g);
Geodetic geodetic_from_ecef(const Vec3& r_e);
// Rotation from NED at `at` to ECEF.
Mat3 C_n_e(const Geodetic& at);

}  // namespace ldv::earth
