#include "estimator/ins/mechanization.hpp"

#include <algorithm>
#include <cmath>

#include "common/geo/earth_model.hpp"

namespace ldv::est {
namespace {
// A step that goes over a pole evaluates gravity and the Earth's rate at the pole, not beyond it (NaN there).
double clamp_to_pole(double lat_rad) { return std::clamp(lat_rad, -kHalfPi, kHalfPi); }
}  // namespace

void Mechanization::reset(const NavState& s) {
  have_prev_ = false;
  dv_n_prev_.setZero();
  dt_prev_ = 0.0;
}

const MechanizationStep& Mechanization::step(NavState& s, const ImuIncrement& inc) {
  const double dt = inc.dt_s;
  const Vec3& dtheta = inc.dtheta_b_rad;
  const Vec3& dvel = inc.dvel_b_mps;

  // Mid-interval velocity and position by extrapolating the previous step's velocity change.
  const Vec3 v0 = s.v_n_mps;
  const Vec3 v_mid = (dt_prev_ > 0.0) ? Vec3(v0 + 0.5 * dv_n_prev_ * (dt / dt_prev_)) : v0;
  const earth::Radii r0 = earth::radii(s.pos.lat_rad);
  const double h_mid = s.pos.h_m - 0.5 * v_mid.z() * dt;
  const double lat_mid = clamp_to_pole(s.pos.lat_rad + 0.5 * v_mid.x() * dt / (r0.meridian_m + h_mid));

  const Vec3 omega_ie_n = earth::omega_ie_n(lat_mid);
  const Vec3 omega_en_n = earth::omega_en_n(lat_mid, h_mid, v_mid);
  const Vec3 zeta = (omega_ie_n + omega_en_n) * dt;  // rotation of n over the interval

  // Rotation and sculling compensation of the velocity increment (two-sample form).
  Vec3 dv_b = dvel + 0.5 * dtheta.cross(dvel);
  if (have_prev_) dv_b += (prev_.dtheta_b_rad.cross(dvel) + prev_.dvel_b_mps.cross(dtheta)) / 12.0;
  const Mat3 C0 = s.C_b_n();
  const Vec3 dv_sf_n = C0 * dv_b - 0.5 * zeta.cross(C0 * dv_b);
  const Vec3 g_n = gravity_.gravity_n(lat_mid, h_mid) + gravity_anomaly_n_;
  const Vec3 dv_gc_n = (g_n - (2.0 * omega_ie_n + omega_en_n).cross(v_mid)) * dt;
  const Vec3 v1 = v0 + dv_sf_n + dv_gc_n;

  // Position: trapezoidal velocity, radii at the mid height/latitude.
  const Vec3 v_avg = 0.5 * (v0 + v1);
  const double h1 = s.pos.h_m - v_avg.z() * dt;
  const double hm = 0.5 * (s.pos.h_m + h1);
  const double lat1 = s.pos.lat_rad + v_avg.x() * dt / (r0.meridian_m + hm);
  const double latm = clamp_to_pole(0.5 * (s.pos.lat_rad + lat1));
  const earth::Radii rm = earth::radii(latm);
  // A step over the pole moves east by millimetres against a distance to the pole of about as little: its
  // longitude change is meaningless (0/0); the crossing below turns the meridian instead.
  const bool over_pole = std::abs(lat1) > kHalfPi;
  const double lon1 =
      over_pole ? s.pos.lon_rad : s.pos.lon_rad + v_avg.y() * dt / ((rm.prime_vertical_m + hm) * std::cos(latm));

  // Attitude: body rotation with coning, n-frame rotation re-evaluated at the updated midpoint.
  Vec3 phi_b = dtheta;
  if (have_prev_) phi_b += prev_.dtheta_b_rad.cross(dtheta) / 12.0;
  const Vec3 zeta_mid = (earth::omega_ie_n(latm) + earth::omega_en_n(latm, hm, v_avg)) * dt;
  s.q_b_n = (quat_from_rotvec(-zeta_mid) * s.q_b_n * quat_from_rotvec(phi_b)).normalized();

  last_.dt_s = dt;
  last_.dv_sf_n_mps = dv_sf_n;
  last_.omega_ib_b_rad_s = dtheta / dt;
  last_.f_b_mps2 = dvel / dt;
  last_.a_n_mps2 = (v1 - v0) / dt;
  dv_n_prev_ = v1 - v0;
  dt_prev_ = dt;
  prev_ = inc;
  have_prev_ = true;

  s.pos = {lat1, wrap_pi(lon1), h1};  // across the antimeridian: back into (-180, 180] deg
  s.v_n_mps = v1;
  s.t_s = inc.t_s;
  last_.crossed_pole = over_pole;
  if (last_.crossed_pole) {
    // Over the pole the meridian goes on down the far side: latitude back below 90 deg, longitude + 180 deg,
    // and north there is the old south (n' = Rz(180 deg) n: north and east negated).
    const Vec3 flip(-1.0, -1.0, 1.0);
    s.pos = {std::copysign(kPi, lat1) - lat1, wrap_pi(lon1 + kPi), h1};
    s.v_n_mps = v1.cwiseProduct(flip);
    s.q_b_n = (quat_from_rotvec(Vec3(0.0, 0.0, kPi)) * s.q_b_n).normalized();
    dv_n_prev_ = dv_n_prev_.cwiseProduct(flip);
  }
  return last_;
}

}  // namespace ldv::est
