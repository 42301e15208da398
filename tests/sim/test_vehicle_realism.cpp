// The vehicle effects of `ldv sim` (sim/vehicle_realism.hpp) measured from the outputs against their
// definitions: IMU latency (tags vs truth, and the cross-correlation of the gyro with the true yaw rate),
// the IMU mounting (rotated sensing, body attitude in truth.nav), GNSS velocity lag, velocity noise and
// outliers, the --realism vehicle preset and datasheet.yaml, and the option errors.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <GeographicLib/NormalGravity.hpp>
#include <set>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/kfgins_files.hpp"
#include "sim/vehicle_realism.hpp"
#include "sim_test_helpers.hpp"

using namespace ldv;
using namespace ldv::sim;
using namespace ldv::sim::test;
namespace fs = std::filesystem;

namespace {
const std::string kLevelStart = R"(name: level_static
start: {lat_deg: 47.4, lon_deg: 8.5, h_m: 400, yaw_deg: 30, pitch_deg: 0, roll_deg: 0, speed_mps: 0}
segments:
  - {type: static, duration_s: 5}
)";

// Index of the truth sample at GPS time t (truth on the IMU grid from t0).
size_t truth_index(const SimResult& r, double t_sow) {
  return static_cast<size_t>(std::llround((t_sow - r.truth.front().t_s) * r.request.imu_rate_hz));
}
}  // namespace

TEST(SimImuLatency, ImuTagsAreTheTrueSampleTimePlusTheLatencyAndTruthStaysOnTrueTime) {
  // Given --imu-latency 0.137 s, written to files
  SimRequest q = perfect_request("turns", 60.0, 200.0);
  q.vehicle.imu_latency_s = 0.137;
  SimResult r = simulate(q);
  const fs::path dir = temp_dir("imu_latency");
  write_outputs(r, dir.string());
  const auto imu = read_kfgins_imu((dir / "imu.txt").string());
  const auto nav = read_nav((dir / "truth.nav").string());
  ASSERT_EQ(imu.size() + 1, nav.size());
  // Then every IMU tag is its true sample time (truth.nav, on the GPS grid) + 0.137 s
  for (size_t k = 0; k < imu.size(); ++k) ASSERT_NEAR(imu[k].t_s - nav[k + 1].sow_s, 0.137, 2e-6) << k;
  EXPECT_NEAR(nav.front().sow_s, q.start_sow_s, 1e-9);
  EXPECT_NEAR(r.injected_effects.at("imu_latency")[0], 0.137, 1e-15);
  // and the KF-GINS start is the first IMU tag.
  EXPECT_NEAR(load_kfgins_config((dir / "kfgins.yaml").string()).start_time_s, imu.front().t_s, 1e-6);
}

TEST(SimImuLatency, CrossCorrelationOfGyroWithTrueYawRateFindsTheLatency) {
  // Given a noisy hg1700-typical on turns with an IMU latency of 0.137 s
  SimRequest q = perfect_request("turns", 120.0, 200.0);
  q.grade = "hg1700-typical";
  q.with_noise = true;
  q.vehicle.imu_latency_s = 0.137;
  const SimResult r = simulate(q);
  // When the gyro z rate (at its tags) is cross-correlated with the true yaw rate (truth.nav yaw differences)
  const double dt = 0.005;
  std::vector<double> yaw_rate(r.truth.size(), 0.0);  // at truth times, central differences
  for (size_t j = 1; j + 1 < r.truth.size(); ++j)
    yaw_rate[j] = wrap_pi(r.truth[j + 1].rpy_rad.z() - r.truth[j - 1].rpy_rad.z()) / (2 * dt);
  auto correlation = [&](int lag) {  // gyro sample k, tagged t_k, against the truth at t_k - lag dt
    double s = 0;
    for (size_t k = 100; k + 100 < r.imu.size(); ++k) {
      const double t_true = r.imu[k].t_s - lag * dt - 0.5 * dt;  // increment centre
      const double x = (t_true - r.truth.front().t_s) / dt;
      const size_t j = static_cast<size_t>(x);
      const double u = x - j;
      s += r.imu[k].dtheta_b_rad.z() / dt * ((1 - u) * yaw_rate[j] + u * yaw_rate[j + 1]);
    }
    return s;
  };
  int best = 0;
  double c_best = -1e300;
  for (int lag = 0; lag <= 80; ++lag)
    if (const double c = correlation(lag); c > c_best) c_best = c, best = lag;
  // Then its peak (parabola through the best lag and its neighbours) is at the latency.
  const double cm = correlation(best - 1), cp = correlation(best + 1);
  const double lag_s = (best + 0.5 * (cm - cp) / (cm - 2 * c_best + cp)) * dt;
  EXPECT_NEAR(lag_s, 0.137, 0.003);
}

TEST(SimImuLatency, IsTheTimeOffsetEffectWithTheOppositeSign) {
  // An IMU late by S relates to the GNSS as --effect time_offset=-S does (a fix labelled t was taken at IMU
  // time t + S). Both put the offset on the IMU's tags (the GNSS tags are GPS time): the same data.
  SimRequest a = perfect_request("turns", 30.0, 100.0);
  a.gnss_rate_hz = 20.0;
  a.vehicle.imu_latency_s = 0.05;
  SimRequest b = a;
  b.vehicle.imu_latency_s.reset();
  b.effects = {"time_offset=-0.05"};
  const SimResult ra = simulate(a), rb = simulate(b);
  ASSERT_EQ(ra.imu.size(), rb.imu.size());
  for (size_t k = 0; k < ra.imu.size(); ++k) {
    ASSERT_NEAR(ra.imu[k].t_s, rb.imu[k].t_s, 1e-9);
    ASSERT_EQ(ra.imu[k].dvel_b_mps, rb.imu[k].dvel_b_mps);
  }
  // The fix labelled t is the same in both.
  size_t matched = 0;
  for (const GnssFix& fa : ra.gnss)
    for (const GnssFix& fb : rb.gnss)
      if (std::abs(fb.t_s - fa.t_s) < 1e-9) {
        EXPECT_LT(exact_ned(fa.pos, fb.pos).norm(), 1e-6) << fa.t_s;
        ++matched;
      }
  EXPECT_GT(matched, 500u);
}

TEST(SimMounting, ImuSensesTheVehicleQuantitiesRotatedAndTruthNavIsTheBodyAttitude) {
  const std::string level = write_text("level_static.yaml", kLevelStart);
  for (const Vec3& m_deg :
       {Vec3(180, 0, 180), Vec3(90, 0, -90), Vec3(0, -90, 90), Vec3(181.5 - 360, 1.2, -178.7), Vec3(3, -2, 91)}) {
    const Mat3 C_b_v = C_b_n_from_euler(m_deg * kDegToRad);  // Rz(yaw) Ry(pitch) Rx(roll), written out in rotation.hpp
    for (const std::string& scenario : {level, std::string("drive")}) {
      SimRequest q = perfect_request(scenario, 60.0, 100.0);
      const SimResult vehicle = simulate(q);
      q.vehicle.mounting_rpy_deg = m_deg;
      const SimResult body = simulate(q);
      if (scenario == level) {
        // Standing level, heading 30 deg: the specific force is C_b_v^T C_n_v (-g_n), g_n normal gravity.
        double gn = 0, gu = 0;
        GeographicLib::NormalGravity::WGS84().Gravity(47.4, 400.0, gn, gu);
        const Mat3 C_n_v = C_b_n_from_euler(Vec3(0, 0, 30) * kDegToRad).transpose();
        EXPECT_LT((body.imu[0].dvel_b_mps / 0.01 - C_b_v.transpose() * C_n_v * -Vec3(gn, 0, -gu)).norm(), 1e-11)
            << m_deg.transpose();
      }
      // Every increment is the vehicle's rotated into the body (the vehicle frame's are the unmounted run's)
      double worst_f = 0, worst_w = 0, worst_att = 0, worst_pos = 0;
      for (size_t k = 0; k < body.imu.size(); ++k) {
        worst_f = std::max(worst_f, (body.imu[k].dvel_b_mps - C_b_v.transpose() * vehicle.imu[k].dvel_b_mps).norm());
        worst_w =
            std::max(worst_w, (body.imu[k].dtheta_b_rad - C_b_v.transpose() * vehicle.imu[k].dtheta_b_rad).norm());
      }
      // and truth.nav holds the body attitude C_b_n = C_v_n C_b_v on the same trajectory.
      for (size_t k = 0; k < body.truth.size(); ++k) {
        const Mat3 expected = C_b_n_from_euler(vehicle.truth[k].rpy_rad) * C_b_v;
        worst_att = std::max(worst_att, (C_b_n_from_euler(body.truth[k].rpy_rad) - expected).norm());
        worst_pos = std::max(worst_pos, exact_ned(vehicle.truth[k].pos, body.truth[k].pos).norm());
      }
      EXPECT_LT(worst_f, 1e-12) << m_deg.transpose() << " " << scenario;
      EXPECT_LT(worst_w, 1e-15) << m_deg.transpose() << " " << scenario;
      EXPECT_LT(worst_att, 1e-12) << m_deg.transpose() << " " << scenario;
      EXPECT_EQ(worst_pos, 0.0);
    }
  }
}

TEST(SimMounting, LeverArmStaysInImuBodyAxes) {
  SimRequest q = perfect_request("drive", 120.0, 100.0);
  q.vehicle.mounting_rpy_deg = Vec3(180, 0, 90);
  q.effects = {"lever_arm=0.5,-0.3,-1.2"};
  const SimResult r = simulate(q);
  for (const GnssFix& g : r.gnss) {
    const TruthSample& t = r.truth[truth_index(r, g.t_s)];
    EXPECT_LT((exact_ned(t.pos, g.pos) - C_b_n_from_euler(t.rpy_rad) * Vec3(0.5, -0.3, -1.2)).norm(), 1e-5);
  }
}

TEST(SimMounting, TheTwentyFourAxisAlignedMountingsAndThePresetsDraw) {
  const auto all = axis_aligned_mountings_deg();
  ASSERT_EQ(all.size(), 24u);
  for (size_t i = 0; i < all.size(); ++i) {
    const Mat3 Ci = C_b_n_from_euler(all[i] * kDegToRad);
    EXPECT_NEAR(Ci.determinant(), 1.0, 1e-12);
    EXPECT_LT((Ci.cwiseAbs() - Ci.cwiseAbs().array().round().matrix()).norm(), 1e-12);  // axes onto axes
    for (size_t j = 0; j < i; ++j) EXPECT_GT((Ci - C_b_n_from_euler(all[j] * kDegToRad)).norm(), 1.0) << i << " " << j;
  }
  // The preset draws one of them with up to 2 deg per axis on top, differently per seed, the same per seed.
  std::set<int> picked;
  for (uint64_t seed = 1; seed <= 60; ++seed) {
    VehicleOptions o;
    o.realism = "vehicle";
    const VehicleRealism v = resolve_vehicle_options(o, seed);
    ASSERT_TRUE(v.mounted);
    int which = -1;
    for (size_t i = 0; i < all.size(); ++i) {
      const Vec3 d = v.mounting_rpy_rad * kRadToDeg - all[i];
      if (std::abs(wrap_pi(d.x() * kDegToRad)) <= 2 * kDegToRad && std::abs(d.y()) <= 2.0 &&
          std::abs(wrap_pi(d.z() * kDegToRad)) <= 2 * kDegToRad)
        which = static_cast<int>(i);
    }
    EXPECT_GE(which, 0) << (v.mounting_rpy_rad * kRadToDeg).transpose();
    picked.insert(which);
    EXPECT_EQ(resolve_vehicle_options(o, seed).mounting_rpy_rad, v.mounting_rpy_rad);
  }
  EXPECT_GE(picked.size(), 15u);  // 60 draws over 24 choices
}

TEST(SimGnssVelocity, LagGivesTheVelocityAtEpochMinusLagAndLeavesPositionsAlone) {
  SimRequest q = perfect_request("drive", 200.0, 100.0);
  q.gnss_velocity = true;
  q.gnss_rate_hz = 5.0;
  const SimResult base = simulate(q);
  q.vehicle.gnss_velocity_lag_s = 0.3;
  const SimResult r = simulate(q);
  ASSERT_EQ(r.gnss.size(), base.gnss.size());
  double moved = 0;
  for (size_t i = 0; i < r.gnss.size(); ++i) {
    const GnssFix& g = r.gnss[i];
    EXPECT_EQ(g.pos.lat_rad, base.gnss[i].pos.lat_rad);
    if (g.t_s - 0.3 < r.truth.front().t_s) continue;
    const TruthSample& then = r.truth[truth_index(r, g.t_s - 0.3)];
    EXPECT_LT((g.vel_n_mps - then.vel_n_mps).norm(), 1e-9) << g.t_s;
    moved = std::max(moved, (g.vel_n_mps - r.truth[truth_index(r, g.t_s)].vel_n_mps).norm());
  }
  EXPECT_GT(moved, 0.3);  // the drive accelerates and turns: the lag shows
}

TEST(SimGnssVelocity, NoiseFactorScalesTheSimulatedNoiseNotTheStatedStd) {
  SimRequest q = perfect_request("drive", 200.0, 100.0);
  q.gnss_velocity = true;
  q.gnss_rate_hz = 10.0;
  q.with_noise = true;
  q.vehicle.gnss_velocity_noise_factor = 3.0;
  const SimResult r = simulate(q);
  Vec3 sum_sq = Vec3::Zero();
  for (const GnssFix& g : r.gnss) {
    sum_sq += (g.vel_n_mps - r.truth[truth_index(r, g.t_s)].vel_n_mps).cwiseAbs2();
    ASSERT_EQ(g.vel_std_n_mps, Vec3(0.02, 0.02, 0.04));
  }
  const Vec3 sd = (sum_sq / static_cast<double>(r.gnss.size())).cwiseSqrt();
  // 2000 epochs: the std of a std estimate is 1.6 %.
  EXPECT_NEAR(sd.x() / 0.06, 1.0, 0.07);
  EXPECT_NEAR(sd.y() / 0.06, 1.0, 0.07);
  EXPECT_NEAR(sd.z() / 0.12, 1.0, 0.07);
}

TEST(SimGnssOutliers, RateSizeAndFlagsAsDefined) {
  SimRequest q = perfect_request("drive", 200.0, 100.0);
  q.gnss_rate_hz = 10.0;
  const SimResult base = simulate(q);
  q.vehicle.gnss_outlier_rate = 0.05;
  const SimResult r = simulate(q);
  ASSERT_EQ(r.gnss.size(), base.gnss.size());
  size_t jumps = 0, k = 0;
  for (size_t i = 0; i < r.gnss.size(); ++i) {
    const Vec3 d = exact_ned(base.gnss[i].pos, r.gnss[i].pos);
    EXPECT_EQ(r.gnss[i].quality, GnssQuality::kFixed);
    EXPECT_EQ(r.gnss[i].pos_std_ned_m, base.gnss[i].pos_std_ned_m);
    if (d.norm() < 1e-9) continue;
    ++jumps;
    // A jump of 1-3 m, recorded with its epoch and offset.
    EXPECT_GE(d.norm(), 1.0 - 1e-6);
    EXPECT_LE(d.norm(), 3.0 + 1e-6);
    ASSERT_LT(k, r.gnss_outliers.size());
    EXPECT_NEAR(r.gnss_outliers[k].t_s, r.gnss[i].t_s, 1e-9);
    EXPECT_LT((r.gnss_outliers[k].offset_ned_m - d).norm(), 1e-6);
    ++k;
  }
  EXPECT_EQ(jumps, r.gnss_outliers.size());
  // 2001 epochs at 5 %: ~100, std ~10.
  EXPECT_NEAR(static_cast<double>(jumps), 0.05 * r.gnss.size(), 40.0);
}

TEST(SimRealism, VehiclePresetTurnsEverythingOnRecordsItAndWritesADatasheetConfig) {
  SimRequest q = perfect_request("drive", 60.0, 100.0);
  q.grade = "hg1700-typical";
  q.with_noise = true;
  q.seed = 9;
  q.vehicle.realism = "vehicle";
  q.vehicle.gnss_velocity_lag_s = 0.2;  // given explicitly: wins over the preset's 0.1
  SimResult r = simulate(q);
  const auto& e = r.injected_effects;
  EXPECT_EQ(e.at("vibration_white_factor")[0], 10.0);
  EXPECT_EQ(e.at("shocks")[0], 2.0e-3);
  EXPECT_GE(e.at("imu_latency")[0], 0.0);
  EXPECT_LE(e.at("imu_latency")[0], 0.3);
  EXPECT_EQ(e.at("gnss_velocity_lag")[0], 0.2);
  EXPECT_EQ(e.at("gnss_velocity_noise_factor")[0], 3.0);
  EXPECT_EQ(e.at("gnss_outliers")[0], 0.005);
  EXPECT_EQ(e.at("vehicle_mounting").size(), 3u);
  EXPECT_LT(std::abs(e.at("odometer_scale")[0]), 0.03);  // N(0, 0.5 %)
  EXPECT_FALSE(r.odometer.empty());
  // The same seed draws the same; the datasheet config is what a new user writes.
  EXPECT_EQ(simulate(q).injected_effects, e);
  const fs::path dir = temp_dir("realism");
  write_outputs(r, dir.string());
  const KfGinsConfig ds = load_kfgins_config((dir / "datasheet.yaml").string());
  const KfGinsConfig kf = load_kfgins_config((dir / "kfgins.yaml").string());
  EXPECT_FALSE(ds.init_pos || ds.init_vel_n_mps || ds.init_rpy_rad);
  EXPECT_TRUE(kf.init_pos && kf.init_rpy_rad);
  EXPECT_EQ(ds.imu_path, kf.imu_path);
  EXPECT_NEAR(ds.imu_noise.arw_rad_per_sqrt_s.x(), 0.125 * kDegToRad / 60.0, 1e-15);  // the datasheet's, not x10
  EXPECT_EQ(ds.antenna_lever_b_m, Vec3::Zero());
  std::set<std::string> ldv_keys;
  for (const auto& kv : ds.ldv) ldv_keys.insert(kv.first.as<std::string>());
  EXPECT_EQ(ldv_keys, (std::set<std::string>{"week", "odopath"}));
  const YAML::Node key = YAML::LoadFile((dir / "truth_effects.yaml").string());
  EXPECT_EQ(key["simulator"]["realism"].as<std::string>(), "vehicle");
  EXPECT_EQ(key["effects"]["vehicle_mounting"]["unit"].as<std::string>(), "deg,deg,deg");
  EXPECT_EQ(key["shock_events"].size(), r.shocks.size());
}

TEST(SimRealism, NoneChangesNothing) {
  SimRequest q = perfect_request("drive", 30.0, 100.0);
  q.with_noise = true;
  q.grade = "hg1900-typical";
  const SimResult a = simulate(q);
  q.vehicle.realism = "none";
  const SimResult b = simulate(q);
  ASSERT_EQ(a.imu.size(), b.imu.size());
  for (size_t k = 0; k < a.imu.size(); ++k) ASSERT_EQ(a.imu[k].dvel_b_mps, b.imu[k].dvel_b_mps);
  EXPECT_EQ(a.injected_effects, b.injected_effects);
  EXPECT_TRUE(b.odometer.empty());
}

TEST(SimRealism, BadVehicleOptionsNameTheOptionAndTheExpectation) {
  auto err = [](const std::function<void(VehicleOptions&)>& set) {
    SimRequest q = perfect_request("static", 5.0);
    set(q.vehicle);
    return input_error_of([&] { simulate(q); });
  };
  EXPECT_NE(err([](VehicleOptions& v) {
              v.realism = "car";
            }).find("--realism: unknown realism 'car': expected none or vehicle"),
            std::string::npos);
  EXPECT_NE(
      err([](VehicleOptions& v) { v.vibration_factor = 0.5; }).find("--vibration: expected a factor in [1, 1000]"),
      std::string::npos);
  EXPECT_NE(err([](VehicleOptions& v) {
              v.mounting_rpy_deg = Vec3(0, 100, 0);
            }).find("--mounting: expected pitch in [-90, 90] deg, found 100"),
            std::string::npos);
  EXPECT_NE(
      err([](VehicleOptions& v) { v.imu_latency_s = -0.1; }).find("--imu-latency: expected a latency in [0, 1] s"),
      std::string::npos);
  EXPECT_NE(err([](VehicleOptions& v) {
              v.gnss_outlier_rate = 2;
            }).find("--gnss-outliers: expected a fraction of epochs in [0, 1]"),
            std::string::npos);
  EXPECT_NE(err([](VehicleOptions& v) {
              v.odo_rate_hz = 0;
            }).find("--odo-rate: expected an odometer rate in [0.1, 1000] Hz, found 0"),
            std::string::npos);
  EXPECT_NE(err([](VehicleOptions& v) { v.shocks_per_km = std::nan(""); }).find("--shocks: expected a rate"),
            std::string::npos);
}

TEST(SimRealismCli, RealismRunWritesOdometerAndDatasheetAndBadOptionsAreNamed) {
  const fs::path dir = temp_dir("cli_realism");
  const std::string ldv = std::string(LDV_BIN_DIR) + "/ldv sim --duration 20 --quiet --imu-rate 100 ";
  ASSERT_EQ(
      std::system((ldv + "--realism vehicle --mounting 180,0,180 --out " + dir.string() + " > /dev/null").c_str()), 0);
  for (const char* f : {"odo.txt", "datasheet.yaml", "kfgins.yaml", "imu.txt"}) EXPECT_TRUE(fs::exists(dir / f)) << f;
  const YAML::Node key = YAML::LoadFile((dir / "truth_effects.yaml").string());
  EXPECT_NEAR(key["effects"]["vehicle_mounting"]["value"][0].as<double>(), 180.0, 1e-9);  // given: not drawn
  const std::string log = (fs::temp_directory_path() / "ldv_sim_test_cli_realism.log").string();
  const int rc = std::system((ldv + "--odo-lever-arm 1,2 --out " + dir.string() + "_bad > " + log + " 2>&1").c_str());
  EXPECT_NE(rc, 0);
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("--odo-lever-arm"), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(dir.string() + "_bad"));
}
