// Issue 36, "self-calibration reports what it found": an IMU whose stamps are 150 ms late is found by the latency
// search and taken out before the diagnosis; `ldv diagnose` must say so (text and JSON `self_calibration`), with the
// value inside 3 sigma of the simulator's truth, instead of "nothing to add (the model is consistent)" alone.
#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "sim/simulator.hpp"
#include "tests/hardening/cli_run.hpp"

namespace ldv {
namespace fs = std::filesystem;

TEST(SelfCalibration, GivenImuStampsLate_ThenDiagnoseReportsTheLatencyItTookOutWithItsSigma) {
  // Given: a tactical drive whose IMU tags are 150 ms late (nothing else hidden), 5 Hz RTK positions only
  const fs::path dir = fs::temp_directory_path() / ("ldv_self_calibration_" + std::to_string(getpid()));
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.seed = 8;
  req.duration_s = 600.0;
  req.scenario = "drive";
  req.gnss_rate_hz = 5.0;
  req.vehicle.imu_latency_s = 0.15;
  sim::SimResult sim = sim::simulate(req);
  sim::write_outputs(sim, dir.string());
  // When
  const fs::path json = dir / "diagnosis.json";
  const test::CliResult r = test::run_ldv(
      {"diagnose", "--kfgins-config", (dir / "kfgins.yaml").string(), "--json", json.string(), "--quiet"}, 240.0);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // Then: the text names it, the JSON carries it as time_offset = -latency (GPS time = IMU time + time_offset)
  EXPECT_NE(r.output.find("Self-calibration"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("IMU stamps late by"), std::string::npos) << r.output;
  const YAML::Node d = YAML::LoadFile(json.string());
  ASSERT_TRUE(d["self_calibration"].IsSequence());
  bool found = false;
  for (const YAML::Node& c : d["self_calibration"]) {
    if (c["name"].as<std::string>() != "time_offset") continue;
    found = true;
    const double estimate_s = c["estimate"][0].as<double>(), sigma_s = c["sigma"][0].as<double>();
    std::printf("self_calibration time_offset %.1f +- %.1f ms (true -150 ms), applied %s\n", 1e3 * estimate_s,
                1e3 * sigma_s, c["applied"].as<bool>() ? "yes" : "no");
    EXPECT_TRUE(c["applied"].as<bool>());
    EXPECT_GT(sigma_s, 0.0);
    EXPECT_NEAR(estimate_s, -0.15, 3.0 * sigma_s + 0.002);
  }
  EXPECT_TRUE(found) << "no time_offset in self_calibration";
  fs::remove_all(dir);
}

// Issue 48, item 5: whether the GNSS velocities are fused is the system's own decision, so `ldv diagnose` lists it
// with what it rested on. The real walk's .pos velocities lag the positions by 0.1-0.15 s and differ from their
// chords by 0.13 m/s RMS against a stated 0.05 m/s (tests/estimator/data/walk_0827_mems.yaml, measured apart): with
// nothing configured, the check finds them several times their stated variance and does not use them.
TEST(SelfCalibration, GivenTheWalksLaggingGnssVelocities_ThenDiagnoseListsThatTheyWereNotUsedWithTheirMisfit) {
  const fs::path here = fs::path(__FILE__).parent_path();
  const fs::path walk = fs::path(LDV_SHARED_DATA_DIR) / "drives/walk_0827";
  if (!fs::exists(walk / "gnss_1730_sf.pos")) GTEST_SKIP() << "no shared walk data at " << walk;
  const fs::path dir = fs::temp_directory_path() / ("ldv_self_calibration_walk_" + std::to_string(getpid()));
  fs::create_directories(dir);
  // The test configuration with absolute paths and the velocity decision left to the system.
  std::ifstream given(here / "../estimator/data/walk_0827_mems.yaml");
  std::ofstream cfg(dir / "walk.yaml");
  for (std::string line; std::getline(given, line);) {
    if (line.rfind("imupath:", 0) == 0) line = "imupath: " + (walk / "imu_1730.csv").string();
    if (line.rfind("gnsspath:", 0) == 0) line = "gnsspath: " + (walk / "gnss_1730_sf.pos").string();
    if (line.find("use_gnss_velocity:") != std::string::npos) continue;
    cfg << line << "\n";
  }
  cfg.close();
  const fs::path json = dir / "diagnosis.json";
  const test::CliResult r = test::run_ldv(
      {"diagnose", "--kfgins-config", (dir / "walk.yaml").string(), "--json", json.string(), "--quiet"}, 240.0);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const YAML::Node d = YAML::LoadFile(json.string());
  bool found = false;
  for (const YAML::Node& c : d["self_calibration"]) {
    if (c["name"].as<std::string>() != "gnss_velocity") continue;
    found = true;
    const double misfit = c["estimate"][0].as<double>(), sigma = c["sigma"][0].as<double>();
    std::printf("self_calibration gnss_velocity: misfit %.2f +- %.2f, applied %s\n", misfit, sigma,
                c["applied"].as<bool>() ? "yes" : "no");
    EXPECT_FALSE(c["applied"].as<bool>());
    EXPECT_GT(misfit - 3.0 * sigma, 1.0);  // beyond a consistent 1 by more than 3 sigma
    EXPECT_GT(sigma, 0.0);
  }
  EXPECT_TRUE(found) << "no gnss_velocity in self_calibration";
  fs::remove_all(dir);
}

// Issue 48, item 5: the body heading an unknown mounting was found at is the system's own finding too. A tactical
// drive whose IMU is turned 90 deg in yaw in the car, no initial state, 8 headings to try (ldv.align_hypotheses):
// ldv diagnose lists body_heading with the IMU's x axis about 90 deg from the course, within its sigma (half the
// spacing of the headings tried).
TEST(SelfCalibration, GivenAnImuTurnedInTheCar_ThenDiagnoseListsTheBodyHeadingItStartedFrom) {
  const fs::path dir = fs::temp_directory_path() / ("ldv_self_calibration_heading_" + std::to_string(getpid()));
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.seed = 9;
  req.duration_s = 300.0;
  req.scenario = "drive";
  req.gnss_rate_hz = 5.0;
  req.vehicle.mounting_rpy_deg = Vec3(0.0, 0.0, 90.0);
  sim::SimResult sim = sim::simulate(req);
  sim::write_outputs(sim, dir.string());
  YAML::Node cfg = YAML::LoadFile((dir / "kfgins.yaml").string());
  for (const char* key : {"initpos", "initvel", "initatt", "initposstd", "initvelstd", "initattstd"}) cfg.remove(key);
  cfg["ldv"]["align_hypotheses"] = 8;
  std::ofstream(dir / "unknown_mounting.yaml") << cfg;
  const fs::path json = dir / "diagnosis.json";
  const test::CliResult r = test::run_ldv(
      {"diagnose", "--kfgins-config", (dir / "unknown_mounting.yaml").string(), "--json", json.string(), "--quiet"},
      240.0);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const YAML::Node d = YAML::LoadFile(json.string());
  bool found = false;
  for (const YAML::Node& c : d["self_calibration"]) {
    if (c["name"].as<std::string>() != "body_heading") continue;
    found = true;
    const double estimate_deg = c["estimate"][0].as<double>() * 180.0 / M_PI;
    const double sigma_deg = c["sigma"][0].as<double>() * 180.0 / M_PI;
    std::printf("self_calibration body_heading %.1f +- %.1f deg (the IMU turned 90 deg in the car)\n", estimate_deg,
                sigma_deg);
    EXPECT_TRUE(c["applied"].as<bool>());
    EXPECT_NEAR(estimate_deg, 90.0, sigma_deg);
  }
  EXPECT_TRUE(found) << "no body_heading in self_calibration\n" << r.output;
  fs::remove_all(dir);
}

}  // namespace ldv
