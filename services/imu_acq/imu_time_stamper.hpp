#pragma once
// Turns device counters into GPS time (DESIGN.md section 4): PPS latches from the device (or the
// kernel PPS API) are paired with the receiver's labels (GNSS_PPS) by PpsLabelMatcher, fitted by
// PpsTimeFit, and every sample's counter goes through the fit. Before the fit locks (or while it
// re-acquires) stamps are extrapolated from the last good stamp, or from the host clock at the
// first sample, at the nominal counter rate, and flagged.
#include <cstdint>
#include <functional>
#include <optional>

#include "common/time/gps_time.hpp"
#include "services/imu_acq/timing/pps_label_matcher.hpp"
#include "services/imu_acq/timing/pps_time_fit.hpp"

namespace ldv::imu {

struct StamperOptions {
  timing::PpsTimeFitOptions fit;
  timing::PpsLabelMatcherOptions matcher;
  double gps_minus_utc_s = 18.0;  // host CLOCK_REALTIME is UTC; only for the unlocked fallback
};

struct Stamp {
  GpsTime time;
  std::int64_t counter = 0;  // the sample counter extended to 64 bits
  bool extrapolated = false; // no PPS fit behind this stamp
};

// One PPS edge after the fit has judged it (what imu_acq publishes on IMU_PPS).
struct JudgedEdge {
  std::int64_t counter = 0;                 // extended
  std::optional<std::int64_t> gps_second;   // total GPS second, when known
  double host_time_s = 0.0;                 // when the latch arrived
  timing::PpsEdgeResult result;
};

class ImuTimeStamper {
 public:
  using EdgeHandler = std::function<void(const JudgedEdge&)>;

  ImuTimeStamper(StamperOptions options, EdgeHandler on_edge);

  void on_pps_latch(std::uint64_t raw_counter, double host_time_s);
  void on_label(const gnss::PpsTimeLabel& label, double host_time_s);
  // Releases edges whose label never came (call every loop turn).
  void poll(double host_time_s);
  Stamp stamp(std::uint64_t raw_counter, double host_time_s);

  const timing::PpsTimeFit& fit() const { return fit_; }

 private:
  std::int64_t extend(std::uint64_t raw_counter);
  void on_matched_edge(std::uint64_t raw_counter, std::optional<std::int64_t> gps_second);

  StamperOptions options_;
  EdgeHandler on_edge_;
  timing::PpsTimeFit fit_;
  timing::PpsLabelMatcher matcher_;
  std::optional<std::int64_t> last_extended_;
  double latch_host_time_s_ = 0.0;
  // Fallback anchor: a counter and its GPS time (the last fitted stamp, or the host clock).
  std::optional<std::pair<std::int64_t, double>> anchor_;  // counter, total GPS seconds
};

}  // namespace ldv::imu
