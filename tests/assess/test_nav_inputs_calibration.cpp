// The calibration file applied by the file inputs of ldv nav / outage / diagnose (toolbox/assess/nav_inputs.hpp).
// Truth comes from outside the calibration code: the simulator's own sensor model (sim/imu_error_model.cpp)
// corrupts the exact increments of a drive with a known bias, scale factor and non-orthogonality, and a
// calibration file holding those values, written here as text, must give the exact increments back. The gyro
// frame rotation and the order against --csv-axes are checked on the real walk with a sensor matrix built here.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/io/input_error.hpp"
#include "sim/simulator.hpp"
#include "toolbox/assess/nav_inputs.hpp"

namespace ldv::assess {
namespace {
// One directory per process: ctest runs the cases of this file in parallel processes, which must not share files.
std::string test_dir() {
  static const std::string dir = [] {
    const std::filesystem::path d = std::filesystem::path(::testing::TempDir()) / ("navcal_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d.string() + "/";
  }();
  return dir;
}

namespace fs = std::filesystem;

struct SimulatedFiles {
  std::string config;              // KF-GINS configuration of the run
  std::map<std::string, std::vector<double>> truth;  // the simulator's injected effects, SI
};

// A 60 s figure-eight without noise, written as KF-GINS files into TempDir/name.
SimulatedFiles simulate_files(const std::string& name, const std::vector<std::string>& effects) {
  sim::SimRequest req;
  req.grade = "perfect";
  req.with_noise = false;
  req.duration_s = 60.0;
  req.scenario = "figure8";
  req.effects = effects;
  sim::SimResult r = sim::simulate(req);
  const fs::path dir = fs::path(test_dir()) / name;
  fs::create_directories(dir);
  r.kfgins.imu_path = (dir / "imu.txt").string();
  r.kfgins.gnss_path = (dir / "gnss.txt").string();
  r.kfgins.output_path = dir.string();
  write_kfgins_imu(r.kfgins.imu_path, r.imu);
  write_kfgins_gnss(r.kfgins.gnss_path, r.gnss, false);
  const std::string config = (dir / "kfgins.yaml").string();
  save_kfgins_config(r.kfgins, config);
  return {config, r.injected_effects};
}

// Error-free increments, and the same drive seen by a MEMS-sized faulty sensor (values in the effects' units).
const SimulatedFiles& exact_run() {
  static const SimulatedFiles f = simulate_files("navcal_exact", {});
  return f;
}
const SimulatedFiles& faulty_run() {
  static const SimulatedFiles f = simulate_files(
      "navcal_faulty", {"gyro_bias=1800,-3600,2700", "accel_bias=50,-80,120", "gyro_scale=5000,-3000,8000",
                        "accel_scale=2000,-1500,3000", "gyro_misalignment=2000,-1500,1000",
                        "accel_misalignment=400,-300,600"});
  return f;
}

std::string triple(const std::vector<double>& v, double unit = 1.0) {
  char s[128];
  std::snprintf(s, sizeof s, "[%.17g, %.17g, %.17g]", v.at(0) / unit, v.at(1) / unit, v.at(2) / unit);
  return s;
}

// The calibration file for the faulty run, from the simulator's truth (scale in ppm, the rest SI).
std::string write_truth_calibration(const std::string& path, const std::string& sigma_lines = "") {
  const auto& t = faulty_run().truth;
  std::ofstream(path) << "format: ldv_imu_calibration_v1\ndescription: simulator truth\n"
                      << "accel:\n  bias_mps2: " << triple(t.at("accel_bias"))
                      << "\n  scale_ppm: " << triple(t.at("accel_scale"), 1e-6)
                      << "\n  misalignment_rad: " << triple(t.at("accel_misalignment")) << "\n"
                      << "gyro:\n  bias_rad_s: " << triple(t.at("gyro_bias"))
                      << "\n  scale_ppm: " << triple(t.at("gyro_scale"), 1e-6)
                      << "\n  misalignment_rad: " << triple(t.at("gyro_misalignment")) << "\n"
                      << sigma_lines;
  return path;
}

// Largest error of `got` against `exact`, relative to the exact increment's size. imu.txt keeps 16 significant
// digits of an increment but its interval comes from two time tags near 3.5e5 s, whose difference is up to
// ~5e-11 s off 1/200 s: the corrected bias * dt carries that, times M^-1 (gain <= 1.05 for these sensor errors),
// which is allowed for.
double worst_relative_error(const std::vector<ImuIncrement>& got, const std::vector<ImuIncrement>& exact,
                            const Vec3& gyro_bias = Vec3::Zero(), const Vec3& accel_bias = Vec3::Zero()) {
  EXPECT_EQ(got.size(), exact.size());
  double worst = 0.0;
  for (size_t k = 0; k < std::min(got.size(), exact.size()); ++k) {
    EXPECT_EQ(got[k].t_s, exact[k].t_s);
    const double dt_error_s = std::abs(got[k].dt_s - 1.0 / 200.0);
    EXPECT_LT(dt_error_s, 1e-9) << k;
    const double e_theta = (got[k].dtheta_b_rad - exact[k].dtheta_b_rad).norm() - 1.05 * gyro_bias.norm() * dt_error_s;
    const double e_vel = (got[k].dvel_b_mps - exact[k].dvel_b_mps).norm() - 1.05 * accel_bias.norm() * dt_error_s;
    worst = std::max(worst, e_theta / exact[k].dtheta_b_rad.norm());
    worst = std::max(worst, e_vel / exact[k].dvel_b_mps.norm());
  }
  return worst;
}

Vec3 truth_vec3(const std::string& effect) {
  const std::vector<double>& v = faulty_run().truth.at(effect);
  return Vec3(v.at(0), v.at(1), v.at(2));
}

NavInputArgs config_args(const std::string& config) {
  NavInputArgs a;
  a.config = config;
  return a;
}

TEST(NavInputsCalibration, GivenIncrementsWithKnownSensorErrors_WhenLoadedWithTheirCalibration_ThenTheExactOnesComeBack) {
  const std::vector<ImuIncrement> exact = load_nav_inputs(config_args(exact_run().config)).imu;
  ASSERT_GT(exact.size(), 10000u);

  NavInputArgs a = config_args(faulty_run().config);
  const NavInputs raw = load_nav_inputs(a);
  // Without the calibration the errors are there: 0.5 deg/s gyro bias is ~1e-2 of a turn's rate.
  EXPECT_GT(worst_relative_error(raw.imu, exact), 1e-2);

  a.calibration = write_truth_calibration(test_dir() + "navcal_truth.yaml");
  const NavInputs corrected = load_nav_inputs(a);
  EXPECT_LT(worst_relative_error(corrected.imu, exact, truth_vec3("gyro_bias"), truth_vec3("accel_bias")), 1e-12);
  EXPECT_NE(corrected.imu_note.find("navcal_truth.yaml applied"), std::string::npos) << corrected.imu_note;
}

TEST(NavInputsCalibration, GivenTheConfigKey_ThenARelativePathIsFoundBesideTheConfig_AndTheCommandLineOverridesIt) {
  // The configuration in its own directory, the calibration beside it, the working directory elsewhere.
  const fs::path dir = fs::path(test_dir()) / "navcal_key";
  fs::create_directories(dir);
  write_truth_calibration((dir / "imu_cal.yaml").string());
  ASSERT_FALSE(fs::exists("imu_cal.yaml"));
  KfGinsConfig cfg = load_kfgins_config(faulty_run().config);
  cfg.ldv["calibration"] = "imu_cal.yaml";
  save_kfgins_config(cfg, (dir / "kfgins.yaml").string());

  const std::vector<ImuIncrement> exact = load_nav_inputs(config_args(exact_run().config)).imu;
  const Vec3 b_g = truth_vec3("gyro_bias"), b_a = truth_vec3("accel_bias");
  EXPECT_LT(worst_relative_error(load_nav_inputs(config_args((dir / "kfgins.yaml").string())).imu, exact, b_g, b_a), 1e-12);

  cfg.ldv["calibration"] = "no_such_calibration.yaml";
  save_kfgins_config(cfg, (dir / "kfgins_other.yaml").string());
  NavInputArgs a = config_args((dir / "kfgins_other.yaml").string());
  EXPECT_THROW(load_nav_inputs(a), InputError);
  a.calibration = (dir / "imu_cal.yaml").string();  // the command line wins: the config's file is not read
  EXPECT_LT(worst_relative_error(load_nav_inputs(a).imu, exact, b_g, b_a), 1e-12);
}

TEST(NavInputsCalibration, GivenCalibrationSigmas_ThenTheyAreTheBiasAndScalePriorsUnlessTheConfigGivesThem) {
  const std::string path = test_dir() + "navcal_sigmas.yaml";
  std::ofstream(path) << "format: ldv_imu_calibration_v1\n"
                         "accel:\n  bias_mps2: [0, 0, 0]\n  scale_ppm: [0, 0, 0]\n  misalignment_rad: [0, 0, 0]\n"
                         "  bias_mps2_sigma: [1e-3, 2e-3, 3e-3]\n  scale_ppm_sigma: [100, 200, 300]\n"
                         "gyro:\n  bias_rad_s: [0, 0, 0]\n  scale_ppm: [0, 0, 0]\n  misalignment_rad: [0, 0, 0]\n"
                         "  bias_rad_s_sigma: [1e-4, 2e-4, 3e-4]\n  scale_ppm_sigma: [0, 500, 600]\n";
  KfGinsConfig cfg = load_kfgins_config(faulty_run().config);
  cfg.init_gyro_bias_std_rad_s.reset();
  cfg.init_accel_bias_std_mps2 = Vec3::Constant(5000 * 1e-5);  // initbastd 5000 mGal: the config's, kept
  cfg.init_gyro_scale_std.reset();
  cfg.init_accel_scale_std.reset();
  const std::string config = test_dir() + "navcal_sigmas_kfgins.yaml";
  save_kfgins_config(cfg, config);

  NavInputArgs a = config_args(config);
  const est::FilterOptions before = load_nav_inputs(a).options;
  a.calibration = path;
  const NavInputs in = load_nav_inputs(a);
  const est::FilterOptions& o = in.options;
  ASSERT_NE(before.gyro_bias.init_std, Vec3(1e-4, 2e-4, 3e-4));
  EXPECT_LT((o.gyro_bias.init_std - Vec3(1e-4, 2e-4, 3e-4)).norm(), 1e-18);
  EXPECT_LT((o.gyro_moving_bias.constant_std - Vec3(1e-4, 2e-4, 3e-4)).norm(), 1e-18);
  EXPECT_LT((o.accel_scale.init_std - Vec3(100e-6, 200e-6, 300e-6)).norm(), 1e-15);
  EXPECT_LT((o.accel_bias.init_std - Vec3::Constant(0.05)).norm(), 1e-15) << "initbastd is in the config";
  EXPECT_EQ(o.gyro_scale.init_std, before.gyro_scale.init_std) << "an axis without a sigma: the prior stays";
  EXPECT_EQ(o.gyro_bias.sigma, before.gyro_bias.sigma) << "only the prior changes, not the process";
  EXPECT_NE(in.imu_note.find("prior std of gyro_bias, accel_scale"), std::string::npos) << in.imu_note;
}

TEST(NavInputsCalibration, GivenAMissingOrBadCalibration_ThenInputErrorNamesTheFileAndKey) {
  NavInputArgs a = config_args(faulty_run().config);
  a.calibration = test_dir() + "navcal_does_not_exist.yaml";
  try {
    load_nav_inputs(a);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("navcal_does_not_exist.yaml"), std::string::npos) << e.what();
  }
  // Degrees where radians belong.
  a.calibration = test_dir() + "navcal_degrees.yaml";
  std::ofstream(a.calibration) << "format: ldv_imu_calibration_v1\naccel:\n  bias_mps2: [0, 0, 0]\n  scale_ppm: [0, 0, 0]\n"
                                  "  misalignment_rad: [0, 0, 0]\ngyro:\n  bias_rad_s: [0, 0, 0]\n  scale_ppm: [0, 0, 0]\n"
                                  "  misalignment_rad: [0.1, 2.5, 0]\n";
  try {
    load_nav_inputs(a);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("navcal_degrees.yaml:9"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("gyro.misalignment_rad"), std::string::npos) << e.what();
  }
  // The configuration key must be a path.
  KfGinsConfig cfg = load_kfgins_config(faulty_run().config);
  cfg.ldv["calibration"].push_back("a.yaml");
  const std::string config = test_dir() + "navcal_bad_key.yaml";
  save_kfgins_config(cfg, config);
  try {
    load_nav_inputs(config_args(config));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("navcal_bad_key.yaml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("ldv.calibration"), std::string::npos) << e.what();
  }
}

// The real walk's device is x forward, y left, z up (--csv-axes 1 -2 -3). A calibration of that device is in
// its own axes; applied after the remap, its y and z biases would land with the wrong sign.
TEST(NavInputsCalibration, GivenATaggedCsv_ThenTheCalibrationIsAppliedInTheDeviceAxesBeforeTheRemap) {
  const std::string walk = std::string(LDV_SHARED_DATA_DIR) + "/drives/walk_0827/";
  NavInputArgs a;
  a.imu_csv = walk + "imu_1730.csv";
  a.rtklib_pos = walk + "gnss_1730_sf.pos";
  a.csv_axes = {1, -2, -3};
  const std::vector<ImuIncrement> body = load_nav_inputs(a).imu;
  ASSERT_GT(body.size(), 1000u);

  const Vec3 b_a(0.05, -0.08, 0.12), s_a(2e-3, -1.5e-3, 3e-3), m_a(1e-3, -2e-3, 1.5e-3);
  const Vec3 b_g(0.01, -0.014, 0.005), s_g(1e-2, -2e-2, 1.5e-2), m_g(5e-3, -4e-3, 6e-3), theta_g(8e-3, -6e-3, 5e-3);
  a.calibration = test_dir() + "navcal_walk.yaml";
  std::ofstream(a.calibration) << "format: ldv_imu_calibration_v1\naccel:\n  bias_mps2: [0.05, -0.08, 0.12]\n"
                                  "  scale_ppm: [2000, -1500, 3000]\n  misalignment_rad: [1e-3, -2e-3, 1.5e-3]\n"
                                  "gyro:\n  bias_rad_s: [0.01, -0.014, 0.005]\n  scale_ppm: [10000, -20000, 15000]\n"
                                  "  misalignment_rad: [5e-3, -4e-3, 6e-3]\n  frame_rotation_rad: [8e-3, -6e-3, 5e-3]\n";
  const std::vector<ImuIncrement> calibrated = load_nav_inputs(a).imu;
  ASSERT_EQ(calibrated.size(), body.size());

  // docs/effects.md by hand: meas = (I + diag(s) + N(m)) C_b_g true + b, C_b_g = Rot(theta)^T for the gyro.
  const auto symmetric = [](const Vec3& s, const Vec3& m) {
    Mat3 S;
    S << 1 + s.x(), m.z(), m.y(),  //
        m.z(), 1 + s.y(), m.x(),   //
        m.y(), m.x(), 1 + s.z();
    return S;
  };
  const Mat3 M_a = symmetric(s_a, m_a);
  const Mat3 M_g = symmetric(s_g, m_g) * Eigen::AngleAxisd(theta_g.norm(), theta_g.normalized()).toRotationMatrix().transpose();
  const Mat3 P = Vec3(1, -1, -1).asDiagonal();  // device -> front-right-down (its own inverse)
  double worst = 0.0;
  for (size_t k = 0; k < body.size(); ++k) {
    const double dt = body[k].dt_s;
    const Vec3 dtheta = P * M_g.inverse() * (P * body[k].dtheta_b_rad - b_g * dt);
    const Vec3 dvel = P * M_a.inverse() * (P * body[k].dvel_b_mps - b_a * dt);
    worst = std::max(worst, (calibrated[k].dtheta_b_rad - dtheta).norm() / (b_g * dt).norm());
    worst = std::max(worst, (calibrated[k].dvel_b_mps - dvel).norm() / (b_a * dt).norm());
  }
  EXPECT_LT(worst, 1e-10);
}

}  // namespace
}  // namespace ldv::assess
