#include "common/geo/earth_model.hpp"

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/NormalGravity.hpp>
#include <cmath>

namespace ldv::earth {

double semi_major_axis_m() { return GeographicLib::Constants::WGS84_a(); }
double eccentricity_squared() {
  const double f = GeographicLib::Constants::WGS84_f();
  return f * (2.0 - f);
}

Radii radii(double lat_rad) {
  const double a = semi_major_axis_m(), e2 = eccentricity_squared();
  const double s = std::sin(lat_rad);
  const double w2 = 1.0 - e2 * s * s;
  const double w = std::sqrt(w2);
  return {a * (1.0 - e2) / (w2 * w), a / w};
}

Vec3 gravity_n(double lat_rad, double h_m) {
  static const GeographicLib::NormalGravity& model = GeographicLib::NormalGravity::WGS84();
  double gamma_north = 0.0, gamma_up = 0.0;
  model.Gravity(lat_rad * kRadToDeg, h_m, gamma_north, gamma_up);
  return {gamma_north, 0.0, -gamma_up};
}

Vec3 omega_ie_n(double lat_rad) {
  return {kOmegaIe_rad_s * std::cos(lat_rad), 0.0, -kOmegaIe_rad_s * std::sin(lat_rad)};
}

Vec3 omega_en_n(double lat_rad, double h_m, const Vec3& v_n) {
  const Radii r = radii(lat_rad);
  return {v_n.y() / (r.prime_vertical_m + h_m), -v_n.x() / (r.meridian_m + h_m),
          -v_n.y() * std::tan(lat_rad) / (r.prime_vertical_m + h_m)};
}

Mat3 dr_n_per_dlla(const Geodetic& at) {
  const Radii r = radii(at.lat_rad);
  Mat3 D = Mat3::Zero();
  D(0, 0) = r.meridian_m + at.h_m;
  D(1, 1) = (r.prime_vertical_m + at.h_m) * std::cos(at.lat_rad);
  D(2, 2) = -1.0;
  return D;
}

Geodetic offset_ned(const Geodetic& from, const Vec3& dr_n) {
  const Radii r = radii(from.lat_rad);
  Geodetic g = from;
  g.lat_rad += dr_n.x() / (r.meridian_m + from.h_m);
  g.lon_rad = wrap_pi(g.lon_rad + dr_n.y() / ((r.prime_vertical_m + from.h_m) * std::cos(from.lat_rad)));
  g.h_m -= dr_n.z();
  return g;
}

Vec3 ned_between(const Geodetic& from, const Geodetic& to) {
  // Near a pole a metre east is a large longitude and two points may lie on opposite meridians (a vehicle
  // driving over the pole): there the vector goes through ECEF (same to first order elsewhere, and slower).
  constexpr double kPolarCap_rad = 89.0 * kDegToRad;
  if (std::abs(from.lat_rad) > kPolarCap_rad || std::abs(to.lat_rad) > kPolarCap_rad)
    return C_n_e(from).transpose() * (ecef_from_geodetic(to) - ecef_from_geodetic(from));
  const Radii r = radii(from.lat_rad);
  return {(to.lat_rad - from.lat_rad) * (r.meridian_m + from.h_m),
          wrap_pi(to.lon_rad - from.lon_rad) * (r.prime_vertical_m + from.h_m) * std::cos(from.lat_rad),
          -(to.h_m - from.h_m)};
}

Vec3 ecef_from_geodetic(const Geodetic& g) {
  Vec3 r;
  GeographicLib::Geocentric::WGS84().Forward(g.lat_rad * kRadToDeg, g.lon_rad * kRadToDeg, g.h_m, r.x(),
                                             r.y(), r.z());
  return r;
}

Geodetic geodetic_from_ecef(const Vec3& r_e) {
  double lat = 0, lon = 0, h = 0;
  GeographicLib::Geocentric::WGS84().Reverse(r_e.x(), r_e.y(), r_e.z(), lat, lon, h);
  return {lat * kDegToRad, lon * kDegToRad, h};
}

Mat3 C_n_e(const Geodetic& at) {
  const double sl = std::sin(at.lat_rad), cl = std::cos(at.lat_rad);
  const double so = std::sin(at.lon_rad), co = std::cos(at.lon_rad);
  Mat3 C;
  C << -sl * co, -so, -cl * co,  //
      -sl * so, co, -cl * so,    //
      cl, 0.0, -sl;
  return C;
}

}  // namespace ldv::earth
