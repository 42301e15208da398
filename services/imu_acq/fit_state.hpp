#pragma once
// imu_acq's PPS fit saved across restarts (a small YAML file in its StateDirectory, written every few
// seconds while locked). The device keeps counting while the service is down, so one point of the
// counter -> GPS line and the counter rate put the first samples after a restart on GPS time at once
// (a 0.1 ppm rate error costs 1 us over 10 s of downtime) instead of host-clock stamps until the fit
// re-locks on three new PPS edges (~3 s).
#include <cstdint>
#include <optional>
#include <string>

namespace ldv::imu {

struct FitState {
  double saved_host_time_s = 0.0;  // host CLOCK_REALTIME at the save (to predict the counter's wraps)
  std::int64_t counter = 0;        // an extended counter reading ...
  double gps_total_s = 0.0;        // ... and its GPS time (seconds since the GPS epoch)
  double counter_hz = 0.0;         // the fitted rate
  int counter_bits = 32;
};

void save_fit_state(const std::string& path, const FitState& s);  // atomic; failures are ignored
// Nothing when the file is missing, unreadable, inconsistent or older than max_age_s.
std::optional<FitState> load_fit_state(const std::string& path, double now_host_s, double max_age_s);

}  // namespace ldv::imu
