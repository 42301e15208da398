// Earth model against published WGS84 values and against GeographicLib's exact ECEF geometry.
#include <gtest/gtest.h>

#include "common/geo/earth_model.hpp"

using namespace ldv;

TEST(EarthModel, NormalGravityMatchesPublishedWgs84EquatorAndPole) {
  // NIMA TR8350.2: gamma_e = 9.7803253359, gamma_p = 9.8321849378 m/s^2 on the ellipsoid.
  EXPECT_NEAR(earth::gravity_n(0.0, 0.0).z(), 9.7803253359, 1e-9);
  EXPECT_NEAR(earth::gravity_n(kPi / 2, 0.0).z(), 9.8321849378, 1e-9);
  // Free-air gradient about -3.086e-6 /s^2 per metre.
  const double dg = earth::gravity_n(0.8, 1000.0).z() - earth::gravity_n(0.8, 0.0).z();
  EXPECT_NEAR(dg, -3.086e-3, 0.01e-3);
}

TEST(EarthModel, RadiiMatchNumericalDerivativeOfEcef) {
  const Geodetic p{0.61, 2.39, 120.0};
  const double dlat = 1e-7, dlon = 1e-7;
  Geodetic pn = p, pe = p;
  pn.lat_rad += dlat;
  pe.lon_rad += dlon;
  const double north_m = (earth::ecef_from_geodetic(pn) - earth::ecef_from_geodetic(p)).norm();
  const double east_m = (earth::ecef_from_geodetic(pe) - earth::ecef_from_geodetic(p)).norm();
  const auto r = earth::radii(p.lat_rad);
  EXPECT_NEAR(north_m / dlat, r.meridian_m + p.h_m, 1.0);
  EXPECT_NEAR(east_m / (dlon * std::cos(p.lat_rad)), r.prime_vertical_m + p.h_m, 1.0);
}

TEST(EarthModel, NedOffsetRoundTripsAndMatchesEcefWithinMillimetres) {
  const Geodetic p{0.53, -1.2, 35.0};
  const Vec3 dr(120.0, -80.0, 3.0);
  const Geodetic q = earth::offset_ned(p, dr);
  const Vec3 back = earth::ned_between(p, q);
  EXPECT_LT((back - dr).norm(), 1e-8);  // double rounding of radians at Earth radius
  const Vec3 exact_n = earth::C_n_e(p).transpose() * (earth::ecef_from_geodetic(q) - earth::ecef_from_geodetic(p));
  EXPECT_LT((exact_n - dr).norm(), 5e-3);  // curvature terms of a 150 m offset
}

TEST(EarthModel, TransportRateOfEastwardMotion) {
  const Vec3 w = earth::omega_en_n(0.7, 0.0, Vec3(0, 30, 0));
  const auto r = earth::radii(0.7);
  EXPECT_NEAR(w.x(), 30.0 / r.prime_vertical_m, 1e-15);
  EXPECT_NEAR(w.z(), -30.0 * std::tan(0.7) / r.prime_vertical_m, 1e-15);
}

TEST(Rotation, EulerRoundTripAndQuaternionRotationVector) {
  const Vec3 rpy(0.3, -0.4, 2.9);
  EXPECT_LT((euler_from_C_b_n(C_b_n_from_euler(rpy)) - rpy).norm(), 1e-12);
  const Vec3 phi(0.1, -0.2, 0.3);
  EXPECT_LT((rotvec_from_quat(quat_from_rotvec(phi)) - phi).norm(), 1e-12);
  // A rotation of 90 deg about z maps x to y.
  const Vec3 y = quat_from_rotvec(Vec3(0, 0, kPi / 2)) * Vec3::UnitX();
  EXPECT_LT((y - Vec3::UnitY()).norm(), 1e-12);
}
