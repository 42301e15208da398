// `ldv diagnose` with the land-vehicle aids (issue 16), as a user runs it:
//   ldv diagnose --kfgins-config FILE.yaml --aid nhc|odometer --json OUT.json
// Given simulated MEMS drives with one hidden vehicle effect the aid sees (an IMU mounted 2 deg off the
// vehicle axes in yaw; an odometer reading 1 % long), the verdict adds exactly that effect and its
// estimate holds the simulated value within 3 sigma.
#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/simulator.hpp"

namespace ldv {
namespace {
namespace fs = std::filesystem;

// The verdict of `ldv diagnose` on a simulated drive: JSON (YAML) root.
YAML::Node diagnose_drive(sim::SimRequest req, const std::string& aid, const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("ldv_diag_aid_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  sim::SimResult s = sim::simulate(req);
  sim::write_outputs(s, (dir / "drive").string());
  const fs::path json = dir / "d.json", log = dir / "diagnose.log";
  const std::string cmd = std::string(LDV_BIN_DIR) + "/ldv diagnose --kfgins-config " + (dir / "drive" / "kfgins.yaml").string() +
                          " --aid " + aid + " --json " + json.string() + " --quiet > " + log.string() + " 2>&1";
  const int rc = std::system(cmd.c_str());
  std::stringstream out;
  out << std::ifstream(log).rdbuf();
  EXPECT_EQ(rc, 0) << cmd << "\n" << out.str();
  YAML::Node d = rc == 0 ? YAML::LoadFile(json.string()) : YAML::Node();
  fs::remove_all(dir);
  return d;
}

sim::SimRequest mems_drive(uint64_t seed) {
  sim::SimRequest req;
  req.grade = "3dm-gx2-typical";
  req.seed = seed;
  req.duration_s = 480.0;
  req.scenario = "drive";
  req.gnss_rate_hz = 1.0;
  return req;
}

TEST(DiagnoseAids, NhcNamesAMountingTwoDegreesOffInYaw) {
  sim::SimRequest req = mems_drive(8);
  req.vehicle.mounting_rpy_deg = Vec3(0.0, 0.0, 2.0);
  const YAML::Node d = diagnose_drive(req, "nhc", "mounting");
  ASSERT_TRUE(d["verdict"]["add"].IsSequence());
  ASSERT_EQ(d["verdict"]["add"].size(), 1u);
  EXPECT_EQ(d["verdict"]["add"][0].as<std::string>(), "vehicle_mounting");
  const YAML::Node e = d["verdict"]["estimates"][0];
  ASSERT_EQ(e["effect"].as<std::string>(), "vehicle_mounting");
  // To first order the residual rotation equals the mounting angles (C_b_v ~ I + [mu x]).
  const double yaw = e["value"][2].as<double>(), sd = e["sigma"][2].as<double>();
  EXPECT_LT(std::abs(yaw - 2.0 * kDegToRad), 3.0 * sd) << yaw * kRadToDeg << " +- " << sd * kRadToDeg << " deg";
  EXPECT_LT(sd, 0.25 * kDegToRad) << "the yaw of the mounting is well observed by NHC at speed";
}

TEST(DiagnoseAids, OdometerNamesAOnePercentScaleError) {
  sim::SimRequest req = mems_drive(9);
  req.vehicle.odometer = true;
  req.effects = {"odometer_scale=1"};  // percent
  const YAML::Node d = diagnose_drive(req, "odometer", "scale");
  ASSERT_TRUE(d["verdict"]["add"].IsSequence());
  ASSERT_EQ(d["verdict"]["add"].size(), 1u);
  EXPECT_EQ(d["verdict"]["add"][0].as<std::string>(), "odometer_scale");
  const YAML::Node e = d["verdict"]["estimates"][0];
  const double k = e["value"][0].as<double>(), sd = e["sigma"][0].as<double>();
  EXPECT_LT(std::abs(k - 0.01), 3.0 * sd) << k << " +- " << sd;
  EXPECT_LT(sd, 0.001);
}

}  // namespace
}  // namespace ldv
