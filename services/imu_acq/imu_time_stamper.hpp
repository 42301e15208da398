#pragma once
// Turns device counters into GPS time (DESIGN.md section 4): PPS latches from the device (or the
// kernel PPS API) are paired with the receiver's labels (GNSS_PPS) by PpsLabelMatcher, fitted by
// PpsTimeFit, and every sample's counter goes through the fit. Before the fit locks (or while it
// re-acquires) stamps are extrapolated and flagged: in holdover from the last fitted stamp at the fitted
// rate, or from a fit saved before a restart (seed(), fit_state.hpp) when the device counter has kept
// running; otherwise from the host clock at the first sample, at the nominal counter rate.
#include <cstdint>
#include <functional>
#include <optional>

#include "common/time/gps_time.hpp"
#include "services/imu_acq/fit_state.hpp"
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
  bool extrapolated = false; // no live PPS fit behind this stamp
  bool holdover = false;     // extrapolated from a fit (the last one, or the saved one): still GPS time
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
  // A fit saved before a restart, used for the stamps until the live fit locks, if the first sample's
  // counter is where the saved rate says it should be now (within max_counter_jump_s: else the device
  // restarted its counter and the seed is dropped).
  void seed(const FitState& saved, double max_counter_jump_s = 0.5);
  // The current counter -> GPS point and rate, for saving (nothing until locked).
  std::optional<FitState> fit_state(double host_time_s) const;

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
  // Fallback anchor: a counter and its GPS time (the last fitted stamp, the saved fit, or the host clock).
  std::optional<std::pair<std::int64_t, double>> anchor_;  // counter, total GPS seconds
  double anchor_hz_ = 0.0;      // counter rate from the anchor on
  bool anchor_is_fit_ = false;  // the anchor comes from a fit (holdover), not from the host clock
  std::optional<FitState> seed_;
  double seed_max_jump_s_ = 0.5;
};

}  // namespace ldv::imu
