// The session the fusion service (and `ldv nav --lcm-log`) runs: the IMU latency is looked for over a sliding
// window unless the configuration rules it out, as `ldv nav` decides it over files (est::imu_latency_wanted):
// off with ldv.imu_latency: off, with a shift the user set (ldv.imu_time_shift_s), and with KF-GINS's behaviour;
// a wrong value is an error naming the file and line.
#include <gtest/gtest.h>

#include <string>

#include "common/io/input_error.hpp"
#include "estimator/run/run_navigation.hpp"
#include "services/fusion/fusion_engine.hpp"

using namespace ldv;

namespace {
bool window_on(const std::string& ldv_yaml) {
  KfGinsConfig cfg;
  cfg.config_path = "fusion_kfgins.yaml";
  if (!ldv_yaml.empty()) cfg.ldv = YAML::Load(ldv_yaml);
  return live_session_options(cfg, est::options_from_kfgins(cfg)).imu_latency_window.has_value();
}
}  // namespace

TEST(LiveSessionOptions, GivenADatasheetConfig_ThenTheLatencyIsLookedForLive) { EXPECT_TRUE(window_on("")); }

TEST(LiveSessionOptions, GivenTheConfigurationRulesItOut_ThenTheLatencyIsNotLookedFor) {
  EXPECT_FALSE(window_on("{imu_latency: 'off'}"));
  EXPECT_FALSE(window_on("{imu_time_shift_s: -0.2}"));
  EXPECT_FALSE(window_on("{kfgins_compatible: true}"));
  EXPECT_FALSE(window_on("{kfgins_compatible: true, imu_latency: auto}")) << "KF-GINS behaviour, exactly";
}

TEST(LiveSessionOptions, GivenAWrongImuLatencyValue_ThenTheErrorNamesTheFileAndTheValue) {
  try {
    window_on("{imu_latency: sometimes}");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("fusion_kfgins.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find("expected auto or off"), std::string::npos) << what;
  }
}
