#include "estimator/filter/nav_error_dynamics.hpp"

#include <cmath>

#include "common/geo/earth_model.hpp"

namespace ldv::est {

Mat9 nav_error_F(const NavState& s, const Vec3& f_n, const Vec3& dg_dlat, const Vec3& dg_dh) {
  const double lat = s.pos.lat_rad, h = s.pos.h_m;
  const earth::Radii r = earth::radii(lat);
  const double Rm = r.meridian_m + h, Rn = r.prime_vertical_m + h;
  const double tl = std::tan(lat), cl = std::cos(lat), sl = std::sin(lat);
  const Vec3& v = s.v_n_mps;
  const double vn = v.x(), ve = v.y(), vd = v.z();
  const double W = earth::kOmegaIe_rad_s;

  const Vec3 w_ie = earth::omega_ie_n(lat);
  const Vec3 w_en = earth::omega_en_n(lat, h, v);

  // Partial derivatives of the Earth and transport rates w.r.t. delta_r (NED metres) and delta_v.
  Mat3 dwie_dr = Mat3::Zero();
  dwie_dr.col(0) = Vec3(-W * sl, 0.0, -W * cl) / Rm;
  Mat3 dwen_dr = Mat3::Zero();
  dwen_dr.col(0) = Vec3(0.0, 0.0, -ve / (Rn * cl * cl)) / Rm;
  dwen_dr.col(2) = Vec3(ve / (Rn * Rn), -vn / (Rm * Rm), -ve * tl / (Rn * Rn));  // delta_h = -delta_r_d
  Mat3 dwen_dv = Mat3::Zero();
  dwen_dv(0, 1) = 1.0 / Rn;
  dwen_dv(1, 0) = -1.0 / Rm;
  dwen_dv(2, 1) = -tl / Rn;

  // The prime-vertical radius varies with latitude (dRn/dlat ~ 2e4 m/rad): it enters the east row.
  const double e2 = earth::eccentricity_squared();
  const double w2 = 1.0 - e2 * sl * sl;
  const double dRn_dlat = earth::semi_major_axis_m() * e2 * sl * cl / (w2 * std::sqrt(w2));

  Mat9 F = Mat9::Zero();
  Mat3 Frr;
  Frr << -vd / Rm, 0.0, vn / Rm,                                                          //
      ve * tl / Rm - ve * dRn_dlat / (Rn * Rm), -vd / Rn - vn * tl / Rm + vn * dRn_dlat / (Rm * Rn), ve / Rn,  //
      0.0, 0.0, 0.0;
  F.block<3, 3>(0, 0) = Frr;
  F.block<3, 3>(0, 3).setIdentity();

  Mat3 dg_dr = Mat3::Zero();
  dg_dr.col(0) = dg_dlat / Rm;
  dg_dr.col(2) = -dg_dh;
  F.block<3, 3>(3, 0) = skew(v) * (2.0 * dwie_dr + dwen_dr) + dg_dr;
  F.block<3, 3>(3, 3) = -skew(2.0 * w_ie + w_en) + skew(v) * dwen_dv;
  F.block<3, 3>(3, 6) = skew(f_n);

  F.block<3, 3>(6, 0) = dwie_dr + dwen_dr;
  F.block<3, 3>(6, 3) = dwen_dv;
  F.block<3, 3>(6, 6) = -skew(w_ie + w_en);
  return F;
}

}  // namespace ldv::est
