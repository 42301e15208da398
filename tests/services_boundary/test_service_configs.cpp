// Service configs are typed and range-checked: counter_hz 0 or NaN, a misspelt key, stop start-up with the
// file, line and key (instead of NaN on every sample or a silently kept default).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "common/config/config_section.hpp"
#include "common/formats/kfgins_config.hpp"
#include "estimator/run/run_navigation.hpp"
#include "services/gnss_link/gnss_link_options.hpp"
#include "services/imu_acq/imu_acq_options.hpp"

using namespace ldv;

namespace {
std::string write(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::path(::testing::TempDir()) / (name + std::to_string(::getpid()) + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(ServiceConfigs, GivenImuAcqCounterHzZeroOrNan_ThenStartUpFailsNamingLineAndRange) {
  for (const std::string v : {"0", ".nan", "-1e7"}) {
    const std::string path =
        write("imu_counter", "input: {type: file, file: {path: x.bin}}\ntsu:\n  counter_hz: " + v + "\n");
    EXPECT_EQ(error_of([&] { imu::load_imu_acq_options(path); }),
              path + ":3: tsu.counter_hz: expected a number in [1000, 1e+10], found " + v);
  }
}

TEST(ServiceConfigs, GivenAMisspeltKey_ThenTheErrorNamesItsLineAndTheNearestValidKey) {
  const std::string imu = write("imu_typo", "input: {type: file, file: {path: x.bin}}\nsample_rate_hzz: 200\n");
  EXPECT_EQ(error_of([&] { imu::load_imu_acq_options(imu); }),
            imu + ":2: unknown key 'sample_rate_hzz' (did you mean 'sample_rate_hz'?)");
  const std::string gnss = write("gnss_typo", "jump_gate:\n  max_jump_m: 30\n  max_gap: 5\n");
  EXPECT_EQ(error_of([&] { gnss::load_gnss_link_options(gnss); }),
            gnss + ":3: unknown key 'jump_gate.max_gap' (did you mean 'max_gap_s'?)");
}

TEST(ServiceConfigs, GivenTheDeployedConfigs_ThenEveryKeyIsKnown) {
  EXPECT_NO_THROW(imu::load_imu_acq_options(std::string(LDV_SOURCE_DIR) + "/deploy/config/imu_acq.yaml"));
  EXPECT_NO_THROW(gnss::load_gnss_link_options(std::string(LDV_SOURCE_DIR) + "/deploy/config/gnss_link.yaml"));
  // The vehicle's KF-GINS template fusion.yaml names (installed to /etc/ldvnav/kfgins.yaml): read as fusion reads it
  const KfGinsConfig vehicle = load_kfgins_config(std::string(LDV_SOURCE_DIR) + "/deploy/config/kfgins.yaml");
  const est::FilterOptions o = est::options_from_kfgins(vehicle);
  EXPECT_GT(o.arw_rad_per_sqrt_s.minCoeff(), 0.0);
  EXPECT_GT(o.vrw_mps_per_sqrt_s.minCoeff(), 0.0);
}

// Issue 35, item 20: a key given twice (an appended line) silently kept its first value.
TEST(ServiceConfigs, GivenAKeyTwice_ThenStartUpFailsNamingBothLines) {
  const std::string path =
      write("imu_dup", "input: {type: file, file: {path: x.bin}}\nsample_rate_hz: 200\nsample_rate_hz: 100\n");
  EXPECT_EQ(error_of([&] { imu::load_imu_acq_options(path); }),
            path + ":3: sample_rate_hz: given twice (first at line 2): which one is meant?");
}

// Issue 35, items 9, 10 and 31: channel names LCM cannot send, a group that is not a multicast address, a NUL in
// a text value: refused where they are read.
TEST(ServiceConfigs, GivenABadChannelGroupOrText_ThenTheKeyIsNamed) {
  config::ConfigSection s(YAML::Load("channel: " + std::string(64, 'C') + "\nspaced: \"A B\"\ngroup: 10.1.2.3\n"
                                     "url: \"239.255.77.1:9999?ttl=255&x=\"\nok: 239.255.77.1\n"),
                          "f.yaml");
  EXPECT_NE(error_of([&] { s.channel("channel", "X"); }).find("channel: expected an LCM channel name"), std::string::npos);
  EXPECT_NE(error_of([&] { s.channel("spaced", "X"); }).find("spaced: expected an LCM channel name"), std::string::npos);
  EXPECT_EQ(s.channel("absent", "TSPI"), "TSPI");
  EXPECT_NE(error_of([&] { s.ipv4_multicast_group("group", "x"); }).find("group: expected an IPv4 multicast address"),
            std::string::npos);
  EXPECT_NE(error_of([&] { s.ipv4_multicast_group("url", "x"); }).find("url: expected an IPv4 multicast address"),
            std::string::npos);
  EXPECT_EQ(s.ipv4_multicast_group("ok", "x"), "239.255.77.1");
  YAML::Node n;
  n["path"] = std::string("a\0b", 3);
  config::ConfigSection t(n, "g.yaml");
  EXPECT_NE(error_of([&] { t.text("path", ""); }).find("path: expected text without a NUL"), std::string::npos);
}
