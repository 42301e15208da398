#pragma once
// Replays a recorded LCM log (lcm-logger) through FusionEngine in the order and with the arrival
// times the log recorded: the offline twin of the live fusion service (same code, same result).
#include <functional>
#include <string>

#include "services/fusion/fusion_engine.hpp"

namespace ldv {

struct LogReplaySummary {
  long imu_messages = 0, gnss_messages = 0, wheel_messages = 0, malformed = 0, other_messages = 0;
  long corrupt_log_events = 0;  // events the log reader skipped (bad lengths or sync, a cut last event)
  std::string initialisation;
};

// Calls on_output for every navigation output. Throws InputError if the log cannot be read. IMU samples
// stamped from the host clock (status bit 0) are skipped unless host_clock_imu, as the live service does.
// WHEEL_SPEED messages are odometer readings when the engine's filter has the odometer aid.
LogReplaySummary replay_fusion_log(const std::string& log_path, FusionEngine& engine,
                                   const std::function<void(const FusionOutput&)>& on_output,
                                   const std::string& imu_channel = "IMU",
                                   const std::string& gnss_channel = "GNSS_SOLUTION", bool host_clock_imu = false);

}  // namespace ldv
