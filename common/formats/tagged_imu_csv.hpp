#pragma once
// IMU logs recorded as CSV text with an RTKLIB time-tag file beside them (the layout of
// ../shared/data/drives/walk_0827: `ax,ay,az,gx,gy,gz,t_counter_ms`). Each sample carries the
// device's own millisecond counter; the tag file gives the host reception time of every byte.
// GPS time of a sample = offset + rate * counter, fitted to the lower envelope of the reception
// times (a sample can arrive late, never early), so host jitter does not enter the time stamps; when that
// fitted rate is implausible for a counter (see TaggedImuCsvOptions), the counter's nominal rate is kept.
// Rates are turned into increments over (t_prev, t] with the trapezoidal rule.
#include <string>
#include <vector>

#include "common/formats/nav_types.hpp"
#include "common/geo/earth_model.hpp"

namespace ldv {

struct TaggedImuCsvOptions {
  double accel_to_mps2 = earth::kStandardGravity_mps2;  // the walk log is in g (standard gravity, as the device datasheets use)
  double gyro_to_rad_s = kDegToRad;
  double counter_to_s = 1e-3;      // the device counter ticks in ms
  // Counter seconds per GPS second. 0: fitted to the reception times, unless that fit is off nominal by more
  // than max_host_rate_error_ppm (no crystal drifts by 0.1 %: the host tags are distorted, e.g. buffered
  // delivery), in which case the nominal rate is kept and the offset comes from the first offset_window_s.
  double counter_rate = 0.0;
  double max_host_rate_error_ppm = 1000.0;
  double offset_window_s = 0.5;
};

struct TaggedImuCsvReport {
  long samples = 0;
  long skipped_lines = 0;       // partial or malformed lines (first/last lines of a log are often cut)
  long skipped_counter = 0;     // repeated or backward counter values
  double host_rate_error_ppm = 0.0;  // device counter rate fitted to the host reception times, minus 1
  double counter_rate = 1.0;         // the rate used
  std::string rate_source;
  double min_latency_s = 0.0;   // 0 with the lower-envelope fit; negative when the host tags are distorted
  double median_latency_s = 0.0;
  double p99_latency_s = 0.0;
};

std::vector<ImuIncrement> read_tagged_imu_csv(const std::string& csv_path, const std::string& tag_path,
                                              const TaggedImuCsvOptions& options = {},
                                              TaggedImuCsvReport* report = nullptr);

}  // namespace ldv
