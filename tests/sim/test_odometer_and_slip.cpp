// The odometer (odo.txt) against an independent rigid-body computation from the truth, its scale, noise
// and resolution, the files and config keys it comes with; and the land motion: no side slip unless
// --wheel-slip asks for it, then the slip of its definition, with increments consistent with the truth.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <GeographicLib/NormalGravity.hpp>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/odometer_text.hpp"
#include "sim_test_helpers.hpp"

using namespace ldv;
using namespace ldv::sim;
using namespace ldv::sim::test;
namespace fs = std::filesystem;

namespace {
constexpr double kOmegaEarth = 7.2921151467e-5;

// Forward speed of a point at lever arm l (IMU body axes) from the truth sample alone:
// v_point = v_n + C_b_n ((w_ib_b - C_n_b w_ie_n) x l) - the transport rate is below 1e-6 rad/s here and
// left out - then along the vehicle x axis, C_v_n = C_b_n C_b_v^T.
double forward_speed(const TruthSample& t, const Vec3& l, const Mat3& C_b_v) {
  const Mat3 C_b_n = C_b_n_from_euler(t.rpy_rad);
  const Vec3 w_ie_n(kOmegaEarth * std::cos(t.pos.lat_rad), 0.0, -kOmegaEarth * std::sin(t.pos.lat_rad));
  const Vec3 w_eb_b = t.omega_ib_b_rad_s - C_b_n.transpose() * w_ie_n;
  const Vec3 v_point_n = t.vel_n_mps + C_b_n * w_eb_b.cross(l);
  return ((C_b_n * C_b_v.transpose()).transpose() * v_point_n).x();
}

SimRequest odometer_request(const std::string& scenario, double duration_s) {
  SimRequest q = perfect_request(scenario, duration_s, 100.0);
  q.vehicle.odometer = true;
  q.vehicle.odo_noise_mps = 0.0;
  return q;
}

size_t odometer_truth_index(const SimResult& r, double t_sow) {
  return static_cast<size_t>(std::llround((t_sow - r.truth.front().t_s) * r.request.imu_rate_hz));
}
}  // namespace

TEST(SimOdometer, SpeedIsTheVehicleForwardSpeedOfTheOdometerPoint) {
  // Given a rear-axle centre 1.4 m behind, 0.2 m right of and 0.3 m below the IMU, and the IMU mounted
  // upside down and backwards (so body x is not the direction of travel)
  for (const Vec3& mount : {Vec3(0, 0, 0), Vec3(180, 0, 180), Vec3(0, 2, -90)}) {
    SimRequest q = odometer_request("drive", 400.0);
    q.vehicle.mounting_rpy_deg = mount;
    const Mat3 C_b_v = C_b_n_from_euler(mount * kDegToRad);
    const Vec3 l_v(-1.4, 0.2, 0.3);  // vehicle axes
    q.vehicle.odo_lever_arm_b_m = C_b_v.transpose() * l_v;
    const SimResult r = simulate(q);
    ASSERT_EQ(r.odometer.size(), 400u * 50u + 1u);
    double worst = 0, most_negative = 0, fastest = 0;
    for (const OdometerSample& s : r.odometer) {
      const size_t k = odometer_truth_index(r, s.t_s);
      ASSERT_NEAR(r.truth[k].t_s, s.t_s, 1e-9);  // 50 Hz on the 100 Hz grid: true GPS time
      worst = std::max(worst, std::abs(s.speed_mps - forward_speed(r.truth[k], q.vehicle.odo_lever_arm_b_m, C_b_v)));
      most_negative = std::min(most_negative, s.speed_mps);
      fastest = std::max(fastest, s.speed_mps);
    }
    // Then odo.txt is that speed (the transport-rate term left out above is < 1e-5 m/s)
    EXPECT_LT(worst, 2e-5) << mount.transpose();
    EXPECT_GT(fastest, 24.0);        // forward is positive whatever the mounting
    EXPECT_LT(most_negative, -1.0);  // the drive reverses (at ~285 s)
  }
}

TEST(SimOdometer, ScaleNoiseAndResolutionAsDefined) {
  SimRequest q = odometer_request("drive", 100.0);
  const SimResult base = simulate(q);
  q.effects = {"odometer_scale=2"};  // percent
  const SimResult scaled = simulate(q);
  EXPECT_NEAR(scaled.injected_effects.at("odometer_scale")[0], 0.02, 1e-15);
  for (size_t i = 0; i < base.odometer.size(); ++i)
    ASSERT_NEAR(scaled.odometer[i].speed_mps, 1.02 * base.odometer[i].speed_mps, 1e-12);

  q.effects.clear();
  q.with_noise = true;
  q.vehicle.odo_noise_mps = 0.05;
  const SimResult noisy = simulate(q);
  double ss = 0;
  for (size_t i = 0; i < base.odometer.size(); ++i)
    ss += std::pow(noisy.odometer[i].speed_mps - base.odometer[i].speed_mps, 2);
  EXPECT_NEAR(std::sqrt(ss / base.odometer.size()) / 0.05, 1.0, 0.05);  // 5001 samples: 1 % std

  q.vehicle.odo_quantum_mps = 0.1;
  const SimResult quantised = simulate(q);
  for (const OdometerSample& s : quantised.odometer)
    ASSERT_NEAR(s.speed_mps / 0.1, std::round(s.speed_mps / 0.1), 1e-9);
}

TEST(SimOdometer, IsNotLateWithTheImuAndWritesItsFileConfigKeyAndTruth) {
  SimRequest q = odometer_request("stops", 30.0);
  q.vehicle.imu_latency_s = 0.2;
  q.vehicle.odo_lever_arm_b_m = Vec3(-1.2, 0.0, 0.4);
  SimResult r = simulate(q);
  EXPECT_NEAR(r.odometer.front().t_s, q.start_sow_s, 1e-9);  // true GPS time, not tag time
  const fs::path dir = temp_dir("odometer_files");
  write_outputs(r, dir.string());
  const auto odo = read_odometer_text((dir / "odo.txt").string());
  ASSERT_EQ(odo.size(), r.odometer.size());
  EXPECT_NEAR(odo[700].speed_mps, r.odometer[700].speed_mps, 1e-6);
  const KfGinsConfig c = load_kfgins_config((dir / "kfgins.yaml").string());
  EXPECT_EQ(c.ldv["odopath"].as<std::string>(), (dir / "odo.txt").string());
  const YAML::Node key = YAML::LoadFile((dir / "truth_effects.yaml").string());
  EXPECT_EQ(key["effects"]["odometer_lever_arm"]["si"][0].as<double>(), -1.2);
  EXPECT_EQ(key["effects"]["odometer_scale"]["unit"].as<std::string>(), "%");
  EXPECT_EQ(key["effects"]["vehicle_mounting"]["si"][2].as<double>(), 0.0);
  EXPECT_FALSE(fs::exists(dir / "datasheet.yaml"));  // only with --realism vehicle
}

TEST(SimLandMotion, NoSideSlipByDefaultAndTheDefinedSlipWithWheelSlip) {
  // Given the drive (turns both ways, circle, figure-eight at up to 25 m/s)
  SimRequest q = perfect_request("drive", 300.0, 100.0);
  const SimResult plain = simulate(q);
  q.vehicle.wheel_slip_deg_per_mps2 = 0.5;
  const SimResult slip = simulate(q);
  double worst_lateral = 0, worst_slip = 0, largest_slip = 0;
  for (size_t k = 1; k + 1 < plain.truth.size(); ++k) {
    // Then without slip the velocity has no component across the vehicle,
    const TruthSample& t = plain.truth[k];
    const Vec3 v_v = C_b_n_from_euler(t.rpy_rad).transpose() * t.vel_n_mps;
    worst_lateral = std::max(worst_lateral, std::hypot(v_v.y(), v_v.z()));
    // and with it the velocity leaves vehicle x by beta = -k speed yaw_rate (yaw rate from the truth itself).
    const TruthSample& s = slip.truth[k];
    const Vec3 u_v = C_b_n_from_euler(s.rpy_rad).transpose() * s.vel_n_mps;
    const double yaw_rate = wrap_pi(slip.truth[k + 1].rpy_rad.z() - slip.truth[k - 1].rpy_rad.z()) / 0.02;
    if (u_v.norm() < 1.0) continue;
    // v_v = speed (cos b, sin b, 0) with a signed speed (negative reversing)
    const double speed = std::copysign(u_v.norm(), u_v.x());
    const double beta = std::atan(u_v.y() / u_v.x()), expected = -0.5 * kDegToRad * speed * yaw_rate;
    worst_slip = std::max(worst_slip, std::abs(beta - expected));
    largest_slip = std::max(largest_slip, std::abs(beta));
  }
  EXPECT_LT(worst_lateral, 1e-12);
  // central difference of the yaw: error ~ yaw''' dt^2 / 6, and pitch/roll make yaw rate and heading rate
  // differ slightly on hills and banks
  EXPECT_LT(worst_slip, 2e-3);
  EXPECT_GT(largest_slip, 0.01);  // ~1 deg at 25 m/s on the turns
  EXPECT_NEAR(slip.injected_effects.at("wheel_slip")[0], 0.5 * kDegToRad, 1e-15);
}

TEST(SimLandMotion, WheelSlipIncrementsStayConsistentWithTheTruth) {
  // The specific force from the increments against 5-point finite differences of the truth velocity:
  // f_n = dv/dt + (2 w_ie + w_en) x v - g (checks the slip's rate term d beta / dt is in the physics).
  SimRequest q = perfect_request("turns", 120.0, 100.0);
  q.vehicle.wheel_slip_deg_per_mps2 = 0.5;
  const SimResult r = simulate(q);
  const double dt = 0.01;
  double worst = 0;
  for (size_t k = 3; k + 3 < r.truth.size(); k += 5) {
    const TruthSample& t = r.truth[k];
    const Vec3 dv = (r.truth[k - 2].vel_n_mps - 8.0 * r.truth[k - 1].vel_n_mps + 8.0 * r.truth[k + 1].vel_n_mps -
                     r.truth[k + 2].vel_n_mps) /
                    (12.0 * dt);
    // The truth's own sensed f_b (what the increments integrate) rotated into NED.
    const Vec3 f_n = C_b_n_from_euler(t.rpy_rad) * t.f_b_mps2;
    const Vec3 w_ie_n(kOmegaEarth * std::cos(t.pos.lat_rad), 0.0, -kOmegaEarth * std::sin(t.pos.lat_rad));
    const double a = 6378137.0, e2 = 6.69437999014e-3, s = std::sin(t.pos.lat_rad);
    const double RN = a / std::sqrt(1 - e2 * s * s), RM = RN * (1 - e2) / (1 - e2 * s * s);
    const Vec3 w_en_n(t.vel_n_mps.y() / (RN + t.pos.h_m), -t.vel_n_mps.x() / (RM + t.pos.h_m),
                      -t.vel_n_mps.y() * std::tan(t.pos.lat_rad) / (RN + t.pos.h_m));
    double gn = 0, gu = 0;
    GeographicLib::NormalGravity::WGS84().Gravity(t.pos.lat_rad * kRadToDeg, t.pos.h_m, gn, gu);
    const Vec3 g_n(gn, 0.0, -gu);
    worst = std::max(worst, (f_n - (dv + (2.0 * w_ie_n + w_en_n).cross(t.vel_n_mps) - g_n)).norm());
  }
  EXPECT_LT(worst, 2e-4);
}
