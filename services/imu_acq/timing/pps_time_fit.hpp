#pragma once
// Counter -> GPS time for PPS time-stamping (DESIGN.md section 4). A free-running counter is
// latched at every IMU sample and at every PPS edge; the receiver labels which GPS second each
// edge is. A least-squares line through the last N accepted edges (offset and frequency) turns any
// sample's counter into GPS time. Host arrival times never enter: they jitter by milliseconds.
//
// Each edge is checked against the fit before it is used: an edge far from a whole second is a
// late (or spurious) pulse and is rejected; a label that disagrees with the whole second the
// counter says is a wrong label and is rejected (the edge is kept with the inferred second);
// consistent disagreement (the fit itself is wrong, e.g. acquired on a wrong label) re-acquires.
// Missing pulses are counted from the seconds skipped.
#include <cstdint>
#include <deque>
#include <optional>

#include "common/time/gps_time.hpp"

namespace ldv::timing {

struct PpsTimeFitOptions {
  double nominal_counter_hz = 10e6;
  int counter_bits = 32;                        // 64 for counters that never wrap (kernel ns stamps)
  double acquisition_frequency_tolerance_ppm = 200.0;  // oscillator vs nominal, before lock
  double locked_frequency_tolerance_ppm = 1.0;  // drift allowed across gaps once locked
  std::size_t window_edges = 16;                // least-squares window
  std::size_t edges_to_lock = 3;
  double edge_tolerance_s = 2e-6;               // |edge - whole second| accepted once locked
  int disagreements_to_reacquire = 3;           // consecutive wrong labels that mean the fit is wrong
};

enum class PpsEdgeVerdict {
  kAccepted,
  kAcceptedWrongLabel,  // edge used with the second the fit infers; the label was rejected
  kReacquired,          // the fit was restarted on this edge and its label
  kLate,                // latched after its whole second by more than the tolerance: not used
  kSpurious,            // before its whole second, a duplicate, or time going backwards: not used
  kUnlabelled,          // no label and nothing to infer it from yet: not used
};

struct PpsEdgeResult {
  PpsEdgeVerdict verdict = PpsEdgeVerdict::kUnlabelled;
  std::int64_t gps_second = 0;    // total GPS seconds of the edge (when known)
  std::int64_t missing_before = 0;  // pulses missed since the previous accepted edge
  double residual_s = 0.0;        // edge time per the fit minus its whole second
};

struct PpsFitCounters {
  std::uint64_t edges = 0;
  std::uint64_t accepted = 0;
  std::uint64_t missing = 0;  // seconds with no pulse at all (late pulses count as late only)
  std::uint64_t late = 0;
  std::uint64_t spurious = 0;
  std::uint64_t wrong_labels = 0;
  std::uint64_t unlabelled = 0;
  std::uint64_t reacquisitions = 0;
};

class PpsTimeFit {
 public:
  explicit PpsTimeFit(PpsTimeFitOptions options = {});

  // One PPS edge: the counter latched at the edge and, when the receiver said so, the edge's
  // total GPS second (week * 604800 + seconds of week).
  PpsEdgeResult add_pps_edge(std::uint64_t counter, std::optional<std::int64_t> gps_second_label);

  // GPS time of a counter reading (a sample latch). nullopt until locked.
  std::optional<GpsTime> stamp(std::uint64_t counter) const;

  bool locked() const { return locked_; }
  double counter_hz() const { return 1.0 / seconds_per_tick_; }
  double frequency_offset_ppm() const { return (counter_hz() / options_.nominal_counter_hz - 1.0) * 1e6; }
  // RMS of the window's edge residuals about the line [s]: the fit's own noise.
  double residual_rms_s() const { return residual_rms_s_; }
  const PpsFitCounters& counters() const { return counters_; }

 private:
  struct Edge {
    std::int64_t counter;  // extended
    std::int64_t second;   // total GPS seconds
  };
  void restart(const Edge& e);
  void accept(const Edge& e);
  void refit();
  // Seconds since the newest edge per the current fit, for an extended counter.
  double seconds_since_newest(std::int64_t counter) const;

  PpsTimeFitOptions options_;
  PpsFitCounters counters_;
  std::deque<Edge> window_;
  std::size_t accepted_since_restart_ = 0;
  bool locked_ = false;
  int disagreements_ = 0;
  std::int64_t late_since_accept_ = 0;
  // Fit: t - newest.second = offset_s_ + seconds_per_tick_ * (counter - newest.counter).
  double offset_s_ = 0.0;
  double seconds_per_tick_;
  double residual_rms_s_ = 0.0;
};

}  // namespace ldv::timing
