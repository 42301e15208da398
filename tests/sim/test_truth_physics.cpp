// The truth and the exact IMU increments against physics written independently in the test:
// closed forms (static, circle), finite differences of the truth itself, Simpson's rule on the
// truth rates, and a free-inertial strapdown run on perfect data.
#include <gtest/gtest.h>

#include <GeographicLib/NormalGravity.hpp>

#include "sim/scenario.hpp"
#include "sim/truth_integrator.hpp"
#include "sim_test_helpers.hpp"

using namespace ldv;
using namespace ldv::sim;
using namespace ldv::sim::test;

namespace {
constexpr double kOmegaEarth = 7.2921151467e-5;  // WGS84 [rad/s]

Vec3 normal_gravity_ned(const Geodetic& p) {  // straight from GeographicLib
  double gn = 0, gu = 0;
  GeographicLib::NormalGravity::WGS84().Gravity(p.lat_rad * kRadToDeg, p.h_m, gn, gu);
  return {gn, 0.0, -gu};
}
Vec3 earth_rate_ned(double lat) { return {kOmegaEarth * std::cos(lat), 0.0, -kOmegaEarth * std::sin(lat)}; }
Vec3 transport_rate_ned(const Geodetic& p, const Vec3& v) {
  const double a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f), s = std::sin(p.lat_rad);
  const double RN = a / std::sqrt(1 - e2 * s * s), RM = RN * (1 - e2) / (1 - e2 * s * s);
  return {v.y() / (RN + p.h_m), -v.x() / (RM + p.h_m), -v.y() * std::tan(p.lat_rad) / (RN + p.h_m)};
}
}  // namespace

TEST(SimTruthPhysics, StaticVehicleSensesMinusGravityAndEarthRateExactly) {
  // Given a vehicle standing still with a tilt and heading 30 deg (built-in `static`)
  const SimResult r = simulate(perfect_request("static", 20.0, 100.0));
  const Geodetic p = r.truth.front().pos;
  const Mat3 C_n_b = C_b_n_from_euler(r.truth.front().rpy_rad).transpose();
  const Vec3 g_n = normal_gravity_ned(p);
  const Vec3 w_ie_n = earth_rate_ned(p.lat_rad);
  // Then every increment is the closed form: dv = -C_n_b g dt, dtheta = C_n_b w_ie dt
  for (const ImuIncrement& s : r.imu) {
    EXPECT_LT((s.dvel_b_mps - (-C_n_b * g_n * s.dt_s)).norm(), 1e-13);
    EXPECT_LT((s.dtheta_b_rad - C_n_b * w_ie_n * s.dt_s).norm(), 1e-18);
    EXPECT_NEAR(s.dvel_b_mps.norm() / s.dt_s, g_n.norm(), 1e-11);
  }
  // and the position never moves.
  for (const TruthSample& t : r.truth) EXPECT_LT(exact_ned(p, t.pos).norm(), 1e-9);
}

TEST(SimTruthPhysics, ConstantSpeedCircleHasClosedFormCentripetalAccelerationAndYawRate) {
  // Given a level circle of radius 40 m at 8 m/s, entered without a ramp (constant yaw rate v/r)
  const std::string file = write_text("circle.yaml", R"(name: circle40
start: {lat_deg: 45, lon_deg: 7, h_m: 300, yaw_deg: 0, speed_mps: 8}
segments:
  - {type: circle, radius_m: 40, turns: 1, ramp_s: 0}
)");
  const double v = 8.0, radius = 40.0, yaw_rate = v / radius, turn_s = 2 * kPi / yaw_rate;
  const SimResult r = simulate(perfect_request(file, std::floor(turn_s * 100) / 100, 100.0));
  const Geodetic start = r.truth.front().pos;
  const Vec3 centre_n(0.0, radius, 0.0);  // to the right of the initial heading (north)
  for (size_t k = 0; k < r.truth.size(); k += 7) {
    const TruthSample& t = r.truth[k];
    const Mat3 C_n_b = C_b_n_from_euler(t.rpy_rad).transpose();
    const Vec3 w_ie = earth_rate_ned(t.pos.lat_rad), w_en = transport_rate_ned(t.pos, t.vel_n_mps);
    // Then the body sees the centripetal acceleration v^2/r to the right, plus gravity and Coriolis
    const Vec3 expected_f = Vec3(0.0, v * v / radius, 0.0) +
                            C_n_b * ((2 * w_ie + w_en).cross(t.vel_n_mps) - normal_gravity_ned(t.pos));
    EXPECT_LT((t.f_b_mps2 - expected_f).norm(), 1e-9) << "t = " << k;
    // and the gyros the yaw rate v/r plus the Earth and transport rates.
    const Vec3 expected_w = Vec3(0.0, 0.0, yaw_rate) + C_n_b * (w_ie + w_en);
    EXPECT_LT((t.omega_ib_b_rad_s - expected_w).norm(), 1e-12);
    // The vehicle stays on the circle (exact ECEF geometry; horizontal distance to the centre).
    const Vec3 d = exact_ned(start, t.pos) - centre_n;
    EXPECT_NEAR(std::hypot(d.x(), d.y()), radius, 1e-3);
  }
  // After (almost exactly) one turn the gyro z increments sum to the yaw turned plus the vertical
  // Earth rate (the transport rate's vertical part integrates to ~0 over a closed circle).
  double sum_z = 0;
  for (const auto& s : r.imu) sum_z += s.dtheta_b_rad.z();
  const double t_end = r.truth.back().t_s - r.truth.front().t_s;
  EXPECT_NEAR(sum_z, yaw_rate * t_end - kOmegaEarth * std::sin(start.lat_rad) * t_end, 1e-7);
  EXPECT_LT(exact_ned(start, r.truth.back().pos).norm(), v * (turn_s - t_end) + 1e-3);
}

TEST(SimTruthPhysics, TruthRatesAreTheDerivativesOfTheTruthStateOnAVariedDrive) {
  // Given 400 s of the default drive (turns, hills, circles, reversing) at 200 Hz
  const SimResult r = simulate(perfect_request("drive", 400.0, 200.0));
  const double dt = r.imu.front().dt_s;
  double worst_f = 0, worst_w = 0, worst_dtheta = 0, worst_dvel = 0;
  // Five-point central differences (truncation dt^4/30 times the fifth derivative).
  auto d5 = [&](auto get, size_t k) {
    using T = decltype(get(r.truth[k]));  // evaluate: no Eigen expression over temporaries
    return T((get(r.truth[k - 2]) - 8.0 * get(r.truth[k - 1]) + 8.0 * get(r.truth[k + 1]) - get(r.truth[k + 2])) /
             (12.0 * dt));
  };
  for (size_t k = 2; k + 2 < r.truth.size(); ++k) {
    const TruthSample &a = r.truth[k - 1], &t = r.truth[k], &b = r.truth[k + 1];
    const Vec3 w_ie = earth_rate_ned(t.pos.lat_rad), w_en = transport_rate_ned(t.pos, t.vel_n_mps);
    const Mat3 C_b_n = C_b_n_from_euler(t.rpy_rad);
    // Velocity equation: dv_n/dt = C_b_n f_b + g_n - (2 w_ie + w_en) x v_n
    const Vec3 dv_dt = d5([](const TruthSample& s) { return Vec3(s.vel_n_mps); }, k);
    const Vec3 rhs = C_b_n * t.f_b_mps2 + normal_gravity_ned(t.pos) - (2 * w_ie + w_en).cross(t.vel_n_mps);
    worst_f = std::max(worst_f, (dv_dt - rhs).norm());
    // Attitude equation: dC_b_n/dt = C_b_n [w_nb_b x], w_nb_b = w_ib_b - C_n_b (w_ie + w_en)
    const Mat3 dC = d5([](const TruthSample& s) { return Mat3(C_b_n_from_euler(s.rpy_rad)); }, k);
    const Vec3 w_nb = t.omega_ib_b_rad_s - C_b_n.transpose() * (w_ie + w_en);
    worst_w = std::max(worst_w, (dC - C_b_n * skew(w_nb)).norm());
    // Increments: Simpson's rule on the truth rates over two intervals.
    if (k % 2 == 1) {
      const Vec3 simpson_w = dt / 3 * (a.omega_ib_b_rad_s + 4 * t.omega_ib_b_rad_s + b.omega_ib_b_rad_s);
      const Vec3 simpson_f = dt / 3 * (a.f_b_mps2 + 4 * t.f_b_mps2 + b.f_b_mps2);
      worst_dtheta = std::max(worst_dtheta, (r.imu[k - 1].dtheta_b_rad + r.imu[k].dtheta_b_rad - simpson_w).norm());
      worst_dvel = std::max(worst_dvel, (r.imu[k - 1].dvel_b_mps + r.imu[k].dvel_b_mps - simpson_f).norm());
    }
  }
  // Then the residuals are at the level of the test's own numerical errors, far below any physical
  // term (a missing transport-rate term alone would leave ~1e-4 m/s^2, a missing Coriolis ~1e-3):
  EXPECT_LT(worst_f, 1e-6);
  EXPECT_LT(worst_w, 1e-7);
  // Simpson's rule is exact to h^5 f'''' only where the integrand is smooth; at the ends of a pitch
  // or roll ramp the second derivative of the rates jumps (quintic ramps are C2), which leaves
  // ~h^3 * jump / 24 ~ 3e-10 rad and ~3e-9 m/s (a missing Coriolis term would be 1.5e-5 m/s per 10 ms).
  EXPECT_LT(worst_dtheta, 1e-9);
  EXPECT_LT(worst_dvel, 1e-8);
}

TEST(SimTruthPhysics, IncrementsAreConvergedInTheNumberOfSubsteps) {
  // Given the hills scenario integrated with 2 and with 8 sub-steps per IMU interval
  const Scenario sc = load_scenario("hills");
  const MotionProfile m = compile_scenario(sc, 120.0);
  TruthOptions o;
  o.dt_s = 0.01;
  o.intervals = 12000;
  o.substeps = 2;
  const TruthRun coarse = integrate_truth(m, o);
  o.substeps = 8;
  const TruthRun fine = integrate_truth(m, o);
  // Then the increments and the final position agree to rounding level.
  double worst_theta = 0, worst_vel = 0;
  for (size_t k = 0; k < coarse.increments.size(); ++k) {
    worst_theta = std::max(worst_theta, (coarse.increments[k].dtheta_b_rad - fine.increments[k].dtheta_b_rad).norm());
    worst_vel = std::max(worst_vel, (coarse.increments[k].dvel_b_mps - fine.increments[k].dvel_b_mps).norm());
  }
  EXPECT_LT(worst_theta, 1e-13);
  EXPECT_LT(worst_vel, 1e-12);
  EXPECT_LT(exact_ned(coarse.truth.back().pos, fine.truth.back().pos).norm(), 1e-6);
}

namespace {
// A compact strapdown mechanisation (two-sample coning and sculling, midpoint Earth and transport
// rates, as in KF-GINS) written here only to check the simulator end to end.
struct Ins {
  Geodetic pos;
  Vec3 v;
  Quat q;  // body to NED
};
Ins propagate(const Ins& s, const ImuIncrement& prev, const ImuIncrement& cur) {
  const double dt = cur.dt_s;
  auto radii = [](const Geodetic& p) {
    const double a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f), sl = std::sin(p.lat_rad);
    const double RN = a / std::sqrt(1 - e2 * sl * sl);
    return std::pair<double, double>{RN * (1 - e2) / (1 - e2 * sl * sl), RN};
  };
  // Midpoint position and velocity by extrapolation.
  auto [RM, RN] = radii(s.pos);
  Geodetic mid = s.pos;
  mid.lat_rad += 0.5 * dt * s.v.x() / (RM + s.pos.h_m);
  mid.h_m -= 0.5 * dt * s.v.z();
  const Vec3 w_ie = earth_rate_ned(mid.lat_rad);
  const Vec3 w_en = transport_rate_ned(mid, s.v);
  const Vec3 g = normal_gravity_ned(mid);
  // Velocity.
  const Vec3 dvfb = cur.dvel_b_mps + 0.5 * cur.dtheta_b_rad.cross(cur.dvel_b_mps) +
                    (prev.dtheta_b_rad.cross(cur.dvel_b_mps) + prev.dvel_b_mps.cross(cur.dtheta_b_rad)) / 12.0;
  const Vec3 zeta = (w_ie + w_en) * dt;
  const Vec3 dvfn = (Mat3::Identity() - 0.5 * skew(zeta)) * (s.q.toRotationMatrix() * dvfb);
  const Vec3 v_mid_guess = s.v + 0.5 * (dvfn + (g - (2 * w_ie + w_en).cross(s.v)) * dt);
  const Vec3 w_en_mid = transport_rate_ned(mid, v_mid_guess);
  Ins out = s;
  out.v = s.v + dvfn + (g - (2 * w_ie + w_en_mid).cross(v_mid_guess)) * dt;
  // Position with the mean velocity.
  const Vec3 vm = 0.5 * (s.v + out.v);
  out.pos.h_m = s.pos.h_m - vm.z() * dt;
  const double hm = 0.5 * (s.pos.h_m + out.pos.h_m);
  out.pos.lat_rad = s.pos.lat_rad + vm.x() * dt / (RM + hm);
  auto [RM2, RN2] = radii(Geodetic{0.5 * (s.pos.lat_rad + out.pos.lat_rad), 0, 0});
  out.pos.lon_rad = s.pos.lon_rad + vm.y() * dt / ((RN2 + hm) * std::cos(0.5 * (s.pos.lat_rad + out.pos.lat_rad)));
  (void)RN;
  (void)RM2;
  // Attitude.
  const Vec3 phi = cur.dtheta_b_rad + prev.dtheta_b_rad.cross(cur.dtheta_b_rad) / 12.0;
  Geodetic mid2{0.5 * (s.pos.lat_rad + out.pos.lat_rad), 0, hm};
  const Vec3 zeta2 = (earth_rate_ned(mid2.lat_rad) + transport_rate_ned(mid2, vm)) * dt;
  out.q = (quat_from_rotvec(-zeta2) * s.q * quat_from_rotvec(phi)).normalized();
  return out;
}
}  // namespace

TEST(SimTruthPhysics, FreeInertialTenMinutesOnPerfectDataStaysOnTheTruth) {
  // Given ten minutes of the manoeuvring drive (after its static minute) with a perfect IMU at 200 Hz
  SimRequest req = perfect_request("drive", 660.0, 200.0);
  const SimResult r = simulate(req);
  const size_t k0 = 12000;  // start the free-inertial run at 60 s, when the vehicle starts moving
  Ins ins{r.truth[k0].pos, r.truth[k0].vel_n_mps, quat_from_euler(r.truth[k0].rpy_rad)};
  // When an independent strapdown mechanisation integrates the increments alone
  for (size_t k = k0; k < r.imu.size(); ++k) ins = propagate(ins, r.imu[k - 1], r.imu[k]);
  // Then it ends within 0.5 m horizontally and 0.002 deg in heading of the truth.
  const TruthSample& t = r.truth.back();
  const Vec3 err = exact_ned(t.pos, ins.pos);
  const Vec3 rpy = euler_from_C_b_n(ins.q.toRotationMatrix());
  EXPECT_LT(std::hypot(err.x(), err.y()), 0.5) << err.transpose();
  EXPECT_LT(std::abs(wrap_pi(rpy.z() - t.rpy_rad.z())) * kRadToDeg, 0.002);
  RecordProperty("horizontal_drift_m", std::to_string(std::hypot(err.x(), err.y())));
  std::printf("free-inertial 600 s on perfect data: horizontal %.4f m, vertical %.4f m, heading %.2e deg\n",
              std::hypot(err.x(), err.y()), err.z(), wrap_pi(rpy.z() - t.rpy_rad.z()) * kRadToDeg);
}
