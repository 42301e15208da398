// The shipped configurations load, and bad values are refused with the key named.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "services/gnss_link/gnss_link_options.hpp"
#include "services/imu_acq/imu_acq_options.hpp"

using namespace ldv;

TEST(AcqOptions, GivenTheDeployedConfigs_ThenTheyLoadWithTheirValues) {
  const auto g = gnss::load_gnss_link_options(std::string(LDV_SOURCE_DIR) + "/deploy/config/gnss_link.yaml");
  EXPECT_EQ(g.input.type, "tcp");
  EXPECT_EQ(g.input.tcp.port, 52001);
  EXPECT_EQ(g.decoder.protocol, gnss::LinkProtocol::kRtklib);
  EXPECT_DOUBLE_EQ(g.jump_gate.max_jump_m, 30.0);
  const auto i = imu::load_imu_acq_options(std::string(LDV_SOURCE_DIR) + "/deploy/config/imu_acq.yaml");
  EXPECT_EQ(i.protocol, imu::DeviceProtocol::kTsu);
  EXPECT_EQ(i.input.serial.baud, 460800);
  EXPECT_EQ(i.gx2_continuous_record, 0xC3);
  EXPECT_DOUBLE_EQ(i.tsu_counter_hz, 10e6);
  EXPECT_EQ(i.pps_source, imu::PpsSource::kDevice);
  EXPECT_TRUE(i.correction.C_device_to_body.isIdentity());
}

TEST(AcqOptions, GivenBadValues_ThenTheErrorNamesTheKey) {
  const auto path = std::filesystem::temp_directory_path() / ("acq_bad_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(path) << "protocol: sirf\n";
  try {
    gnss::load_gnss_link_options(path.string());
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("protocol"), std::string::npos);
  }
  std::ofstream(path) << "input: {type: serial, serial: {baud: 12345}}\n";
  EXPECT_THROW(imu::load_imu_acq_options(path.string()), std::runtime_error);
  std::ofstream(path) << "pps: {source: gps}\n";
  EXPECT_THROW(imu::load_imu_acq_options(path.string()), std::runtime_error);
  std::filesystem::remove(path);
}
