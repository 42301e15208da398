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
#include "common/io/dropped_records.hpp"

namespace ldv {

struct TaggedImuCsvOptions {
  double accel_to_mps2 = earth::kStandardGravity_mps2;  // the walk log is in g (standard gravity, as the device datasheets use)
  double gyro_to_rad_s = kDegToRad;
  double counter_to_s = 1e-3;      // the device counter ticks in ms
  // Counter seconds per GPS second. 0: fitted to the reception times, unless that fit is off nominal by more
  // than max_host_rate_error_ppm (no crystal drifts by 0.1 %: the tags do not fit this file), in which case the
  // nominal rate is kept and the offset comes from the first offset_window_s. The byte positions are matched in
  // the line-end convention the tag file counts (TaggedImuCsvReport::line_ends): read in the other one, walk_0827
  // showed a "host rate" of -2.05 % that was only its 20,456 missing CRs in 1,001,983 bytes.
  double counter_rate = 0.0;
  double max_host_rate_error_ppm = 1000.0;
  double offset_window_s = 0.5;
  // Width of the device counter in bits (16..64). 0: a wrap is detected at 16, 24 or 32 bits (the counter falls
  // back to a small value, and the step across the wrap is within max_counter_step_s). The counter is unwrapped.
  int counter_bits = 0;
  // A counter step beyond this is not a gap but a corrupted counter: the record is dropped (out of range).
  double max_counter_step_s = 86400.0;
  double max_dropped_fraction = 0.10;  // beyond it the file is refused (a wrong file or layout)
};

struct TaggedImuCsvReport {
  long samples = 0;
  DroppedRecords dropped;       // every dropped line, by reason (first and last lines of a log are often cut)
  long skipped_lines = 0;       // malformed, wrong column count or non-finite (a summary of `dropped`)
  long skipped_counter = 0;     // counter repeated, backwards, jumping or out of range (a summary of `dropped`)
  int counter_bits = 0;         // the counter width unwrapped (given or detected; 0: no wrap seen)
  long counter_wraps = 0;
  // The line-end convention the tag file's byte positions count: the CSV as stored (git normalises CRLF to LF)
  // may differ from the bytes the host received. E.g. "CRLF (as recorded; the stored file has LF)".
  std::string line_ends;
  long long crlf_added_bytes = 0;
  long gaps = 0;                       // intervals > 1.5 median intervals (kept)
  std::vector<ImuTimeGap> long_gaps;   // intervals > 10 median intervals (kept; line = the CSV line after it)
  double longest_gap_s = 0.0;  // carriage returns counted into positions that the stored file lacks
  double host_rate_error_ppm = 0.0;  // device counter rate fitted to the host reception times, minus 1
  double counter_rate = 1.0;         // the rate used
  std::string rate_source;
  double min_latency_s = 0.0;   // 0 with the lower-envelope fit; negative when the host tags are distorted
  double median_latency_s = 0.0;
  double p99_latency_s = 0.0;
  // The first tag of each distinct sample [s, the increments' time base] and how many rows repeated the sample
  // before them (a sensor read faster than it samples): the tags' jitter is measured from these
  // (estimator/calibrate/imu_stamp_jitter.hpp); the trapezoid's increments no longer show the repeats.
  std::vector<double> distinct_sample_tags_s;
  long repeated_rows = 0;
};

std::vector<ImuIncrement> read_tagged_imu_csv(const std::string& csv_path, const std::string& tag_path,
                                              const TaggedImuCsvOptions& options = {},
                                              TaggedImuCsvReport* report = nullptr);

}  // namespace ldv
