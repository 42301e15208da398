// Service configs are typed and range-checked: counter_hz 0 or NaN, a misspelt key, stop start-up with the
// file, line and key (instead of NaN on every sample or a silently kept default).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "common/config/config_section.hpp"
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
}
